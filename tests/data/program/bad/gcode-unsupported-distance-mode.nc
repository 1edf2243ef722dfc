; expect 4:1
%
G21 G90
G91 G1 X1 F100
M30
%
