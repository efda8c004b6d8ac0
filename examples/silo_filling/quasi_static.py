"""Seed 004's Fig. 9 comparison: the filling's final deposit re-solved quasi-statically by pmech's
implicit solver, and the two runs' wall tractions side by side.

    python3 examples/silo_filling/quasi_static.py case FILL_DIR QS_CASE.json
        writes a quasi-static case of the deposit FILL_DIR ended with (its surface from the last frame:
        per 50 mm column the top of the highest point, plus its half-size), at the deposit's mean
        density, Mohr-Coulomb with the granular model's friction angle, Coulomb walls as in the filling
    python3 examples/silo_filling/quasi_static.py compare FILL_DIR QS_DIR
        prints the wall's and the floor's normal and tangential forces of both runs (forces.csv; the
        filling's averaged over its last 20 outputs) and the filling's wall profile
    python3 examples/silo_filling/quasi_static.py figure FILL_DIR QS_DIR [OUT_DIR] [--window SECONDS]
        seed 004's Fig. 9: the wall's and the floor's normal and tangential tractions of the filling's
        end (wall_boundary_conditions1.csv and 2.csv averaged over the profiles of its last SECONDS,
        default 2, whole output intervals only), of the quasi-static solution (its last load step) and
        Janssen's for the deposit's mean height and density (as figures.py); writes fig9_tractions.svg,
        .png (through ffmpeg) and .csv into OUT_DIR (default QS_DIR) and prints the forces over the
        lower and upper halves of the wall and on the floor against Janssen's

The elastic constants of the fill at rest are the granular model's tangent at the deposit's mean
pressure p: K_t = (1 + e0) / kappa p, E = 3 K_t (1 - 2 nu); a small cohesion (1 % of rho g H) keeps
the points at the free surface, which carry no pressure, from failing in tension during the Newton
iterations.
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import last_frame, read_vtu  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures as figs  # noqa: E402

WIDTH, CELL, KAPPA, E0, NU, PHI, MU_W = 1.0, 0.05, 0.02, 0.9, 0.3, 30.0, 0.364


def deposit(run):
    """Columns' tops, mass and mean pressure of the last frame of an explicit run."""
    _, path = last_frame(run)
    f = read_vtu(path)
    n, pts, m, pr, hs = f["n"], f["Points"], f["mass"], f["pressure"], f["half_size"]
    ncol = int(round(WIDTH / CELL))
    top = [0.0] * ncol
    for i in range(n):
        j = int(pts[3 * i] / CELL)
        if 0 <= j < ncol:
            top[j] = max(top[j], pts[3 * i + 1] + hs[2 * i + 1])
    mass = sum(m)
    p_mean = sum(m[i] * max(pr[i], 0.0) for i in range(n)) / mass
    return top, mass, p_mean


def make_case(run, out):
    top, mass, p_mean = deposit(run)
    area = sum(t * CELL for t in top)
    rho = mass / area
    H = max(top)
    K = (1 + E0) / KAPPA * p_mean
    E = 3 * K * (1 - 2 * NU)
    ny = int(math.ceil(H / CELL)) + 4
    outline = [[0.0, 0.0], [WIDTH, 0.0]]
    for j in reversed(range(len(top))):
        outline.append([min((j + 1) * CELL, WIDTH), top[j]])
        outline.append([j * CELL, top[j]])
    # drop repeated points and columns without material at the edges
    pts = []
    for q in outline:
        if not pts or abs(q[0] - pts[-1][0]) > 1e-12 or abs(q[1] - pts[-1][1]) > 1e-12:
            pts.append([round(q[0], 6), round(q[1], 6)])
    case = {
        "title": "Final deposit of the silo filling at rest, quasi-static (seed 004 Fig. 9)",
        "dimension": 2,
        "analysis": {"type": "quasi_static", "end_time": 1.0, "load_steps": 10, "gravity": [0.0, -9.81]},
        # square cells of the filling's size, so that both runs' wall profiles have the same stations
        "grid": {"type": "rectangle", "origin": [-CELL, 0.0], "size": [WIDTH + CELL, round(ny * CELL, 6)],
                 "cells": [int(round((WIDTH + CELL) / CELL)), ny]},
        "materials": [{"name": "grain", "model": "mohr_coulomb", "density": round(rho, 3),
                       "youngs_modulus": round(E, 1), "poisson_ratio": NU, "friction_angle": PHI,
                       "cohesion": round(0.01 * rho * 9.81 * H, 3)}],
        "bodies": [{"name": "deposit", "material": "grain", "shape": {"type": "polygon", "points": pts},
                    "particles_per_cell": 3}],
        "boundary_conditions": [
            {"type": "fixed", "boundary": {"x": 0}, "directions": ["x"]},
            {"type": "friction", "boundary": "x_max", "coefficient": MU_W},
            {"type": "friction", "boundary": "y_min", "coefficient": MU_W},
        ],
        "output": {"directory": "silo_filling_qs.out", "interval": 1.0},
    }
    with open(out, "w") as fh:
        json.dump(case, fh, indent=1)
    print("deposit: %.1f kg/m, %.3f m^2 under its surface (rho %.0f kg/m^3), top %.2f m, mean p %.0f Pa, "
          "E %.3g Pa" % (mass, area, rho, H, p_mean, E))


def resultants(run, n_last):
    """Wall's and floor's normal and tangential force (N/m) from forces.csv, the last n_last rows averaged."""
    rows = [r.split(",") for r in open(os.path.join(run, "forces.csv")).read().split("\n")[1:] if r][-n_last:]
    # columns: time, then per condition: normal, tangent_x, tangent_y, x, y (wall: condition 1, floor: 2)
    avg = [sum(float(r[k]) for r in rows) / len(rows) for k in range(len(rows[0]))]
    return {"wall normal": avg[1], "wall tangential": avg[3], "floor normal": avg[6], "floor tangential": avg[7]}


def wall_profiles(run, name, window):
    """A wall CSV's profile averaged over the output intervals within the last `window` seconds (each
    row is already the mean over the interval before its time; weighted by the interval's length):
    ([(s, x, y, normal, tangent)], the span averaged over)."""
    rows = list(csv.DictReader(open(os.path.join(run, name))))
    times = sorted({float(r["time"]) for r in rows})
    end = times[-1]
    # each profile's interval starts at the time before it (the run's start for the first)
    starts = dict(zip(times, [0.0] + times[:-1]))
    used = [t for t in times if starts[t] >= end - window - 1e-9] or [end]
    weight = {t: t - starts[t] for t in used}
    span = sum(weight.values())
    acc = {}
    for r in rows:
        t = float(r["time"])
        if t not in weight:
            continue
        q = acc.setdefault(float(r["s"]), [float(r["x"]), float(r["y"]), 0.0, 0.0])
        q[2] += weight[t] / span * float(r["normal"])
        q[3] += weight[t] / span * float(r["tangent"])
    return [(k, v[0], v[1], v[2], v[3]) for k, v in sorted(acc.items())], span


def pieces(st, coord):
    """Each station's piece of wall along coordinate coord (half a cell either side, half a cell at
    the two ends): a profile lumps the force over its piece onto the station, so traction times the
    piece's length is that force and the pieces' sums split the resultant exactly."""
    n = len(st)
    h = st[1][coord] - st[0][coord] if n > 1 else 1.0
    return [(max(q[coord] - 0.5 * h, st[0][coord]), min(q[coord] + 0.5 * h, st[-1][coord])) for q in st]


def part(st, col, lo, hi, coord):
    """Force (N/m) the stations with lo <= coordinate < hi carry in column col (3 normal, 4 tangent),
    and the extent [a, b] of wall their pieces cover."""
    f, a, b = 0.0, math.inf, -math.inf
    for q, (p0, p1) in zip(st, pieces(st, coord)):
        if lo <= q[coord] < hi:
            f += q[col] * (p1 - p0)
            a, b = min(a, p0), max(b, p1)
    return f, a, b


def janssen_force(fn, a, b, n=400):
    """Integral of fn over [a, b] by the midpoint rule (fn is smooth: n = 400 is exact to 1e-5)."""
    h = (b - a) / n
    return sum(fn(a + (k + 0.5) * h) for k in range(n)) * h


def figure(fill, qs, out, window):
    _, path = last_frame(fill)
    mass, area, _, h_wall, _ = figs.deposit(path)
    H, rho = area / WIDTH, mass / area
    dyn = {k: wall_profiles(fill, n, window) for k, n in (("wall", figs.WALL), ("floor", figs.FLOOR))}
    sta = {k: wall_profiles(qs, n, 0.0) for k, n in (("wall", figs.WALL), ("floor", figs.FLOOR))}
    jv = lambda z: figs.janssen_v(rho, z)  # noqa: E731
    j_wall_n = lambda y: figs.K_J * jv(H - y) if y < H else 0.0  # noqa: E731
    j_wall_t = lambda y: MU_W * j_wall_n(y)  # noqa: E731
    print("deposit: %.0f kg/m, mean height H = %.2f m (%.2f m at the wall), mean density %.0f kg/m^3; "
          "the filling's profiles averaged over its last %.1f s" % (mass, H, h_wall, rho, dyn["wall"][1]))
    print("| force (N/m) | filling | quasi-static | Janssen | filling / Janssen | quasi-static / Janssen | filling / quasi-static |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    table = []
    for label, key, col, lo, hi, jfn in (
            ("wall normal, lower half (y < H/2)", "wall", 3, -1.0, H / 2, j_wall_n),
            ("wall normal, upper half (y >= H/2)", "wall", 3, H / 2, 1e9, j_wall_n),
            ("wall tangential, lower half", "wall", 4, -1.0, H / 2, j_wall_t),
            ("wall tangential, upper half", "wall", 4, H / 2, 1e9, j_wall_t),
            ("floor normal", "floor", 3, -1.0, 1e9, lambda x: jv(H)),
            ("floor tangential", "floor", 4, -1.0, 1e9, lambda x: 0.0)):
        coord = 2 if key == "wall" else 1
        fd, a, b = part(dyn[key][0], col, lo, hi, coord)
        fq, _, _ = part(sta[key][0], col, lo, hi, coord)
        # Janssen's over the material's part of those pieces (the floor's first station lies in the
        # grid's column beyond the axis)
        fj = janssen_force(jfn, max(a, 0.0), min(b, WIDTH) if key == "floor" else b)
        r = lambda u, v: "%.2f" % (u / v) if abs(v) > 1e-9 else "-"  # noqa: E731
        print("| %s | %.0f | %.0f | %.0f | %s | %s | %s |" % (label, fd, fq, fj, r(fd, fj), r(fq, fj), r(fd, fq)))
        table.append((label, fd, fq, fj))
    write_fig9(out, H, rho, dyn, sta, j_wall_n, j_wall_t, jv)
    return table


def write_fig9(out, H, rho, dyn, sta, j_wall_n, j_wall_t, jv):
    ys = [H * q / 60 for q in range(61)]
    black, red, grey = "#000000", "#d62728", "#7f7f7f"
    wall = [([(r[3] / 1e3, r[2]) for r in dyn["wall"][0]], black, 2.5, False),
            ([(r[4] / 1e3, r[2]) for r in dyn["wall"][0]], black, 1.0, False),
            ([(r[3] / 1e3, r[2]) for r in sta["wall"][0]], red, 2.5, False),
            ([(r[4] / 1e3, r[2]) for r in sta["wall"][0]], red, 1.0, False),
            ([(j_wall_n(y) / 1e3, y) for y in ys], grey, 2.0, True),
            ([(j_wall_t(y) / 1e3, y) for y in ys], grey, 1.0, True)]
    # the floor's stations from the axis on (the grid's column beyond it holds no material)
    fd, fs = [r for r in dyn["floor"][0] if r[1] >= 0], [r for r in sta["floor"][0] if r[1] >= 0]
    floor = [([(r[1], r[3] / 1e3) for r in fd], black, 2.5, False),
             ([(r[1], r[4] / 1e3) for r in fd], black, 1.0, False),
             ([(r[1], r[3] / 1e3) for r in fs], red, 2.5, False),
             ([(r[1], r[4] / 1e3) for r in fs], red, 1.0, False),
             ([(0.0, jv(H) / 1e3), (WIDTH, jv(H) / 1e3)], grey, 2.0, True),
             ([(0.0, 0.0), (WIDTH, 0.0)], grey, 1.0, True)]
    def upper(v):
        return figs.nice_step(v) * math.ceil(v / figs.nice_step(v))
    top_w = upper(max(abs(p[0]) for sr in wall for p in sr[0]))
    top_f = upper(max(abs(p[1]) for sr in floor for p in sr[0]))
    hgt = math.ceil(H * 2 + 1e-9) / 2
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="980" height="480" font-family="sans-serif">',
           '<rect width="980" height="480" fill="white"/>',
           '<text x="490" y="20" font-size="14" text-anchor="middle">Silo filling at 45 s: wall and floor tractions, '
           'dynamic against quasi-static (thick: normal, thin: tangential)</text>']
    svg += figs.svg_panel(70, 40, 380, 360, (-top_w / 4, top_w), (0, hgt), "wall traction (kPa)", "height y (m)", wall)
    svg += figs.svg_panel(560, 40, 380, 360, (0, WIDTH), (-top_f / 4, top_f), "distance from the axis x (m)",
                          "floor traction (kPa)", floor)
    legend = [("filling, mean of its last %.1f s" % dyn["wall"][1], black, False), ("quasi-static (implicit)", red, False),
              ("Janssen, K = %.2f, mu = %.3f, H = %.2f m, rho = %.0f kg/m^3" % (figs.K_J, MU_W, H, rho), grey, True)]
    for (text, colour, dashed), x in zip(legend, (70, 300, 500)):
        svg.append('<line x1="%g" y1="462" x2="%g" y2="462" stroke="%s" stroke-width="2"%s/>'
                   % (x, x + 24, colour, ' stroke-dasharray="6,4"' if dashed else ""))
        svg.append('<text x="%g" y="466" font-size="11">%s</text>' % (x + 30, text))
    svg.append("</svg>")
    os.makedirs(out, exist_ok=True)
    svg_path = os.path.join(out, "fig9_tractions.svg")
    open(svg_path, "w").write("\n".join(svg) + "\n")
    if shutil.which("ffmpeg"):
        subprocess.run(["ffmpeg", "-loglevel", "error", "-y", "-i", svg_path, svg_path[:-4] + ".png"], check=False)
    with open(os.path.join(out, "fig9_tractions.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["surface", "x", "y", "filling_normal", "filling_tangent", "quasi_static_normal",
                    "quasi_static_tangent", "janssen_normal", "janssen_tangent"])
        for key in ("wall", "floor"):
            # the two grids differ in height: match the stations by their place on the wall
            c = 2 if key == "wall" else 1
            qmap = {round(r[c], 6): r for r in sta[key][0]}
            for r in dyn[key][0]:
                q = qmap.get(round(r[c], 6), (0, 0, 0, 0.0, 0.0))
                jn = j_wall_n(r[2]) if key == "wall" else jv(H)
                jt = j_wall_t(r[2]) if key == "wall" else 0.0
                w.writerow([key, r[1], r[2], r[3], r[4], q[3], q[4], jn, jt])


def compare(fill, qs):
    a, b = resultants(fill, 20), resultants(qs, 1)
    print("force (N/m)        filling (last 20 outputs)   quasi-static   ratio")
    for k in a:
        print("%-18s %12.0f %18.0f %10.2f" % (k, a[k], b[k], a[k] / b[k] if b[k] else float("nan")))
    rows = [r.split(",") for r in open(os.path.join(fill, "wall_boundary_conditions1.csv")).read().split("\n")[1:] if r]
    last = max(float(r[0]) for r in rows)
    print("filling's wall profile at t = %g s (y, normal, tangential traction, Pa):" % last)
    for r in rows:
        if float(r[0]) == last and (float(r[4]) or float(r[5])):
            print("  %.2f %9.0f %9.0f" % (float(r[3]), float(r[4]), float(r[5])))


def main(argv):
    window = 2.0
    if "--window" in argv:
        k = argv.index("--window")
        window = float(argv[k + 1])
        argv = argv[:k] + argv[k + 2:]
    if len(argv) == 4 and argv[1] == "case":
        make_case(argv[2], argv[3])
    elif len(argv) == 4 and argv[1] == "compare":
        compare(argv[2], argv[3])
    elif len(argv) in (4, 5) and argv[1] == "figure":
        figure(argv[2], argv[3], argv[4] if len(argv) == 5 else argv[3], window)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
