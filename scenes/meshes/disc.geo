// A disc of radius R centred at (cx, cy): an O-grid of quadrilaterals, a square core of half-width
// R/2 with n x n cells and four blocks of n x layers cells blending its edges into the circle.
// Defaults: the sedimenting disc of Glowinski et al. (2001), diameter 2.5 mm at (0.01, 0.04) m.
// Override with "parameters": {"R": ..., "cx": ..., "cy": ..., "n": ..., "layers": ...} in a moreau
// scene. Every surface is counter-clockwise. Physical groups: the surface "disc", the curve "rim".
DefineConstant[ R = {0.00125, Name "radius"}, cx = {0.01, Name "centre x"}, cy = {0.04, Name "centre y"},
                n = {8, Name "cells along a side of the core"}, layers = {4, Name "cells from the core to the rim"} ];

a = R / 2; c = R / Sqrt(2);
Point(1) = {cx, cy, 0};
Point(2) = {cx - a, cy - a, 0}; Point(3) = {cx + a, cy - a, 0};
Point(4) = {cx + a, cy + a, 0}; Point(5) = {cx - a, cy + a, 0};
Point(6) = {cx - c, cy - c, 0}; Point(7) = {cx + c, cy - c, 0};
Point(8) = {cx + c, cy + c, 0}; Point(9) = {cx - c, cy + c, 0};

Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 2};            // the core
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};  // the rim
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};         // core to rim

Curve Loop(1) = {1, 2, 3, 4};       Plane Surface(1) = {1};
Curve Loop(2) = {9, 5, -10, -1};    Plane Surface(2) = {2};
Curve Loop(3) = {10, 6, -11, -2};   Plane Surface(3) = {3};
Curve Loop(4) = {11, 7, -12, -3};   Plane Surface(4) = {4};
Curve Loop(5) = {12, 8, -9, -4};    Plane Surface(5) = {5};

Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8} = n + 1;
Transfinite Curve{9, 10, 11, 12} = layers + 1;
Transfinite Surface{1:5};
Recombine Surface{1:5};

Physical Curve("rim") = {5, 6, 7, 8};
Physical Surface("disc") = {1:5};
