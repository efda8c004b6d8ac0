#!/usr/bin/env python3
"""Write silo.msh (MSH 4.1 ASCII) with the entities and physical groups of silo.geo, without Gmsh:
the silo's meridian plane r in [0, 1], z in [0, 3.5] on a grid of h = 0.05 m, each quad cut into two
triangles along alternating diagonals. `make_mesh.py JITTER` moves interior nodes by up to JITTER h
(nodes on the boundary lines and on the fill surface z = 3 only along them); the shipped mesh has
none (see the README for what a jittered mesh shows). Physical groups: 2-D
"fill" (z < 3) and "headspace", 1-D "floor" (z = 0), "wall" (r = 1), "axis" (r = 0)."""
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from msh41 import write_msh41  # noqa: E402

random.seed(7)
jit = float(sys.argv[1]) if len(sys.argv) > 1 else 0.0
h, R, HF, HT = 0.05, 1.0, 3.0, 3.5
nx, ny, jf = round(R / h), round(HT / h), round(HF / h)
nodes = {}
for j in range(ny + 1):
    for i in range(nx + 1):
        x, y = round(i * h, 12), round(j * h, 12)
        if i not in (0, nx):
            x += random.uniform(-jit, jit) * h
        if j not in (0, jf, ny):
            y += random.uniform(-jit, jit) * h
        nodes[(i, j)] = (len(nodes) + 1, x, y)
tag = lambda i, j: nodes[(i, j)][0]
tris = {1: [], 2: []}
for j in range(ny):
    for i in range(nx):
        a, b, c, d = tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)
        s = 1 if j < jf else 2
        if (i + j) % 2 == 0:
            tris[s] += [(a, b, c), (a, c, d)]
        else:
            tris[s] += [(a, b, d), (b, c, d)]
lines = {
    1: [(tag(i, 0), tag(i + 1, 0)) for i in range(nx)],                        # floor
    2: [(tag(nx, j), tag(nx, j + 1)) for j in range(jf)],                      # wall, fill
    3: [(tag(i + 1, jf), tag(i, jf)) for i in range(nx - 1, -1, -1)],          # fill surface
    4: [(tag(0, j + 1), tag(0, j)) for j in range(jf - 1, -1, -1)],            # axis, fill
    5: [(tag(nx, j), tag(nx, j + 1)) for j in range(jf, ny)],                  # wall, headspace
    6: [(tag(i + 1, ny), tag(i, ny)) for i in range(nx - 1, -1, -1)],          # top
    7: [(tag(0, j + 1), tag(0, j)) for j in range(ny - 1, jf - 1, -1)],        # axis, headspace
}
pts = {1: (0, 0), 2: (R, 0), 3: (R, HF), 4: (0, HF), 5: (R, HT), 6: (0, HT)}
curves = {1: (1, 2, [1]), 2: (2, 3, [2]), 3: (3, 4, []), 4: (4, 1, [3]), 5: (3, 5, [2]), 6: (5, 6, []),
          7: (6, 4, [3])}
surfaces = {1: ((0, 0, R, HF), [4], [1, 2, 3, 4]), 2: ((0, HF, R, HT), [5], [-3, 5, 6, 7])}
names = [(1, 1, "floor"), (1, 2, "wall"), (1, 3, "axis"), (2, 4, "fill"), (2, 5, "headspace")]
write_msh41("silo.msh", names, pts, curves, surfaces, nodes, lines, tris)
