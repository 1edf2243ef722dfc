; expect 2:3
% program 1
G21 G90
M30
%
