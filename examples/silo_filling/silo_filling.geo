// The plane-strain half silo of the filling example (x across, y up): the silo 1 m wide from its
// plane of symmetry (x = 0, the "axis") to its wall (x = 1), 5.2 m high, and one column of cells
// beyond the axis (x = -0.05 to 0), where the grid holds the axis' symmetry. Transfinite quads of
// 50 mm: the cells of a 21 x 104 rectangle, which pmech runs as that structured grid.
// Regenerate silo_filling.msh with:  gmsh silo_filling.geo -2 -format msh41 -o silo_filling.msh
DefineConstant[ h = 0.05 ];  // cell size (m); -setnumber h VALUE overrides it
W = 1.0; H = 5.2;
Point(1) = {-h, 0, 0}; Point(2) = {0, 0, 0}; Point(3) = {W, 0, 0};
Point(4) = {-h, H, 0}; Point(5) = {0, H, 0}; Point(6) = {W, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3};   // the floor, beyond the axis and inside the silo
Line(3) = {4, 5}; Line(4) = {5, 6};   // the top
Line(5) = {1, 4}; Line(6) = {2, 5};   // the grid's far side beyond the axis, and the axis
Line(7) = {3, 6};                     // the wall
Curve Loop(1) = {1, 6, -3, -5}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 7, -4, -6}; Plane Surface(2) = {2};
Transfinite Curve{1, 3} = 2;
Transfinite Curve{2, 4} = Round(W / h) + 1;
Transfinite Curve{5, 6, 7} = Round(H / h) + 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};
Physical Curve("floor") = {1, 2};
Physical Curve("wall") = {7};
Physical Curve("axis") = {6};
Physical Surface("silo") = {2};
Physical Surface("beyond_axis") = {1};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
