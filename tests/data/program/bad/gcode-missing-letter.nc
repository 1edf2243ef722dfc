; expect 4:7
%
G21 G90
G1 X1 5
M30
%
