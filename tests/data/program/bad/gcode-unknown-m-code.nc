; expect 4:5
%
G21 G90
M10 M99
M30
%
