// Turek & Hron's (2006) FSI channel [0, 2.5] x [0, 0.41] with the cylinder of radius 0.05 centred
// at (0.2, 0.2) cut out; the elastic bar behind it (x in [0.25, 0.6], y in [0.19, 0.21] at rest)
// is not cut out: it is an immersed solid (scenes/meshes/turek_hron_bar.geo). Block-structured
// quadrilaterals: an O-grid of four blocks between the cylinder and the square [0.1, 0.3]^2, a
// uniform near wake x in [0.3, 0.8] where the bar swings (square cells of side h = 0.05 / N, as on
// the square's sides), and a far wake to the outlet whose columns grow geometrically from h.
// Every surface is counter-clockwise. Physical groups: inlet (x = 0), outlet (x = 2.5), walls
// (y = 0 and y = 0.41), cylinder; the cells are the surface "fluid". N = 1 has 240 cells and
// each doubling of N quadruples that (gmsh -setnumber N 4, or "parameters": {"N": 4}).
DefineConstant[ N = {4, Name "refinement level"} ];

h = 0.05 / N;
nq = 4 * N;   // cells along a quarter of the cylinder, a side of the square and across y in [0.1, 0.3]
nr = 4 * N;   // radial cells, cylinder to square, clustered at the cylinder
nl = 2 * N;   // cells across the inlet strip x in [0, 0.1]
nv = 2 * N;   // cells across the strips below (y in [0, 0.1]) and above (y in [0.3, 0.41])
nw = 10 * N;  // uniform columns of the near wake, x in [0.3, 0.8]
nd = 8 * N;   // growing columns of the far wake, x in [0.8, 2.5]
// Their ratio q solves h (q^nd - 1) / (q - 1) = 1.7: Newton's method on the convex
// g(q) = h (q^nd - 1) - 1.7 (q - 1), started above its root so that it descends monotonically.
q = 1.5;
For k In {1:400}
  q = q - (h * (q^nd - 1) - 1.7 * (q - 1)) / (h * nd * q^(nd - 1) - 1.7);
EndFor

cx = 0.2; cy = 0.2; r = 0.05; a = r / Sqrt(2);
Point(1) = {cx, cy, 0};                       // centre
Point(2) = {cx - a, cy - a, 0}; Point(3) = {cx + a, cy - a, 0};
Point(4) = {cx + a, cy + a, 0}; Point(5) = {cx - a, cy + a, 0};
Point(6) = {0.1, 0.1, 0}; Point(7) = {0.3, 0.1, 0}; Point(8) = {0.3, 0.3, 0}; Point(9) = {0.1, 0.3, 0};
Point(10) = {0, 0, 0}; Point(11) = {0.1, 0, 0}; Point(12) = {0.3, 0, 0};
Point(14) = {0, 0.1, 0}; Point(16) = {0, 0.3, 0};
Point(18) = {0, 0.41, 0}; Point(19) = {0.1, 0.41, 0}; Point(20) = {0.3, 0.41, 0};
// Near-wake / far-wake boundary x = 0.8 and the outlet x = 2.5.
Point(22) = {0.8, 0, 0}; Point(23) = {0.8, 0.1, 0}; Point(24) = {0.8, 0.3, 0}; Point(25) = {0.8, 0.41, 0};
Point(26) = {2.5, 0, 0}; Point(27) = {2.5, 0.1, 0}; Point(28) = {2.5, 0.3, 0}; Point(29) = {2.5, 0.41, 0};

// The cylinder (counter-clockwise) and the square around it.
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Line(5) = {6, 7}; Line(6) = {7, 8}; Line(7) = {8, 9}; Line(8) = {9, 6};
// Radial lines, from the cylinder outward.
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};
// Inlet column x in [0, 0.1].
Line(13) = {10, 11}; Line(14) = {14, 6}; Line(15) = {16, 9}; Line(16) = {18, 19};
Line(17) = {10, 14}; Line(18) = {14, 16}; Line(19) = {16, 18};
Line(20) = {11, 6}; Line(21) = {9, 19};
// Middle column x in [0.1, 0.3] below and above the square.
Line(22) = {11, 12}; Line(23) = {19, 20}; Line(24) = {12, 7}; Line(25) = {8, 20};
// Near wake x in [0.3, 0.8]: horizontal lines and the column's right side.
Line(26) = {12, 22}; Line(27) = {7, 23}; Line(28) = {8, 24}; Line(29) = {20, 25};
Line(30) = {22, 23}; Line(31) = {23, 24}; Line(32) = {24, 25};
// Far wake x in [0.8, 2.5].
Line(33) = {22, 26}; Line(34) = {23, 27}; Line(35) = {24, 28}; Line(36) = {25, 29};
Line(37) = {26, 27}; Line(38) = {27, 28}; Line(39) = {28, 29};

Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8, 18, 22, 23, 31, 38} = nq + 1;
Transfinite Curve{9, 10, 11, 12} = nr + 1 Using Progression 1.1^(4 / N);
Transfinite Curve{13, 14, 15, 16} = nl + 1;
Transfinite Curve{17, 20, 24, 30, 37, 19, 21, 25, 32, 39} = nv + 1;
Transfinite Curve{26, 27, 28, 29} = nw + 1;
Transfinite Curve{33, 34, 35, 36} = nd + 1 Using Progression q;

// O-grid blocks: below, right, above and left of the cylinder.
Curve Loop(1) = {9, 5, -10, -1};  Plane Surface(1) = {1};
Curve Loop(2) = {10, 6, -11, -2}; Plane Surface(2) = {2};
Curve Loop(3) = {11, 7, -12, -3}; Plane Surface(3) = {3};
Curve Loop(4) = {12, 8, -9, -4};  Plane Surface(4) = {4};
// Inlet column: bottom, middle, top.
Curve Loop(5) = {13, 20, -14, -17}; Plane Surface(5) = {5};
Curve Loop(6) = {14, -8, -15, -18}; Plane Surface(6) = {6};
Curve Loop(7) = {15, 21, -16, -19}; Plane Surface(7) = {7};
// Middle column: below and above the square.
Curve Loop(8) = {22, 24, -5, -20}; Plane Surface(8) = {8};
Curve Loop(9) = {-7, 25, -23, -21}; Plane Surface(9) = {9};
// Near wake: bottom, middle, top.
Curve Loop(10) = {26, 30, -27, -24}; Plane Surface(10) = {10};
Curve Loop(11) = {27, 31, -28, -6};  Plane Surface(11) = {11};
Curve Loop(12) = {28, 32, -29, -25}; Plane Surface(12) = {12};
// Far wake: bottom, middle, top.
Curve Loop(13) = {33, 37, -34, -30}; Plane Surface(13) = {13};
Curve Loop(14) = {34, 38, -35, -31}; Plane Surface(14) = {14};
Curve Loop(15) = {35, 39, -36, -32}; Plane Surface(15) = {15};

Transfinite Surface{1:15};
Recombine Surface{1:15};

Physical Curve("inlet") = {17, 18, 19};
Physical Curve("outlet") = {37, 38, 39};
Physical Curve("walls") = {13, 22, 26, 33, 16, 23, 29, 36};
Physical Curve("cylinder") = {1, 2, 3, 4};
Physical Surface("fluid") = {1:15};
