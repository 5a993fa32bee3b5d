// Turek & Hron's (2006) channel [0, 2.5] x [0, 0.41] with the cylinder (radius 0.05 at (0.2, 0.2))
// and the bar behind it (0.35 x 0.02 m, x from the cylinder to 0.6, y in [0.19, 0.21]) both cut
// out: a body-fitted mesh of the rigid obstacle of CFD1, the reference for the immersed bar. The
// bar may be bent as a cantilever under a uniform load, y += D s^2 (6L^2 - 4Ls + s^2) / (3L^4)
// (s the distance from the cylinder, L the bar's length, D the tip's rise in m), the shape of FSI1's
// bar to within a few per cent. Its top and bottom are split into K equal segments, tagged
// "top_k" and "bottom_k" (k = 1..K from the cylinder), its free end "end", so that boundary_force
// probes give the load's distribution along the bar. Cells: unstructured quadrilaterals of
// h = 0.05/N, h/B in the bar's zone, h/2 on the cylinder, growing towards the outlet (as
// scenes/meshes/turek_hron_channel_refined.geo). Physical groups as there, plus the bar's.
DefineConstant[ N = {8}, B = {2}, K = {14}, D = {0} ];
h = 0.05 / N; hb = h / B;
cx = 0.2; cy = 0.2; r = 0.05;
x0 = cx + Sqrt(r^2 - 0.01^2);
Lb = 0.6 - x0;
Point(1) = {0, 0, 0}; Point(2) = {2.5, 0, 0}; Point(3) = {2.5, 0.41, 0}; Point(4) = {0, 0.41, 0};
Point(5) = {cx, cy, 0};
Point(6) = {x0, 0.21, 0}; Point(7) = {cx - r, cy, 0}; Point(8) = {x0, 0.19, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8};
// bottom: x0 -> 0.6 in K segments; end; top: 0.6 -> x0
For k In {1:K-1}
  sk = Lb * k / K; wk = D * sk^2 * (6 * Lb^2 - 4 * Lb * sk + sk^2) / (3 * Lb^4);
  Point(100 + k) = {x0 + sk, 0.19 + wk, 0};
  Point(200 + k) = {x0 + sk, 0.21 + wk, 0};
EndFor
Point(100 + K) = {0.6, 0.19 + D, 0}; Point(200 + K) = {0.6, 0.21 + D, 0};

For k In {1:K}
  Line(100 + k) = {(k == 1 ? 8 : 100 + k - 1), 100 + k};
  Line(200 + k) = {200 + k, (k == 1 ? 6 : 200 + k - 1)};
  Physical Curve(Sprintf("bottom_%g", k)) = {100 + k};
  Physical Curve(Sprintf("top_%g", k)) = {200 + k};
EndFor
Line(300) = {100 + K, 200 + K};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 101:100+K, 300, 200+K:201:-1};
Plane Surface(1) = {1, 2};
Field[1] = Box; Field[1].XMin = 0.24; Field[1].XMax = 0.61; Field[1].YMin = 0.18; Field[1].YMax = 0.22 + D;
Field[1].VIn = hb; Field[1].VOut = 1; Field[1].Thickness = 0.02;
Field[2] = Distance; Field[2].CurvesList = {5, 6}; Field[2].NumPointsPerCurve = 200;
Field[3] = MathEval; Field[3].F = Sprintf("%g + 0.3 * F2", h / 2);
Field[4] = MathEval; Field[4].F = Sprintf("%g * (1 + 4 * max(0, x - 0.8))", h);
Field[5] = Min; Field[5].FieldsList = {1, 3, 4};
Background Field = 5;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6; Mesh.RecombinationAlgorithm = 2; Mesh.RecombineAll = 1;
Physical Curve("inlet") = {4};
Physical Curve("outlet") = {2};
Physical Curve("walls") = {1, 3};
Physical Curve("cylinder") = {5, 6};
Physical Curve("end") = {300};
Physical Surface("fluid") = {1};
