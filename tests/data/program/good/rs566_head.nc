%
(STITCHSIM scene=flat_panel head=rs566 stitch_length_mm=4.000000 mode=coupled)
G21 G90
T2 M6
G0 X0 Y0 Z0 A0 B0 C0 U0 V0
M10
G1 X4 U4 V4 F2400
G1 X8 C-10 U8 V8
M11
M30
%
