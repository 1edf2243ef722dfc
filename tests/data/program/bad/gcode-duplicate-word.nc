; expect 4:7
%
G21 G90
G1 X1 X2 F100
M30
%
