; expect 4:5
%
G21 G90
M10 M11
M30
%
