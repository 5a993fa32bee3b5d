// Turek & Hron's (2006) elastic bar: 0.35 x 0.02 m behind the cylinder of radius 0.05 centred at
// (0.2, 0.2), its lower right corner at (0.6, 0.19), point A = (0.6, 0.2) the middle of its free
// end. Its left end is the arc where it meets the cylinder (the physical curve "clamp"); NX x NY
// transfinite quadrilaterals ("parameters": {"NX": 70, "NY": 4}). The surface is "bar".
DefineConstant[ NX = {70, Name "cells along the bar"}, NY = {4, Name "cells across the bar"} ];

x0 = 0.2 + Sqrt(0.05^2 - 0.01^2);  // where y = 0.19 and y = 0.21 meet the cylinder
Point(1) = {x0, 0.19, 0}; Point(2) = {0.6, 0.19, 0}; Point(3) = {0.6, 0.21, 0}; Point(4) = {x0, 0.21, 0};
Point(5) = {0.2, 0.2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Circle(4) = {4, 5, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = NX + 1; Transfinite Curve{2, 4} = NY + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("clamp") = {4};
Physical Surface("bar") = {1};
