// Two elastic hemispheres of radius 1 touching at the origin, both meshed in linear tetrahedra:
// the upper one (centre (0, 0, 1)) below its centre, the lower one (centre (0, 0, -1)) above.
// A benchmark of contact between two tetrahedral Gmsh bodies (BENCHMARKS.md, "Two hemispheres
// meshed in Gmsh"):
//        gmsh -3 -format msh41 -setnumber hf 0.012 -setnumber hc 0.09 hemispheres.geo -o h.msh
// (25 212 nodes; hf: element size at the contact, hc: far from it).
SetFactory("OpenCASCADE");
If (!Exists(hf))
  hf = 0.02;
EndIf
If (!Exists(hc))
  hc = 0.15;
EndIf
Sphere(1) = {0, 0, 1, 1};
Box(2) = {-1, -1, 0, 2, 2, 1};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Sphere(4) = {0, 0, -1, 1};
Box(5) = {-1, -1, -1, 2, 2, 1};
BooleanIntersection(6) = { Volume{4}; Delete; }{ Volume{5}; Delete; };

// Fine near the first contact point, growing away from it.
Point(100) = {0, 0, 0, hf};
Field[1] = Distance;
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hf;
Field[2].SizeMax = hc;
Field[2].DistMin = 0.15;
Field[2].DistMax = 0.8;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

// Sets 1-6 in hertz (`hertz import` prints them).
Physical Volume("lower", 1) = {6};
Physical Volume("upper", 2) = {3};
Physical Surface("lower_bottom", 3) = {4};
Physical Surface("upper_top", 4) = {2};
Physical Surface("lower_dome", 5) = {3};
Physical Surface("upper_dome", 6) = {1};
