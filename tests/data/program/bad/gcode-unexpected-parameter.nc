; expect 3:5
%
G21 P2
M30
%
