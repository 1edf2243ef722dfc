; expect 4:4
%
G21 G90
G0 G1 X1
M30
%
