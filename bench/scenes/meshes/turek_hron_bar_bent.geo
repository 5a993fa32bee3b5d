// Turek & Hron's bar (scenes/meshes/turek_hron_bar.geo) bent as a cantilever under a uniform load,
// y += D s^2 (6L^2 - 4Ls + s^2) / (3L^4) (s the distance from the cylinder, L the bar's length, D
// the tip's rise in m): the bent bar of turek_hron_channel_bar_cut.geo, to be immersed. NX x NY
// transfinite quadrilaterals; the top and bottom are splines through 41 points of the shape.
DefineConstant[ NX = {70}, NY = {4}, D = {0} ];
x0 = 0.2 + Sqrt(0.05^2 - 0.01^2); Lb = 0.6 - x0;
M = 40;
For k In {0:M}
  sk = Lb * k / M; wk = D * sk^2 * (6 * Lb^2 - 4 * Lb * sk + sk^2) / (3 * Lb^4);
  Point(100 + k) = {x0 + sk, 0.19 + wk, 0};
  Point(200 + k) = {x0 + sk, 0.21 + wk, 0};
EndFor
Point(5) = {0.2, 0.2, 0};
Spline(1) = {100:100+M};
Line(2) = {100 + M, 200 + M};
Spline(3) = {200+M:200:-1};
Circle(4) = {200, 5, 100};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = NX + 1; Transfinite Curve{2, 4} = NY + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("clamp") = {4};
Physical Surface("bar") = {1};
