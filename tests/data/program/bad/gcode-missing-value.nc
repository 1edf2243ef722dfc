; expect 4:4
%
G21 G90
G1 X Y2 F100
M30
%
