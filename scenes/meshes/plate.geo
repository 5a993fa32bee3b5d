// A rectangular plate of length L and thickness W centred at (cx, cy), turned by `angle` (rad)
// counter-clockwise, meshed by nx x ny quadrilaterals. Physical surface "plate".
DefineConstant[ L = {0.004, Name "length"}, W = {0.001, Name "thickness"}, cx = {0.02, Name "centre x"},
                cy = {0.1, Name "centre y"}, angle = {0.3, Name "angle"}, nx = {16, Name "cells along"},
                ny = {4, Name "cells across"} ];
c = Cos(angle); s = Sin(angle);
Point(1) = {cx + (-L/2) * c - (-W/2) * s, cy + (-L/2) * s + (-W/2) * c, 0};
Point(2) = {cx + ( L/2) * c - (-W/2) * s, cy + ( L/2) * s + (-W/2) * c, 0};
Point(3) = {cx + ( L/2) * c - ( W/2) * s, cy + ( L/2) * s + ( W/2) * c, 0};
Point(4) = {cx + (-L/2) * c - ( W/2) * s, cy + (-L/2) * s + ( W/2) * c, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1; Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1};
