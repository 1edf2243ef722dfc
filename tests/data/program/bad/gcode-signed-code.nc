; expect 3:2
%
N-10 G21
M30
%
