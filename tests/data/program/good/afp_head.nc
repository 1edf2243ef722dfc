%
(STITCHSIM scene=cylinder_course head=afp mode=afp)
G21 G90
T3 M6
G0 X0 Y0 Z500 A0 B0 C0
G1 X0 Y0 Z0 F6000
G1 X1000 B10 C90
G0 Z500
M30
%
