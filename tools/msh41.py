"""Write a 2-D Gmsh MSH 4.1 ASCII file: points, curves and surfaces as entities with physical
groups, one node block, line and triangle element blocks. Shared by the examples' make_mesh.py
scripts so that they need no Gmsh."""


def write_msh41(path, names, pts, curves, surfaces, nodes, lines, tris):
    """names: [(dim, tag, "name")]; pts: {tag: (x, y)}; curves: {tag: (point_a, point_b, [phys])};
    surfaces: {tag: ((xmin, ymin, xmax, ymax), [phys], [signed curve loop])};
    nodes: {key: (node_tag, x, y)}; lines: {curve: [(n1, n2)]}; tris: {surface: [(n1, n2, n3)]}."""
    def tags(t):
        return f"{len(t)}{''.join(' %d' % v for v in t)}"
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(names))]
    out += [f'{d} {t} "{n}"' for d, t, n in names]
    out += ["$EndPhysicalNames", "$Entities", f"{len(pts)} {len(curves)} {len(surfaces)} 0"]
    for p, (x, y) in pts.items():
        out.append(f"{p} {x:.17g} {y:.17g} 0 0")
    for c, (a, b, ph) in curves.items():
        (xa, ya), (xb, yb) = pts[a], pts[b]
        out.append(f"{c} {min(xa, xb):.17g} {min(ya, yb):.17g} 0 {max(xa, xb):.17g} {max(ya, yb):.17g} 0 "
                   f"{tags(ph)} 2 {a} -{b}")
    for s, ((xa, ya, xb, yb), ph, loop) in surfaces.items():
        out.append(f"{s} {xa:.17g} {ya:.17g} 0 {xb:.17g} {yb:.17g} 0 {tags(ph)} {tags(loop)}")
    out += ["$EndEntities", "$Nodes", f"1 {len(nodes)} 1 {len(nodes)}", f"2 1 0 {len(nodes)}"]
    order = sorted(nodes.values())
    out += [str(t) for t, _, _ in order]
    out += [f"{x:.17g} {y:.17g} 0" for _, x, y in order]
    out += ["$EndNodes", "$Elements"]
    nel = sum(len(v) for v in lines.values()) + sum(len(v) for v in tris.values())
    out.append(f"{len(lines) + len(tris)} {nel} 1 {nel}")
    e = 1
    for dim, blocks in ((1, lines), (2, tris)):
        for ent, elems in blocks.items():
            out.append(f"{dim} {ent} {dim} {len(elems)}")
            for el in elems:
                out.append(f"{e} {' '.join(str(n) for n in el)}")
                e += 1
    out.append("$EndElements")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
