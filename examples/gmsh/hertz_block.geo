// Half model (x >= 0) of an elastic block 12 wide and 12 deep under a rigid cylinder of
// radius 10 touching its top at the origin: examples/gmsh/hertz_gmsh.in.
// Mesh:  gmsh -2 -format msh41 hertz_block.geo -o hertz_block.msh
// 6-node triangles (hertz_gmsh_tri6.in), twice the size for the same node spacing:
//        gmsh -2 -format msh41 -setnumber order 2 hertz_block.geo -o hertz_block_tri6.msh
If (!Exists(order))
  order = 1;
EndIf
Mesh.ElementOrder = order;
h_fine = 0.04 * order;    // element size at the contact (the contact half-width is about 0.75)
h_coarse = 1.0;   // element size far from it

Point(1) = {0, -12, 0, h_coarse};
Point(2) = {12, -12, 0, h_coarse};
Point(3) = {12, 0, 0, h_coarse};
Point(4) = {3, 0, 0, h_coarse};
Point(5) = {0, 0, 0, h_fine};
Line(1) = {1, 2};  // bottom
Line(2) = {2, 3};  // right
Line(3) = {3, 4};  // top, free
Line(4) = {4, 5};  // top, contact candidates (0 <= x <= 3)
Line(5) = {5, 1};  // symmetry plane x = 0
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

// Fine near the first contact point, growing away from it.
Field[1] = Distance;
Field[1].PointsList = {5};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_fine;
Field[2].SizeMax = h_coarse;
Field[2].DistMin = 1.2;
Field[2].DistMax = 8;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.Algorithm = 6;   // Frontal-Delaunay

// Physical groups become hertz sets 1..4 (the surface first, then curves by tag).
Physical Surface("block", 1) = {1};
Physical Curve("symmetry", 2) = {5};
Physical Curve("bottom", 3) = {1};
Physical Curve("contact", 4) = {4};
