// Turek & Hron's (2006) FSI channel [0, 2.5] x [0, 0.41] with the cylinder of radius 0.05 centred
// at (0.2, 0.2) cut out, refined where the immersed elastic bar lies (x in [0.25, 0.6], y in
// [0.19, 0.21] at rest; scenes/meshes/turek_hron_bar.geo). An immersed surface is felt by the flow
// only to within a fluid cell, so the bar's zone needs cells much smaller than the rest of the
// channel needs; a block-structured mesh (turek_hron_channel.geo) cannot refine one zone alone.
// Unstructured quadrilaterals (Frontal-Delaunay triangles recombined into quads and subdivided),
// sized by
//   - hb = h / B in the box x in [0.24, 0.61], y in [0.2 - W, 0.2 + W] around the bar (W = 0.02
//     for a bar at rest; FSI2's bar swings through y = 0.2 +- 0.1), growing to h over 0.02 m
//     outside it;
//   - h / 2 on the cylinder, growing by 0.3 per metre of distance from it;
//   - h = 0.05 / N up to x = 0.8, then growing linearly to 7.8 h at the outlet.
// Physical groups: inlet (x = 0), outlet (x = 2.5), walls (y = 0 and y = 0.41), cylinder; the
// cells are the surface "fluid". N = 8, B = 2 has 15,137 cells, 2.7 mm wide in the bar's zone
// ("parameters": {"N": 8, "B": 2}).
DefineConstant[ N = {8, Name "refinement level"}, B = {2, Name "refinement of the bar's zone"},
                W = {0.02, Name "half height of the bar's zone"} ];

h = 0.05 / N;
hb = h / B;
cx = 0.2; cy = 0.2; r = 0.05;
Point(1) = {0, 0, 0}; Point(2) = {2.5, 0, 0}; Point(3) = {2.5, 0.41, 0}; Point(4) = {0, 0.41, 0};
Point(5) = {cx, cy, 0};
Point(6) = {cx + r, cy, 0}; Point(7) = {cx, cy + r, 0}; Point(8) = {cx - r, cy, 0}; Point(9) = {cx, cy - r, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};

Field[1] = Box;  // the bar's zone
Field[1].XMin = 0.24; Field[1].XMax = 0.61; Field[1].YMin = 0.2 - W; Field[1].YMax = 0.2 + W;
Field[1].VIn = hb; Field[1].VOut = 1; Field[1].Thickness = 0.02;
Field[2] = Distance;  // from the cylinder
Field[2].CurvesList = {5, 6, 7, 8}; Field[2].NumPointsPerCurve = 200;
Field[3] = MathEval; Field[3].F = Sprintf("%g + 0.3 * F2", h / 2);
Field[4] = MathEval; Field[4].F = Sprintf("%g * (1 + 4 * max(0, x - 0.8))", h);  // the wake
Field[5] = Min; Field[5].FieldsList = {1, 3, 4};
Background Field = 5;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
// Frontal-Delaunay (6); gmsh 4.8's Frontal-Delaunay for quads (8) fails with a background field.
Mesh.Algorithm = 6; Mesh.RecombinationAlgorithm = 2; Mesh.RecombineAll = 1;

Physical Curve("inlet") = {4};
Physical Curve("outlet") = {2};
Physical Curve("walls") = {1, 3};
Physical Curve("cylinder") = {5, 6, 7, 8};
Physical Surface("fluid") = {1};
