// Retaining wall (seed 004 section 5.2), plane strain: the 10 x 5 m box of retaining_wall_rectangle.json
// cut along the bodies' edges into transfinite blocks of 0.125 m quads (the same cells as that case's
// 80 x 40 grid). Columns: x = 0..3 (in front of the wall), 3..3.5 (the wall), 3.5..10 (behind it);
// rows: y = 0..1 (foundation soil), 1..1.125 and 1.125..1.25 (the wall's cracked base; the face is
// held above y = 1.125 while the fill settles), 1.25..4 (the wall and the stored material), 4..5 (air).
// Regenerate retaining_wall.msh with:  gmsh retaining_wall.geo -2 -format msh41 -o retaining_wall.msh
DefineConstant[ h = 0.125 ];  // cell size (m); -setnumber h VALUE overrides it
xs[] = {0, 3, 3.5, 10};
ys[] = {0, 1, 1.125, 1.25, 4, 5};
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
Physical Curve("left") = {2000, 2004, 2008, 2012, 2016};
Physical Curve("right") = {2003, 2007, 2011, 2015, 2019};
Physical Curve("wall_face") = {2009, 2013};
Physical Surface("soil") = {1, 2, 3};
Physical Surface("wall_base") = {5, 8};
Physical Surface("wall") = {11};
Physical Surface("stored") = {6, 9, 12};
Physical Surface("air") = {4, 7, 10, 13, 14, 15};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
