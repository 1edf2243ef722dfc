; expect 4:1
%
G21 G90
G2 X1 Y1
M30
%
