#!/usr/bin/env python3
"""Mesh study of the rigid footing (docs/verification-notes.md, "Prandtl's strip footing").

    python3 examples/rigid_footing/mesh_study.py cases DIR     # writes DIR/<h>_<acts_at>.json
    for f in DIR/*.json; do pmech run $f -o ${f%.json} --quiet --threads 1; done
    python3 examples/rigid_footing/mesh_study.py table DIR     # pressure / Prandtl per run

The cases are tests/verification/cases/prandtl_footing.json on 20 x 12, 40 x 24, 80 x 48 and 160 x 96
cells, run to t = 0.5 s, with the footing acting node by node (acts_at "nodes") and at the particles
("particles"). The table gives the footing's vertical force on the clay (forces.csv, column footing_y)
over the half width B/2 = 0.25 m against Prandtl's (2 + pi) c_u, c_u = 10 kPa: the mean over the rows
in the two settlement windows, and the means over every 0.025 s from t = 0.05 s (a run that stopped
early has fewer).
"""
import csv
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
BASE = os.path.join(HERE, "..", "..", "tests", "verification", "cases", "prandtl_footing.json")
MESHES = {"h100": [20, 12], "h050": [40, 24], "h025": [80, 48], "h0125": [160, 96]}
PRANDTL = (2 + math.pi) * 10e3
HALF_WIDTH = 0.25
WINDOWS = [(0.2, 0.3), (0.3, 0.45)]  # settlement 7.5-12.5 mm and 12.5-20 mm


def write_cases(out):
    os.makedirs(out, exist_ok=True)
    with open(BASE) as f:
        base = json.load(f)
    for name, cells in MESHES.items():
        for acts_at in ("nodes", "particles"):
            case = json.loads(json.dumps(base))
            case["grid"]["cells"] = cells
            case["analysis"]["end_time"] = 0.5
            case["output"] = {"interval": 0.05}
            case["obstacles"][0]["acts_at"] = acts_at
            with open(os.path.join(out, f"{name}_{acts_at}.json"), "w") as f:
                json.dump(case, f, indent=1)


def ratio(t, fy, lo, hi):
    v = [c for tt, c in zip(t, fy) if lo <= tt <= hi]
    return sum(v) / len(v) / HALF_WIDTH / PRANDTL if v else float("nan")


def table(out):
    print("| run | settlement 7.5-12.5 mm | 12.5-20 mm | every 0.025 s from t = 0.05 s |")
    print("|---|---|---|---|")
    for name in MESHES:
        for acts_at in ("nodes", "particles"):
            path = os.path.join(out, f"{name}_{acts_at}", "forces.csv")
            if not os.path.exists(path):
                continue
            with open(path) as f:
                rows = list(csv.DictReader(f))
            t = [float(r["time"]) for r in rows]
            fy = [-float(r["footing_y"]) for r in rows]
            series = [ratio(t, fy, k * 0.025 - 0.0125, k * 0.025 + 0.0125) for k in range(2, 21)]
            series = " ".join(f"{x:.3f}" for x in series if not math.isnan(x))
            w = " | ".join(f"{ratio(t, fy, lo, hi):.3f}" for lo, hi in WINDOWS)
            print(f"| {name} {acts_at} (to t = {t[-1]:.2f} s) | {w} | {series} |")


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("cases", "table"):
        sys.exit(__doc__)
    (write_cases if sys.argv[1] == "cases" else table)(sys.argv[2])
