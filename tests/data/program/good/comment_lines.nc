(leading comment before the start mark)
%
(a comment-only line)
; a semicolon comment-only line
G21 G90
(   padded comment text   )
T1 M6
G0 X0 Y0 Z0 A0 B0 C0 U0 V0
M10
G1 X5 U5 V5 F3000
(middle) G1 (comments between) X10 (words) U10 V10
M11
M30
%
