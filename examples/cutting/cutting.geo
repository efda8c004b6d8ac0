// Orthogonal cutting (seed 004 section 5.3.2), plane stress, metres: the plate 16..40 mm long and
// 10 mm high on a base held fixed, and open space around it for the chip, in transfinite blocks of
// 0.5 mm quads (the same cells as case_rectangle.json's 72 x 36 grid). The tool moves and stays an
// obstacle. Columns: x = 12..16 (where the tool goes past the plate's end), 16..40 (the plate),
// 40..48 (where the tool starts); rows: y = 0..10 (the plate's height), 10..18 (the chip's space).
// Regenerate cutting.msh with:  gmsh cutting.geo -2 -format msh41 -o cutting.msh
DefineConstant[ h = 0.0005 ];  // cell size (m); -setnumber h VALUE overrides it
xs[] = {0.012, 0.016, 0.040, 0.048};
ys[] = {0, 0.010, 0.018};
NX = #xs[]; NY = #ys[];
For j In {0 : NY - 1}
  For i In {0 : NX - 1}
    Point(1 + j * NX + i) = {xs[i], ys[j], 0};
  EndFor
EndFor
// horizontal lines: tag 1000 + j * NX + i from point (i, j) to (i + 1, j); vertical: 2000 + j * NX + i
For j In {0 : NY - 1}
  For i In {0 : NX - 2}
    Line(1000 + j * NX + i) = {1 + j * NX + i, 2 + j * NX + i};
    Transfinite Curve{1000 + j * NX + i} = Round((xs[i + 1] - xs[i]) / h) + 1;
  EndFor
EndFor
For j In {0 : NY - 2}
  For i In {0 : NX - 1}
    Line(2000 + j * NX + i) = {1 + j * NX + i, 1 + (j + 1) * NX + i};
    Transfinite Curve{2000 + j * NX + i} = Round((ys[j + 1] - ys[j]) / h) + 1;
  EndFor
EndFor
// block (i, j): surface 1 + j * (NX - 1) + i
For j In {0 : NY - 2}
  For i In {0 : NX - 2}
    Curve Loop(1 + j * (NX - 1) + i) = {1000 + j * NX + i, 2000 + j * NX + i + 1, -(1000 + (j + 1) * NX + i),
                                        -(2000 + j * NX + i)};
    Plane Surface(1 + j * (NX - 1) + i) = {1 + j * (NX - 1) + i};
    Transfinite Surface{1 + j * (NX - 1) + i};
    Recombine Surface{1 + j * (NX - 1) + i};
  EndFor
EndFor
Physical Curve("base") = {1000, 1001, 1002};
Physical Surface("plate") = {2};
Physical Surface("open") = {1, 3, 4, 5, 6};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
