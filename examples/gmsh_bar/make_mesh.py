#!/usr/bin/env python3
"""Write bar.msh (MSH 4.1 ASCII) with the entities and physical groups of bar.geo, without Gmsh:
a grid of h = 0.01 with interior nodes jittered by up to 0.25 h (nodes on lines move only along
them), each quad cut into two triangles along alternating diagonals."""
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from msh41 import write_msh41  # noqa: E402

random.seed(4)
h, H, x0, xi, x1 = 0.01, 0.04, -0.1, 0.0, 1.0
nx, ny = round((x1 - x0) / h), round(H / h)
i_int = round((xi - x0) / h)  # column of the interface x = 0
nodes = {}
for j in range(ny + 1):
    for i in range(nx + 1):
        x, y = round(x0 + i * h, 12), round(j * h, 12)
        on_v = i in (0, i_int, nx)
        on_h = j in (0, ny)
        if not on_v:
            x += random.uniform(-0.25, 0.25) * h
        if not on_h:
            y += random.uniform(-0.25, 0.25) * h
        nodes[(i, j)] = (len(nodes) + 1, x, y)
tag = lambda i, j: nodes[(i, j)][0]
tris = {1: [], 2: []}  # surface -> triangles
for j in range(ny):
    for i in range(nx):
        a, b, c, d = tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)
        s = 1 if i < i_int else 2
        if (i + j) % 2 == 0:
            tris[s] += [(a, b, c), (a, c, d)]
        else:
            tris[s] += [(a, b, d), (b, c, d)]
lines = {
    1: [(tag(i, 0), tag(i + 1, 0)) for i in range(i_int)],
    2: [(tag(i, 0), tag(i + 1, 0)) for i in range(i_int, nx)],
    3: [(tag(nx, j), tag(nx, j + 1)) for j in range(ny)],
    4: [(tag(i + 1, ny), tag(i, ny)) for i in range(nx - 1, i_int - 1, -1)],
    5: [(tag(i + 1, ny), tag(i, ny)) for i in range(i_int - 1, -1, -1)],
    6: [(tag(0, j + 1), tag(0, j)) for j in range(ny - 1, -1, -1)],
    7: [(tag(i_int, j), tag(i_int, j + 1)) for j in range(ny)],
}
pts = {1: (x0, 0), 2: (xi, 0), 3: (x1, 0), 4: (x1, H), 5: (xi, H), 6: (x0, H)}
curves = {1: (1, 2, [1]), 2: (2, 3, [1]), 3: (3, 4, [3]), 4: (4, 5, [2]), 5: (5, 6, [2]), 6: (6, 1, []),
          7: (2, 5, [4])}
surfaces = {1: ((x0, 0, xi, H), [5], [1, 7, 5, 6]), 2: ((xi, 0, x1, H), [6], [2, 3, 4, -7])}
names = [(1, 1, "bottom"), (1, 2, "top"), (1, 3, "fixed_end"), (1, 4, "free_end"), (2, 5, "air"), (2, 6, "bar")]
write_msh41("bar.msh", names, pts, curves, surfaces, nodes, lines, tris)
