// A quarter sphere cap (radius 10, cut at height 4) on a block (10 × 10 × 3), both 10-node
// tetrahedra: the quadratic mortar case of BENCHMARKS.md ("Quadratic tetrahedra, mortar
// multipliers: one rank against two"). Mesh and convert:
//   gmsh -3 -format msh41 -setnumber hf 0.15 -setnumber hc 1.0 sphere_on_block_tet10.geo -o two.msh
//   hertz import two.msh -o two_mesh.in     (then run tools/sphere_on_block_tet10.in beside it)
SetFactory("OpenCASCADE");
Mesh.ElementOrder = 2;
R = 10; H = 4; D = 3;
Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, H};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {0, 0, -D, R, R, D};
Point(100) = {0, 0, 0, hf};
Field[1] = Distance; Field[1].PointsList = {100};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hf; Field[2].SizeMax = hc;
Field[2].DistMin = 1.6; Field[2].DistMax = 4;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
eps = 1e-6;
Physical Volume("cap", 1) = {3};
Physical Volume("block", 2) = {4};
top() = Surface In BoundingBox{-eps, -eps, H - eps, R + eps, R + eps, H + eps};
bottom() = Surface In BoundingBox{-eps, -eps, -D - eps, R + eps, R + eps, -D + eps};
x0() = Surface In BoundingBox{-eps, -eps, -D-eps, eps, R + eps, H + eps};
y0() = Surface In BoundingBox{-eps, -eps, -D-eps, R + eps, eps, H + eps};
btop() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, R + eps, eps};
sphere() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, R + eps, H + eps};
sphere() -= top(); sphere() -= x0(); sphere() -= y0();
sphere() -= btop();
Physical Surface("top", 3) = {top()};
Physical Surface("bottom", 4) = {bottom()};
Physical Surface("x0", 5) = {x0()};
Physical Surface("y0", 6) = {y0()};
Physical Surface("blocktop", 7) = {btop()};
Physical Surface("sphere", 8) = {sphere()};
