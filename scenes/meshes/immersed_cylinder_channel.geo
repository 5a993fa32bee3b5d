// Schaefer & Turek's (1996) channel [0, 2.2] x [0, 0.41] without the cylinder, for a cylinder
// immersed in it (scenes/cylinder_re20_immersed.json): square cells of size h = 0.1 / N (N cells
// per cylinder diameter) over x in [0, 0.6], which holds the cylinder (centred at x = 0.2) and its
// near wake, then cells growing geometrically to the outlet (3N columns, the first about as wide as h).
// Quadrilaterals, counter-clockwise. Physical groups: inlet (x = 0), outlet (x = 2.2), walls
// (y = 0 and y = 0.41); the cells are the surface "fluid". Override N with "parameters": {"N": 32}.
DefineConstant[ N = {16, Name "cells per cylinder diameter"} ];

h = 0.1 / N;
ny = Ceil(0.41 / h);  // cells across the channel
nx = Round(0.6 / h);  // uniform columns
nd = 3 * N;           // growing columns over the remaining 1.6 m
// Their ratio q solves h (q^nd - 1) / (q - 1) = 1.6: Newton's method on
// g(q) = h (q^nd - 1) - 1.6 (q - 1) from above its root (g is convex, so it descends monotonically).
q = 1.5;
For k In {1:400}
  q = q - (h * (q^nd - 1) - 1.6 * (q - 1)) / (h * nd * q^(nd - 1) - 1.6);
EndFor

Point(1) = {0, 0, 0}; Point(2) = {0.6, 0, 0}; Point(3) = {2.2, 0, 0};
Point(4) = {2.2, 0.41, 0}; Point(5) = {0.6, 0.41, 0}; Point(6) = {0, 0.41, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {5, 4};
Line(5) = {6, 5}; Line(6) = {1, 6}; Line(7) = {2, 5};

Curve Loop(1) = {1, 7, -5, -6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, -4, -7}; Plane Surface(2) = {2};

Transfinite Curve{1, 5} = nx + 1;
Transfinite Curve{2, 4} = nd + 1 Using Progression q;
Transfinite Curve{3, 6, 7} = ny + 1;
Transfinite Surface{1:2};
Recombine Surface{1:2};

Physical Curve("inlet") = {6};
Physical Curve("outlet") = {3};
Physical Curve("walls") = {1, 2, 4, 5};
Physical Surface("fluid") = {1, 2};
