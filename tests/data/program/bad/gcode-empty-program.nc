; expect 2:1
%
(nothing here)
