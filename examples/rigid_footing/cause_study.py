#!/usr/bin/env python3
"""Which cause keeps the footing's pressure above Prandtl's (docs/verification-notes.md, "Prandtl's strip
footing"): the test case changed in one thing at a time, on the h = 0.05 and 0.025 m meshes.

    python3 examples/rigid_footing/cause_study.py cases DIR   # writes DIR/<variant>_<mesh>.json
    for f in DIR/*.json; do pmech run $f -o ${f%.json} --quiet --threads 1; done
    python3 examples/rigid_footing/cause_study.py table DIR   # pressure / Prandtl per run
    python3 examples/rigid_footing/cause_study.py edge RUN H  # per frame: the footing's edge node's share

Variants of tests/verification/cases/prandtl_footing.json (explicit MUSL, F-bar, damping 0.05, footing at
0.05 m/s ramped over its first 2.5 mm of settlement, 2 x 2 points per cell):
  base       unchanged
  slow, fast the footing at 0.025 and 0.1 m/s (ramp and end time scaled so that the ramp ends, and the
             run stops, at the same settlement): the rate and the inertia
  damp0      no damping; damp10 damping 0.10
  nofbar     F-bar off
  ppc3       3 x 3 points per cell
  qs         quasi-static (implicit, no inertia, no damping; no F-bar there), 0.5 mm load steps
  qs_bs2, ex_bs2
             quasi-static and explicit (F-bar off, damping 0.05) with quadratic B-splines, which lock
             less than linear quads without F-bar: the same shape functions with and without dynamics
The table gives the footing's vertical force on the clay (forces.csv, column footing_y) over the half
width B/2 = 0.25 m against (2 + pi) c_u, c_u = 10 kPa, as means over the rows in settlement windows
(the settlement of each row from the footing's velocity function).
"""
import csv
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
BASE = os.path.join(HERE, "..", "..", "tests", "verification", "cases", "prandtl_footing.json")
MESHES = {"h050": [40, 24], "h025": [80, 48], "h0125": [160, 96]}
PRANDTL = (2 + math.pi) * 10e3
HALF_WIDTH = 0.25
SPEED, RAMP, END = 0.05, 0.1, 0.5  # the test case's footing speed and ramp time; runs to 22.5 mm
WINDOWS = [(0.0075, 0.0125), (0.0125, 0.02), (0.02, 0.0225)]  # settlement (m)


def variant(base, name):
    c = json.loads(json.dumps(base))
    a, ob = c["analysis"], c["obstacles"][0]
    scale = 1.0
    if name == "slow":
        scale = 2.0
    elif name == "fast":
        scale = 0.5
    elif name == "damp0":
        a["damping"] = 0.0
    elif name == "damp10":
        a["damping"] = 0.10
    elif name == "nofbar":
        a["fbar"] = "none"
    elif name == "ppc3":
        c["bodies"][0]["particles_per_cell"] = 3
    elif name in ("qs", "qs_bs2"):
        c["analysis"] = {"type": "quasi_static", "end_time": END, "load_steps": int(round(END / 0.01)),
                         "gravity": [0.0, 0.0]}
    elif name == "ex_bs2":
        a["fbar"] = "none"
    if name in ("qs_bs2", "ex_bs2"):
        c["shape_function"] = "bspline2"
    ob["velocity"] = [0, {"value": -SPEED / scale, "ramp_time": RAMP * scale}]
    if "scheme" in c["analysis"]:
        c["analysis"]["end_time"] = END * scale
    c["output"] = {"interval": 0.05 * scale}
    return c, scale


VARIANTS = ["base", "slow", "fast", "damp0", "damp10", "nofbar", "ppc3", "qs", "qs_bs2", "ex_bs2"]


def write_cases(out, names):
    os.makedirs(out, exist_ok=True)
    with open(BASE) as f:
        base = json.load(f)
    for name in names:
        for mesh, cells in MESHES.items():
            c, scale = variant(base, name)
            c["grid"]["cells"] = cells
            with open(os.path.join(out, f"{name}_{mesh}.json"), "w") as f:
                json.dump(c, f, indent=1)


def settlement(t, scale):
    """The footing's settlement at time t: the ramped velocity integrated (time scaled by scale)."""
    ramp, v = RAMP * scale, SPEED / scale
    return v * t * t / (2 * ramp) if t < ramp else v * (t - ramp / 2)


def ratio(s, fy, lo, hi):
    v = [c for ss, c in zip(s, fy) if lo <= ss <= hi]
    return sum(v) / len(v) / HALF_WIDTH / PRANDTL if v else float("nan")


def table(out):
    print("| run | settlement 7.5-12.5 mm | 12.5-20 mm | 20-22.5 mm | every 2.5 mm from 5 mm |")
    print("|---|---|---|---|---|")
    for name in VARIANTS:
        scale = {"slow": 2.0, "fast": 0.5}.get(name, 1.0)
        for mesh in MESHES:
            path = os.path.join(out, f"{name}_{mesh}", "forces.csv")
            if not os.path.exists(path):
                continue
            with open(path) as f:
                rows = list(csv.DictReader(f))
            if not rows:
                continue
            s = [settlement(float(r["time"]), scale) for r in rows]
            fy = [-float(r["footing_y"]) for r in rows]
            series = [ratio(s, fy, k * 0.0025 - 0.00125, k * 0.0025 + 0.00125) for k in range(2, 10)]
            series = " ".join(f"{x:.3f}" for x in series if not math.isnan(x))
            w = " | ".join(f"{ratio(s, fy, lo, hi):.3f}" for lo, hi in WINDOWS)
            print(f"| {name} {mesh} (to {1e3 * s[-1]:.1f} mm) | {w} | {series} |")


def edge(run, h):
    """Per frame of RUN's wall_footing.csv (cell size h): the force on the footing's base (its stations'
    normal traction times their spacing h, the base being the lowest row of stations at 0 <= x <= B/2),
    the part at the node on its edge line x = B/2, and the pressure over B/2 with and without that part
    and over B/2 + h (the width the footing drives once it holds the edge node: that node's support
    reaches a cell beyond the edge), each over (2 + pi) c_u."""
    with open(os.path.join(run, "wall_footing.csv")) as f:
        rows = list(csv.DictReader(f))
    frames = {}
    for r in rows:
        frames.setdefault(r["time"], []).append(r)
    print("| t (s) | settlement (mm) | force on the base (kN/m) | at the edge node | / (B/2) | without the edge "
          "node / (B/2) | / (B/2 + h) |")
    print("|---|---|---|---|---|---|---|")
    for t, rs in frames.items():
        y0 = min(float(r["y"]) for r in rs)
        base = [r for r in rs if abs(float(r["y"]) - y0) < 1e-9 and -1e-9 < float(r["x"]) < HALF_WIDTH + 1e-9]
        total = sum(float(r["normal"]) for r in base) * h
        at_edge = sum(float(r["normal"]) for r in base if float(r["x"]) > HALF_WIDTH - 1e-9) * h
        p = [total / HALF_WIDTH, (total - at_edge) / HALF_WIDTH, total / (HALF_WIDTH + h)]
        print(f"| {float(t):.2f} | {1e3 * settlement(float(t), 1.0):.1f} | {total / 1e3:.2f} | {at_edge / 1e3:.2f} | "
              + " | ".join(f"{x / PRANDTL:.3f}" for x in p) + " |")


if __name__ == "__main__":
    if len(sys.argv) < 3 or sys.argv[1] not in ("cases", "table", "edge"):
        sys.exit(__doc__)
    if sys.argv[1] == "cases":
        write_cases(sys.argv[2], sys.argv[3:] or VARIANTS)
    elif sys.argv[1] == "edge":
        edge(sys.argv[2], float(sys.argv[3]))
    else:
        table(sys.argv[2])
