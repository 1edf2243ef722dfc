; expect 2:1
%
G21 G90
M30
