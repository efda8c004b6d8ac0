#!/usr/bin/env python3
"""Write gmsh_incline<deg>.msh (MSH 4.1 ASCII) for verify_gmsh_incline: a strip of triangles above a
straight slope at 10, 25 and 35 degrees, its bottom the 1-D physical group "slope". Columns are
vertical (x = i h), rows follow the slope (y = y_b(x) + j h), so no cell side lies along an axis
except the vertical ones and the slope's own edges are neither horizontal nor vertical. Each
parallelogram is cut into two triangles along alternating diagonals. The slope's line elements are
written in both directions (every other one reversed), as a mesh generator may: the reader must turn
them to point along the mesh's boundary itself."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools"))
from msh41 import write_msh41  # noqa: E402

H, NX, NY, Y0 = 0.01, 50, 14, 0.4


def write(deg):
    tn = math.tan(math.radians(deg))
    nodes = {}
    for j in range(NY + 1):
        for i in range(NX + 1):
            x = i * H
            nodes[(i, j)] = (len(nodes) + 1, x, Y0 - x * tn + j * H)
    tag = lambda i, j: nodes[(i, j)][0]
    tris = {1: []}
    for j in range(NY):
        for i in range(NX):
            a, b, c, d = tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)
            tris[1] += [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
    lines = {1: [(tag(i, 0), tag(i + 1, 0)) if i % 2 == 0 else (tag(i + 1, 0), tag(i, 0)) for i in range(NX)],
             2: [(tag(NX, j), tag(NX, j + 1)) for j in range(NY)],
             3: [(tag(i + 1, NY), tag(i, NY)) for i in range(NX - 1, -1, -1)],
             4: [(tag(0, j + 1), tag(0, j)) for j in range(NY - 1, -1, -1)]}
    xr = NX * H
    pts = {1: (0, Y0), 2: (xr, Y0 - xr * tn), 3: (xr, Y0 - xr * tn + NY * H), 4: (0, Y0 + NY * H)}
    curves = {1: (1, 2, [1]), 2: (2, 3, []), 3: (3, 4, []), 4: (4, 1, [])}
    box = (0, Y0 - xr * tn, xr, Y0 + NY * H)
    surfaces = {1: (box, [2], [1, 2, 3, 4])}
    names = [(1, 1, "slope"), (2, 2, "strip")]
    write_msh41(f"gmsh_incline{deg}.msh", names, pts, curves, surfaces, nodes, lines, tris)


for deg in (10, 25, 35):
    write(deg)
