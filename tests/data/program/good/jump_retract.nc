%
(STITCHSIM scene=stringer_panel head=rs535 stitch_length_mm=5.000000 mode=decoupled)
G21 G90
T1 M6
G0 X0 Y0 Z0 A0 B0 C0 U0 V0
M10
G1 X5 U5 V5 F3000
M11
M20 (retract to jump the stringer)
G0 Z80
G0 X45
G0 Z0
M21 (lower)
M10
G1 X50 U10 V10 F3000
M11 M30
%
