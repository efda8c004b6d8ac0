#!/usr/bin/env python3
"""Write bar.msh (MSH 4.1 ASCII) with the entities and physical groups of bar.geo, without Gmsh:
a grid of h = 0.01 with interior nodes jittered by up to 0.25 h (nodes on lines move only along
them), each quad cut into two triangles along alternating diagonals."""
import random

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
curve_pts = {1: (1, 2), 2: (2, 3), 3: (3, 4), 4: (4, 5), 5: (5, 6), 6: (6, 1), 7: (2, 5)}
curve_phys = {1: [1], 2: [1], 3: [3], 4: [2], 5: [2], 6: [], 7: [4]}
surf = {1: ([1, 7, 5, 6], [5]), 2: ([2, 3, 4, -7], [6])}
out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", "6",
       '1 1 "bottom"', '1 2 "top"', '1 3 "fixed_end"', '1 4 "free_end"', '2 5 "air"', '2 6 "bar"',
       "$EndPhysicalNames", "$Entities", "6 7 2 0"]
for p, (x, y) in pts.items():
    out.append(f"{p} {x:.17g} {y:.17g} 0 0")
for c, (a, b) in curve_pts.items():
    (xa, ya), (xb, yb) = pts[a], pts[b]
    ph = curve_phys[c]
    out.append(f"{c} {min(xa, xb):.17g} {min(ya, yb):.17g} 0 {max(xa, xb):.17g} {max(ya, yb):.17g} 0 "
               f"{len(ph)}{''.join(' %d' % t for t in ph)} 2 {a} -{b}")
for s, (cl, ph) in surf.items():
    xs = [x0, xi] if s == 1 else [xi, x1]
    out.append(f"{s} {xs[0]:.17g} 0 0 {xs[1]:.17g} {H:.17g} 0 {len(ph)}{''.join(' %d' % t for t in ph)} "
               f"{len(cl)}{''.join(' %d' % t for t in cl)}")
out += ["$EndEntities", "$Nodes", f"1 {len(nodes)} 1 {len(nodes)}", f"2 1 0 {len(nodes)}"]
order = sorted(nodes.values())
out += [str(t) for t, _, _ in order]
out += [f"{x:.17g} {y:.17g} 0" for _, x, y in order]
out += ["$EndNodes", "$Elements"]
nel = sum(len(v) for v in lines.values()) + sum(len(v) for v in tris.values())
out.append(f"{len(lines) + len(tris)} {nel} 1 {nel}")
e = 1
for c, segs in lines.items():
    out.append(f"1 {c} 1 {len(segs)}")
    for a, b in segs:
        out.append(f"{e} {a} {b}")
        e += 1
for s, ts in tris.items():
    out.append(f"2 {s} 2 {len(ts)}")
    for a, b, c in ts:
        out.append(f"{e} {a} {b} {c}")
        e += 1
out.append("$EndElements")
open("bar.msh", "w").write("\n".join(out) + "\n")
