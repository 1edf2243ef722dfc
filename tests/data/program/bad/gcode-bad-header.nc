; expect 2:25
(STITCHSIM scene=circle head)
%
G21 G90
M30
%
