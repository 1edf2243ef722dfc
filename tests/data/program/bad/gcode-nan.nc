; expect 4:5
%
G21 G90
G1 Xnan F100
M30
%
