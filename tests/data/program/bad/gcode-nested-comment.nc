; expect 3:12
%
G21 (outer (inner) text)
M30
%
