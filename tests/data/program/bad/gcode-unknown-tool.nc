; expect 4:1
%
G21 G90
T9 M6
M30
%
