"""Seed 004's Fig. 9 comparison: the filling's final deposit re-solved quasi-statically by pmech's
implicit solver, and the two runs' wall tractions side by side.

    python3 examples/silo_filling/quasi_static.py case FILL_DIR QS_CASE.json
        writes a quasi-static case of the deposit FILL_DIR ended with (its surface from the last frame:
        per 50 mm column the top of the highest point, plus its half-size), at the deposit's mean
        density, Mohr-Coulomb with the granular model's friction angle, Coulomb walls as in the filling
    python3 examples/silo_filling/quasi_static.py compare FILL_DIR QS_DIR
        prints the wall's and the floor's normal and tangential forces of both runs (forces.csv; the
        filling's averaged over its last 20 outputs) and the filling's wall profile (quasi-static runs
        write no wall profiles)

The elastic constants of the fill at rest are the granular model's tangent at the deposit's mean
pressure p: K_t = (1 + e0) / kappa p, E = 3 K_t (1 - 2 nu); a small cohesion (1 % of rho g H) keeps
the points at the free surface, which carry no pressure, from failing in tension during the Newton
iterations.
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import last_frame, read_vtu  # noqa: E402

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
        "grid": {"type": "rectangle", "origin": [-CELL, 0.0], "size": [WIDTH + CELL, H + 4 * CELL],
                 "cells": [int(round((WIDTH + CELL) / CELL)), int(math.ceil((H + 4 * CELL) / CELL))]},
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


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("case", "compare"):
        sys.exit(__doc__)
    if sys.argv[1] == "case":
        make_case(sys.argv[2], sys.argv[3])
    else:
        compare(sys.argv[2], sys.argv[3])
