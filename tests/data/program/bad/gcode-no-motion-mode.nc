; expect 4:1
%
G21 G90
X1 Y2
M30
%
