; expect 4:1
%
G21 G90
M30
