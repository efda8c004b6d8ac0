// Meridian plane of an axisymmetric silo (x = r, y = z): radius 1 m, fill 3 m, headspace to 3.5 m.
// gmsh -2 silo.geo -format msh41 -o silo.msh   (the shipped silo.msh was written by make_mesh.py)
h = 0.05;
Point(1) = {0, 0, 0, h};   Point(2) = {1, 0, 0, h};   Point(3) = {1, 3, 0, h};
Point(4) = {0, 3, 0, h};   Point(5) = {1, 3.5, 0, h}; Point(6) = {0, 3.5, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {3, 5}; Line(6) = {5, 6}; Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4};  Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7}; Plane Surface(2) = {2};
Physical Curve("floor") = {1};
Physical Curve("wall") = {2, 5};
Physical Curve("axis") = {4, 7};
Physical Surface("fill") = {1};
Physical Surface("headspace") = {2};
