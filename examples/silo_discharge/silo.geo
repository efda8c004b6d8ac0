// Meridian plane of the flat-bottomed silo (x = r, y = z): radius 1 m, fill 3 m high, headspace to
// 3.2 m, central outlet of radius 0.2 m. Transfinite quads of 20 mm, the same cells as the
// 50 x 160 rectangular grid of discharge_rectangle.json, so that the two runs are comparable.
// Regenerate silo.msh with:  gmsh silo.geo -2 -format msh41 -o silo.msh
DefineConstant[ h = 0.02 ];  // cell size (m); -setnumber h VALUE overrides it
R = 1.0; R_OUT = 0.2; H_FILL = 3.0; H_TOP = 3.2;
Point(1) = {0, 0, 0};      Point(2) = {R_OUT, 0, 0};      Point(3) = {R, 0, 0};
Point(4) = {0, H_FILL, 0}; Point(5) = {R_OUT, H_FILL, 0}; Point(6) = {R, H_FILL, 0};
Point(7) = {0, H_TOP, 0};  Point(8) = {R_OUT, H_TOP, 0};  Point(9) = {R, H_TOP, 0};
// the floor: outlet r < R_OUT, the rest closed
Line(1) = {1, 2}; Line(2) = {2, 3};
// the fill's top and the headspace's top
Line(3) = {4, 5}; Line(4) = {5, 6}; Line(5) = {7, 8}; Line(6) = {8, 9};
// axis, the outlet's edge line r = R_OUT (inside the fill), wall: each in the fill and the headspace
Line(7) = {1, 4};  Line(8) = {4, 7};
Line(9) = {2, 5};  Line(10) = {5, 8};
Line(11) = {3, 6}; Line(12) = {6, 9};
Curve Loop(1) = {1, 9, -3, -7};   Plane Surface(1) = {1};
Curve Loop(2) = {2, 11, -4, -9};  Plane Surface(2) = {2};
Curve Loop(3) = {3, 10, -5, -8};  Plane Surface(3) = {3};
Curve Loop(4) = {4, 12, -6, -10}; Plane Surface(4) = {4};
Transfinite Curve{1, 3, 5} = Round(R_OUT / h) + 1;
Transfinite Curve{2, 4, 6} = Round((R - R_OUT) / h) + 1;
Transfinite Curve{7, 9, 11} = Round(H_FILL / h) + 1;
Transfinite Curve{8, 10, 12} = Round((H_TOP - H_FILL) / h) + 1;
Transfinite Surface{1, 2, 3, 4};
Recombine Surface{1, 2, 3, 4};
Physical Curve("outlet") = {1};
Physical Curve("floor") = {2};
Physical Curve("wall") = {11, 12};
Physical Curve("axis") = {7, 8};
Physical Surface("fill") = {1, 2};
Physical Surface("headspace") = {3, 4};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
