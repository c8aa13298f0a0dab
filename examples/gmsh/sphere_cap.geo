// Quarter model (x >= 0, y >= 0) of an elastic sphere of radius 10 whose lowest point touches a
// rigid plane z = 0 at the origin, cut at height 4: examples/gmsh/sphere_tet10.in.
// Mesh (10-node tetrahedra):
//        gmsh -3 -format msh41 -setnumber order 2 sphere_cap.geo -o sphere_cap_tet10.msh
SetFactory("OpenCASCADE");
If (!Exists(order))
  order = 2;
EndIf
Mesh.ElementOrder = order;
R = 10;
H = 4;
h_fine = 0.12 * order;   // element size at the contact (the contact radius is about 1.2)
h_coarse = 1.5;          // element size far from it

Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, H};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };

// Fine near the first contact point, growing away from it.
Point(100) = {0, 0, 0, h_fine};
Field[1] = Distance;
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_fine;
Field[2].SizeMax = h_coarse;
Field[2].DistMin = 1.6;
Field[2].DistMax = 4;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

// Physical groups become hertz sets 1..5 (the volume first, then surfaces by tag).
eps = 1e-6;
Physical Volume("cap", 1) = {3};
top() = Surface In BoundingBox{-eps, -eps, H - eps, R + eps, R + eps, H + eps};
x0() = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, H + eps};
y0() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, H + eps};
sphere() = Surface{:};
sphere() -= {top(), x0(), y0()};
Physical Surface("top", 2) = {top()};
Physical Surface("x0", 3) = {x0()};
Physical Surface("y0", 4) = {y0()};
Physical Surface("sphere", 5) = {sphere()};
