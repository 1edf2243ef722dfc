%
g21 g90
t2 m6
g0 x0 y0 z10 a0 b0 c90 u0 v0
m10
g1 x5 u5 v5 f1200
g1 x10 u10 v10
m11
m30
%
