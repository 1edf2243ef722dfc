; expect 4:8
%
G21 G90
G1 X1.2.3 F100
M30
%
