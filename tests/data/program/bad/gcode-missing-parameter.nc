; expect 3:5
%
G21 M60
M30
%
