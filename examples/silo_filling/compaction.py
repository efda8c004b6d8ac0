"""Where the deposit's over-compaction comes from: short fills of ten portions (t = 0-1.8 s, run to
3.5 s) in variants of case_rectangle.json (case.json on its rectangle), and three volumes of each deposit at its end.

    python3 examples/silo_filling/compaction.py case VARIANT OUT.json
        VARIANT: drop5 (portions fall 5 m and land at 10 m/s, as in case.json), drop1 (they fall
        1.35 m, 5 m/s, in a grid 1.6 m high), fine (drop5 on 25 mm cells, 3 x 3 points per cell,
        dt 2e-5 s, below its stable step of 2.3e-5 s), dt2 (drop5 at the paper's dt = 2e-5 s: the
        step fine runs at, on case.json's 50 mm cells), drop5x30 (drop5 with 30 portions, t = 0-5.8 s, run
        to 7 s), finex30 (fine with those 30 portions), drop1x30
        (drop1 with those 30 portions), drop5x60 (drop5 with 60 portions, t = 0-11.8 s, run to 13 s)
    python3 examples/silo_filling/compaction.py measure RUN_DIR [RUN_DIR ...]
    python3 examples/silo_filling/compaction.py points RUN_DIR [RUN_DIR ...]
    python3 examples/silo_filling/compaction.py skeleton RUN_DIR [RUN_DIR ...]

The three volumes (m^2 per metre of depth) of the deposit's points (those joined to the floor, as
figures.py finds them): from its surface (the area under the 50 mm columns' tops: what the positions
occupy), from the model's state (sum m (1 + e) / rho_s with e = min(e0 - kappa ln(p / p0), e_max),
the void ratio the granular law gives at each point's pressure: at rest its pressure is the elastic
one, so this is the model's own eps_v), and from the points' deformation gradients (sum V0 det F,
the VTU's volume). The granular law has no irreversible compaction, so a deposit at rest whose
surface holds less than its state's volume is denser in its positions than in its material: the
difference is numerical, not the model compacting as sand would. Also per 0.1 m layer from the
floor: the mass in the layer over the layer's area against the density the state gives there.
"""
import copy
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, last_frame, read_vtu  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures as figs  # noqa: E402

KAPPA, E0, P0, EMAX, RHO_S = 0.02, 0.9, 600.0, 1.0, 2850.0
HERE = os.path.dirname(os.path.abspath(__file__))


def make_case(variant, out):
    c = json.load(open(os.path.join(HERE, "case_rectangle.json")))
    c = copy.deepcopy(c)
    c["title"] = "Silo filling, a short fill (%s): where the deposit's over-compaction comes from" % variant
    c["analysis"]["end_time"] = 3.5
    src = c["sources"][0]
    src["until"] = 1.8
    c["output"] = {"directory": "compaction_%s.out" % variant, "interval": 0.5}
    if variant in ("drop1", "drop1x30"):
        src["shape"]["min"], src["shape"]["max"] = [0.0, 1.35], [0.2, 1.45]
        c["grid"]["size"], c["grid"]["cells"] = [1.05, 1.6], [21, 32]
        if variant == "drop1x30":
            src["until"], c["analysis"]["end_time"] = 5.8, 7.0
    elif variant == "fine":
        c["grid"]["cells"] = [42, 208]
        c["analysis"]["dt"] = 2.0e-5
    elif variant == "dt2":
        c["analysis"]["dt"] = 2.0e-5
    elif variant == "drop5x60":
        src["until"], c["analysis"]["end_time"] = 11.8, 13.0
    elif variant in ("drop5x30", "finex30"):
        src["until"], c["analysis"]["end_time"] = 5.8, 7.0
        if variant == "finex30":
            c["grid"]["cells"] = [42, 208]
            c["analysis"]["dt"] = 2.0e-5
    elif variant != "drop5":
        sys.exit("unknown variant %s (drop5, drop1, fine, dt2, drop5x30, finex30, drop1x30, drop5x60)" % variant)
    with open(out, "w") as fh:
        json.dump(c, fh, indent=1)


def e_of(p):
    return min(E0 - KAPPA * math.log(p / P0), EMAX) if p > 0 else EMAX


def measure(run):
    t, path = last_frame(run)
    f = read_vtu(path)
    n, pts, m, hs, pr, vol = f["n"], f["Points"], f["mass"], f["half_size"], f["pressure"], f["volume"]
    inside = figs.connected(n, pts, hs)
    ncol = int(round(figs.WIDTH / figs.CELL))
    top = [0.0] * ncol
    mass = v_state = v_detf = 0.0
    layers = {}
    for i in range(n):
        if not inside[i]:
            continue
        j = int(pts[3 * i] / figs.CELL)
        if 0 <= j < ncol:
            top[j] = max(top[j], pts[3 * i + 1] + hs[2 * i + 1])
        mass += m[i]
        vs = m[i] * (1 + e_of(pr[i])) / RHO_S
        v_state += vs
        v_detf += vol[i]
        k = int(pts[3 * i + 1] / 0.1)
        q = layers.setdefault(k, [0.0, 0.0, 0.0])
        q[0] += m[i]
        q[1] += vs
        q[2] += m[i] * pr[i]
    v_surf = sum(h * figs.CELL for h in top)
    print("%s: t = %.2f s, deposit %.1f kg/m (%d of %d points); volume from its surface %.4f m^2, from the "
          "model's state %.4f (surface / state %.3f), from det F %.4f (det F / state %.3f); mean density "
          "%.0f kg/m^3 (state: %.0f, release: 1500)"
          % (run, t, mass, sum(inside), n, v_surf, v_state, v_surf / v_state, v_detf, v_detf / v_state,
             mass / v_surf, mass / v_state))
    # the state at each layer's mean pressure: the pressures scatter from point to point (rows near
    # zero between rows carrying the load), and e(p) is convex, so the points' own e overstate the
    # volume a smooth field of the same mean would hold
    v_mean = sum(q[0] * (1 + e_of(q[2] / q[0])) / RHO_S for q in layers.values())
    print("  at each 0.1 m layer's mean pressure the state holds %.4f m^2 (surface / that %.3f, density "
          "%.0f kg/m^3)" % (v_mean, v_surf / v_mean, mass / v_mean))
    full = [k for k in sorted(layers) if (k + 1) * 0.1 <= min(top) + 1e-9]
    if full:
        print("  full layers (0.1 m from the floor): mass / area against the state's density at the layer's "
              "mean pressure: " + ", ".join("%.3f" % ((layers[k][0] / (0.1 * figs.WIDTH)) * (1 + e_of(layers[k][2] / layers[k][0])) / RHO_S) for k in full))


def positions_density(f, case, stencils=False, quarters=False):
    """Each point's density from the positions of all points, as the solver computes it before a step
    (src/mesh/density.c on a structured quad grid): nodal mass sum N_I m over the integral of N_I over
    the cells that hold a point, interpolated back to the point."""
    g = case["grid"]
    if g.get("type") == "gmsh":  # silo_filling.msh runs as this rectangle's structured grid
        g = json.load(open(os.path.join(HERE, "case_rectangle.json")))["grid"]
    (ox, oy), (sx, sy), (nx, ny) = g.get("origin", [0.0, 0.0]), g["size"], g["cells"]
    hx, hy = sx / nx, sy / ny
    n, pts, m = f["n"], f["Points"], f["mass"]
    mass_node, occupied, stencil = {}, set(), []
    for i in range(n):
        cx = min(max(int((pts[3 * i] - ox) / hx), 0), nx - 1)
        cy = min(max(int((pts[3 * i + 1] - oy) / hy), 0), ny - 1)
        a, b = (pts[3 * i] - ox) / hx - cx, (pts[3 * i + 1] - oy) / hy - cy
        st = [((cx, cy), (1 - a) * (1 - b)), ((cx + 1, cy), a * (1 - b)), ((cx + 1, cy + 1), a * b),
              ((cx, cy + 1), (1 - a) * b)]
        stencil.append(st)
        occupied.add((cx, cy, int(a >= 0.5), int(b >= 0.5)) if quarters else (cx, cy, -1, -1))
        for node, w in st:
            mass_node[node] = mass_node.get(node, 0.0) + w * m[i]
    den = {}
    for cx, cy, u, v in occupied:
        # the integral of each node's shape function over the cell, or over the occupied quarter
        # (of (1 - a) over a half: 3/8 on its own side, 1/8 on the other)
        ia = (0.5, 0.5) if u < 0 else ((0.375, 0.125) if u == 0 else (0.125, 0.375))
        ib = (0.5, 0.5) if v < 0 else ((0.375, 0.125) if v == 0 else (0.125, 0.375))
        for node, (j, k) in (((cx, cy), (0, 0)), ((cx + 1, cy), (1, 0)), ((cx + 1, cy + 1), (1, 1)), ((cx, cy + 1), (0, 1))):
            den[node] = den.get(node, 0.0) + ia[j] * ib[k] * hx * hy
    rho = [sum(w * mass_node[node] / den[node] for node, w in st) for st in stencil]
    return (rho, stencil) if stencils else rho


def p_of(ev):
    """The granular law's elastic pressure at the volumetric strain ev (eps_v held at e_max)."""
    ev = min(ev, math.log((1 + EMAX) / (1 + E0)))
    return P0 * math.exp((1 + E0) / KAPPA * (1 - math.exp(ev)))


def points(run):
    """Per point of the deposit, at every frame: the volumetric strain the granular law holds (its state,
    eps_v), the one the positions' density gives, ln(rho_ref / rho_positions), and ln det F, with the
    pressure; the state looser than the positions (eps_v above theirs) is crowding that costs no pressure."""
    case = json.load(open(os.path.join(run, "run.json")))["case"]
    case = json.load(open(case if os.path.isabs(case) else os.path.join(os.getcwd(), case)))
    rho_ref = case["materials"][0]["density"]
    print("%s: per frame, over the deposit's points (mass-weighted means; eps: volumetric strains)" % run)
    print("  t (s) | points | eps_v state | eps positions | ln det F | state - positions | share state "
          "looser by > 0.01 | by < -0.01 | mean p (kPa) | p at the positions' mean eps (kPa) | share p < 1 kPa")
    last = None
    for t, path in frames(run):
        f = read_vtu(path)
        if "material_state" not in f or f["n"] == 0:
            continue
        n, pts, hs, m = f["n"], f["Points"], f["half_size"], f["mass"]
        ns = len(f["material_state"]) // n
        inside = figs.connected(n, pts, hs)
        rho = positions_density(f, case)
        rows = []
        for i in range(n):
            if inside[i] and rho[i] > 0:
                rows.append((m[i], f["material_state"][ns * i + 1], math.log(rho_ref / rho[i]),
                             f["volumetric_strain"][i], f["pressure"][i], pts[3 * i + 1]))
        if not rows:
            continue
        M = sum(r[0] for r in rows)
        mean = [sum(r[0] * r[k] for r in rows) / M for k in range(1, 5)]
        looser = sum(r[0] for r in rows if r[1] - r[2] > 0.01) / M
        denser = sum(r[0] for r in rows if r[1] - r[2] < -0.01) / M
        low = sum(r[0] for r in rows if r[4] < 1000) / M
        print("  %5.2f | %5d | %.4f | %.4f | %.4f | %+.4f | %.2f | %.2f | %.2f | %.2f | %.2f"
              % (t, len(rows), mean[0], mean[1], mean[2], mean[0] - mean[1], looser, denser, mean[3] / 1e3,
                 p_of(mean[1]) / 1e3, low))
        last = (t, rows)
    if not last:
        sys.exit("%s: no frame carries material_state" % run)
    t, rows = last
    print("  at t = %.2f s per 0.1 m layer from the floor: mass-weighted eps_v state, eps positions, ln det F, "
          "mean p and the law's p at each mean eps (kPa), share of points with p < 1 kPa, spread (standard "
          "deviation) of eps_v and of eps positions" % t)
    layers = {}
    for r in rows:
        layers.setdefault(int(r[5] / 0.1), []).append(r)
    for k in sorted(layers):
        q = layers[k]
        M = sum(r[0] for r in q)
        ev, ep, ef, pm = (sum(r[0] * r[j] for r in q) / M for j in (1, 2, 3, 4))
        sv, sp = (math.sqrt(sum(r[0] * (r[j] - c) ** 2 for r in q) / M) for j, c in ((1, ev), (2, ep)))
        print("  %.1f-%.1f m: %5d points | %.4f | %.4f | %.4f | p %.2f, p(state) %.2f, p(positions) %.2f | %.2f"
              " | %.4f %.4f" % (0.1 * k, 0.1 * k + 0.1, len(q), ev, ep, ef, pm / 1e3, p_of(ev) / 1e3,
                                 p_of(ep) / 1e3, sum(r[0] for r in q if r[4] < 1000) / M, sv, sp))


def skeleton(run):
    """Candidate measures of the skeleton's volume at every frame: each point's density from positions
    (the solver's before a step); the same averaged node -> points -> node once and twice (the measure
    tried for the granular state, README "A measure that does not scatter, tried"); the same with only
    the occupied quarters of each cell counted as filled, then averaged twice (the other one tried); and
    the distance to the nearest point in spacings of the release lattice (d0 = sqrt(m / rho_ref)). For
    each: the standard deviation of ln rho within each 0.1 m layer of the deposit, and the share of
    points read apart (looser than e_max; nearest point further than 1.25 d0) in the deposit, in the
    deposit below its top 50 mm, and among the points not yet in the deposit (falling portions and
    their landing front)."""
    case = json.load(open(os.path.join(run, "run.json")))["case"]
    case = json.load(open(case if os.path.isabs(case) else os.path.join(os.getcwd(), case)))
    rho_ref = case["materials"][0]["density"]
    thr = rho_ref * (1 + E0) / (1 + EMAX)
    print("%s: share of points read apart (deposit / below its top 50 mm / not in the deposit) and, per 0.1 m "
          "layer of the deposit, the standard deviation of ln rho" % run)
    for t, path in frames(run):
        f = read_vtu(path)
        n, pts, hs, m = f["n"], f["Points"], f["half_size"], f["mass"]
        if n == 0:
            continue
        inside = figs.connected(n, pts, hs)
        own, stencil = positions_density(f, case, stencils=True)
        once = smooth_density(own, stencil, m)
        twice = smooth_density(once, stencil, m)
        quarters = smooth_density(smooth_density(positions_density(f, case, quarters=True), stencil, m), stencil, m)
        d0 = math.sqrt(sum(m) / n / rho_ref)
        near = nearest(pts, n)
        ncol = int(round(figs.WIDTH / figs.CELL))
        top = [0.0] * ncol
        for i in range(n):
            j = int(pts[3 * i] / figs.CELL)
            if inside[i] and 0 <= j < ncol:
                top[j] = max(top[j], pts[3 * i + 1])
        dep = [i for i in range(n) if inside[i]]
        below = [i for i in dep if not (0 <= int(pts[3 * i] / figs.CELL) < ncol and
                                        pts[3 * i + 1] > top[int(pts[3 * i] / figs.CELL)] - figs.CELL)]
        out = [i for i in range(n) if not inside[i]]
        print("  t = %.2f s: %d points in the deposit (%d below its top 50 mm), %d not" % (t, len(dep), len(below), len(out)))
        for name, v in (("own", own), ("averaged once", once), ("averaged twice", twice),
                        ("occupied quarters, averaged twice", quarters)):
            share = [sum(1 for i in q if v[i] < thr) / max(1, len(q)) for q in (dep, below, out)]
            layers = {}
            for i in dep:
                if v[i] > 0:
                    layers.setdefault(int(pts[3 * i + 1] / 0.1), []).append(math.log(v[i] / rho_ref))
            sds = []
            for k in sorted(layers):
                q = layers[k]
                if len(q) > 30:
                    mu = sum(q) / len(q)
                    sds.append(math.sqrt(sum((x - mu) ** 2 for x in q) / len(q)))
            print("    %-34s apart %.3f / %.3f / %.3f; sd per layer %s"
                  % (name, share[0], share[1], share[2], " ".join("%.3f" % x for x in sds)))
        share = [sum(1 for i in q if near[i] > 1.25 * d0) / max(1, len(q)) for q in (dep, below, out)]
        print("    %-34s apart %.3f / %.3f / %.3f" % ("nearest point", share[0], share[1], share[2]))


def smooth_density(rho, stencil, m):
    """One pass node -> points -> node: each node the mass-weighted mean of its points' values."""
    num, den = {}, {}
    for i, st in enumerate(stencil):
        for node, w in st:
            num[node] = num.get(node, 0.0) + w * m[i] * rho[i]
            den[node] = den.get(node, 0.0) + w * m[i]
    return [sum(w * num[node] / den[node] for node, w in st if den[node] > 0) for st in stencil]


def nearest(pts, n):
    """Distance from each point to its nearest neighbour (a bucket search on 50 mm cells)."""
    cells = {}
    for i in range(n):
        cells.setdefault((int(math.floor(pts[3 * i] / figs.CELL)), int(math.floor(pts[3 * i + 1] / figs.CELL))), []).append(i)
    out = [math.inf] * n
    for i in range(n):
        cx, cy = int(math.floor(pts[3 * i] / figs.CELL)), int(math.floor(pts[3 * i + 1] / figs.CELL))
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in cells.get((cx + dx, cy + dy), ()):
                    if j != i:
                        out[i] = min(out[i], math.hypot(pts[3 * j] - pts[3 * i], pts[3 * j + 1] - pts[3 * i + 1]))
    return out


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "case":
        make_case(sys.argv[2], sys.argv[3])
    elif len(sys.argv) >= 3 and sys.argv[1] == "measure":
        for r in sys.argv[2:]:
            measure(r)
    elif len(sys.argv) >= 3 and sys.argv[1] == "points":
        for r in sys.argv[2:]:
            points(r)
    elif len(sys.argv) >= 3 and sys.argv[1] == "skeleton":
        for r in sys.argv[2:]:
            skeleton(r)
    else:
        sys.exit(__doc__)
