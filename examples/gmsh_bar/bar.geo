// Dyka bar (examples/dyka_bar) on an unstructured triangle mesh: the bar 0 <= x <= 1 and an empty
// strip -0.1 <= x <= 0 in front of its free end, height 0.04 m (4 triangles' worth).
// Regenerate with:  gmsh -2 bar.geo -format msh41 -o bar.msh
// (the shipped bar.msh was written by make_mesh.py with the same entities and physical names).
h = 0.01;
H = 0.04;
Point(1) = {-0.1, 0, 0, h};
Point(2) = {0, 0, 0, h};
Point(3) = {1, 0, 0, h};
Point(4) = {1, H, 0, h};
Point(5) = {0, H, 0, h};
Point(6) = {-0.1, H, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {4, 5};
Physical Curve("fixed_end") = {3};
Physical Curve("free_end") = {7};
Physical Surface("air") = {1};
Physical Surface("bar") = {2};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.ElementOrder = 1;
