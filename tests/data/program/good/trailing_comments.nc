%
G21 G90 (metric, absolute)
T1 M6 (mount the RS535)
G0 X0 Y0 Z0 A0 B0 C0 U0 V0 (start pose)
M10 ; stitching on
G1 X5 U5 V5 F3000 (stitch 1) ; translation line
G1 C-3 ; rotation line
M11 (off)
M30 ; end
%
