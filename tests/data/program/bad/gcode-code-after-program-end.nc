; expect 5:1
%
G21 G90
M30
G0 X1
%
