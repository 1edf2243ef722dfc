; expect 3:5
%
G20 G21
M30
%
