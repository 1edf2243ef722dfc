; expect 3:19
%
G21 G90 (rotate 90°)
M30
%
