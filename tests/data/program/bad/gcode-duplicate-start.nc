; expect 3:1
%
%
G21
M30
%
