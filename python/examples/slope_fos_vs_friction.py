#!/usr/bin/env python3
"""A parameter study from Python: the factor of safety of Griffiths & Lane's 2:1 slope
(examples/slope_fos) against the friction angle, by strength reduction, on the coarse grid h = H/10.

    python3 python/examples/slope_fos_vs_friction.py [OUT_DIR] [--angles 10,20,30] [--cells-per-m 1]

Writes OUT_DIR/fos_vs_friction.csv and OUT_DIR/fos_vs_friction.png (default OUT_DIR: fos_study.out).
Each search runs the case with c' / F and atan(tan(phi') / F) for trial factors F and bisects between
the factors that hold and fail; see examples/slope_fos/README.md for what the grid does to the answer.
"""
import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir))  # run from a checkout without installing

import pmech  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", nargs="?", default="fos_study.out")
    ap.add_argument("--angles", default="10,20,30", help="friction angles in degrees")
    ap.add_argument("--cells-per-m", type=float, default=1.0, help="grid cells per metre (1: h = H/10)")
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    case = pmech.Case(os.path.join(HERE, os.pardir, os.pardir, "examples", "slope_fos", "case.json"))
    case["grid.cells"] = [round(34 * a.cells_per_m), round(12 * a.cells_per_m)]
    # a bracket wide enough for every angle of the study, searched to 0.02
    case["analysis.strength_reduction"] = {"min": 0.6, "max": 2.6, "tolerance": 0.02}
    rows = []
    for phi in [float(x) for x in a.angles.split(",")]:
        case["materials[0].friction_angle"] = phi
        t0 = time.time()
        fos, lo, hi = case.factor_of_safety(threads=a.threads)
        rows.append((phi, fos, lo, hi, time.time() - t0))
        print("friction angle %4.1f deg: factor of safety %.3f (holds at %.3f, fails at %.3f), %.0f s" % rows[-1])
    with open(os.path.join(a.out, "fos_vs_friction.csv"), "w") as f:
        f.write("friction_angle,fos,holds,fails,seconds\n")
        for r in rows:
            f.write("%g,%.4f,%.4f,%.4f,%.1f\n" % r)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is missing: no plot (apt-get install python3-matplotlib)")
        return 0
    fig, ax = plt.subplots(figsize=(6, 4))
    phis = [r[0] for r in rows]
    ax.errorbar(phis, [r[1] for r in rows], yerr=[[r[1] - r[2] for r in rows], [r[3] - r[1] for r in rows]],
                marker="o", capsize=3, label="pmech, MPM, h = %.2g m" % (1 / a.cells_per_m))
    ax.axhline(1.0, color="grey", lw=0.8, ls="--")
    ax.set_xlabel("friction angle [deg]")
    ax.set_ylabel("factor of safety")
    ax.set_title("2:1 slope, H = 10 m, c' = 10 kPa")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    png = os.path.join(a.out, "fos_vs_friction.png")
    fig.savefig(png, dpi=100)
    print("wrote", png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
