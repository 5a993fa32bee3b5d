// A channel [0, 0.4] x [0, 0.1] m with a flap 0.01 m wide and 0.05 m tall standing on its bottom
// wall at x in [0.1, 0.11] cut out (bench/immersed_wall_flap.py). Unstructured quadrilaterals of
// size h (Frontal-Delaunay triangles recombined). Physical groups: inlet (x = 0), outlet (x = 0.4),
// walls (y = 0 on both sides of the flap, y = 0.1), the flap's upstream face in K segments
// up_1 .. up_K and its downstream face down_1 .. down_K (k = 1 at the wall), and its top flap_top;
// the cells are the surface "fluid".
DefineConstant[ h = {0.0025, Name "cell size"}, K = {10, Name "segments per face"} ];
Point(1) = {0, 0, 0, h}; Point(2) = {0.1, 0, 0, h}; Point(3) = {0.11, 0, 0, h}; Point(4) = {0.4, 0, 0, h};
Point(5) = {0.4, 0.1, 0, h}; Point(6) = {0, 0.1, 0, h};
Point(7) = {0.1, 0.05, 0, h}; Point(8) = {0.11, 0.05, 0, h};
For k In {1:K-1}
  Point(100 + k) = {0.1, 0.05 * k / K, 0, h};
  Point(200 + k) = {0.11, 0.05 * k / K, 0, h};
EndFor
Line(1) = {1, 2}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 6}; Line(5) = {6, 1};
For k In {1:K}
  Line(100 + k) = {(k == 1 ? 2 : 100 + k - 1), (k == K ? 7 : 100 + k)};
  Line(200 + k) = {(k == K ? 8 : 200 + k), (k == 1 ? 3 : 200 + k - 1)};
  Physical Curve(Sprintf("up_%g", k)) = {100 + k};
  Physical Curve(Sprintf("down_%g", k)) = {200 + k};
EndFor
Line(300) = {7, 8};
Curve Loop(1) = {1, 101:100+K, 300, 200+K:201:-1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Mesh.Algorithm = 6; Mesh.RecombinationAlgorithm = 2; Mesh.RecombineAll = 1;
Physical Curve("inlet") = {5};
Physical Curve("outlet") = {3};
Physical Curve("walls") = {1, 2, 4};
Physical Curve("flap_top") = {300};
Physical Surface("fluid") = {1};
