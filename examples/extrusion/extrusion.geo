// Plane-strain extrusion through a 30 degree wedge die (seed 004 section 5.3.1), half model, metres:
// the space the metal can occupy, bounded by the axis (y = 0), the container wall (y = 10 mm), the
// die's inclined face (from x = 20 mm down to the exit half-height 5 mm at x = 28.66 mm) and its
// 2 mm land; behind the die the strip leaves into open space up to x = 56 mm, y = 12 mm. The ram
// moves and stays an obstacle: the 4 mm behind the billet are meshed for it to move into.
// Transfinite quads of 1 mm, 0.5 mm high where the die has halved the height (the wedge's quads
// shrink from 1 to 0.5 mm across it), so that the die's face and land are rows of grid nodes.
// Regenerate extrusion.msh with:  gmsh extrusion.geo -2 -format msh41 -o extrusion.msh
DefineConstant[ h = 0.001 ];  // cell size (m); -setnumber h VALUE overrides it
H0 = 0.010; H1 = 0.005; X_DIE = 0.020; L_CONE = H1 / Tan(30 * Pi / 180); L_LAND = 0.002;
X_RAM = -0.004; X_END = 0.056; Y_TOP = 0.012;
X_EXIT = X_DIE + L_CONE; X_BACK = X_EXIT + L_LAND;
Point(1) = {X_RAM, 0, 0};  Point(2) = {0, 0, 0};   Point(3) = {X_DIE, 0, 0};  Point(4) = {X_EXIT, 0, 0};
Point(5) = {X_BACK, 0, 0}; Point(6) = {X_END, 0, 0};
Point(7) = {X_RAM, H0, 0}; Point(8) = {0, H0, 0};  Point(9) = {X_DIE, H0, 0}; Point(10) = {X_EXIT, H1, 0};
Point(11) = {X_BACK, H1, 0}; Point(12) = {X_END, H1, 0};
Point(13) = {X_BACK, Y_TOP, 0}; Point(14) = {X_END, Y_TOP, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};   // axis
Line(6) = {7, 8}; Line(7) = {8, 9};                                                        // container
Line(8) = {9, 10};                                                                         // die face
Line(9) = {10, 11};                                                                        // die land
Line(10) = {11, 12}; Line(11) = {13, 14};
Line(12) = {1, 7}; Line(13) = {2, 8}; Line(14) = {3, 9}; Line(15) = {4, 10}; Line(16) = {5, 11};
Line(17) = {6, 12}; Line(18) = {11, 13}; Line(19) = {12, 14};
Curve Loop(1) = {1, 13, -6, -12};  Plane Surface(1) = {1};   // behind the billet, where the ram goes
Curve Loop(2) = {2, 14, -7, -13};  Plane Surface(2) = {2};   // billet in the container
Curve Loop(3) = {3, 15, -8, -14};  Plane Surface(3) = {3};   // billet in the die's wedge
Curve Loop(4) = {4, 16, -9, -15};  Plane Surface(4) = {4};   // billet along the land
Curve Loop(5) = {5, 17, -10, -16}; Plane Surface(5) = {5};   // the strip's way out
Curve Loop(6) = {10, 19, -11, -18}; Plane Surface(6) = {6};  // open space above it
N_H = Round(H0 / h);
Transfinite Curve{1, 6} = Round(-X_RAM / h) + 1;
Transfinite Curve{2, 7} = Round(X_DIE / h) + 1;
Transfinite Curve{3, 8} = Round(L_CONE / h) + 1;
Transfinite Curve{4, 9} = Round(L_LAND / h) + 1;
Transfinite Curve{5, 10, 11} = Round((X_END - X_BACK) / h) + 1;
Transfinite Curve{12, 13, 14, 15, 16, 17} = N_H + 1;
Transfinite Curve{18, 19} = Round((Y_TOP - H1) / h) + 1;
Transfinite Surface{1, 2, 3, 4, 5, 6};
Recombine Surface{1, 2, 3, 4, 5, 6};
Physical Curve("axis") = {1, 2, 3, 4, 5};
Physical Curve("container") = {6, 7};
Physical Curve("die_face") = {8};
Physical Curve("die_land") = {9};
Physical Surface("billet") = {2, 3, 4};
Physical Surface("open") = {1, 5, 6};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
