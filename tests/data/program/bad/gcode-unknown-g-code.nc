; expect 3:5
%
G21 G17
M30
%
