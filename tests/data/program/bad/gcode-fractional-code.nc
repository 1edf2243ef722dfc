; expect 4:6
%
G21 G90
T1 M6.5
M30
%
