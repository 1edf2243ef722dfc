; expect 3:5
%
G21 M6
M30
%
