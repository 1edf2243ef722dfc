; expect 3:9
%
G21 G90 (metric
M30
%
