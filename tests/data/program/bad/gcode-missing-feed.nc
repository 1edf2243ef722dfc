; expect 4:4
%
G21 G90
G1 X1 Y2
M30
%
