; expect 3:9
%
G21 G90 )
M30
%
