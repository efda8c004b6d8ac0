#!/usr/bin/env python3
"""Run-out study of planar cohesionless column collapses against the laws of Lube et al. (2005).

    python3 study.py PMECH [--aspect 0.5,1,2,4,8] [--cells 10,20] [--cells-y 32] [--flip 1.0] [--fbar]
                     [--transfer apic|xpic] [--xpic-order 5] [--material '{"key": value}']
                     [--floor fixed|coulomb] [--floor-mu 0.577] [--floor-offset 0.5] [--end-time 0.6]
                     [--interval 0.03] [--jobs 2] [--keep]

For every aspect ratio a = H / L0 and mesh (cells per column width L0 = 1 m) it writes a case from
case.json (the column, the grid and the end time scaled with a), runs it with one thread, and
measures the final deposit from the last frame: the front (the particles' x sorted, up to the first
gap wider than 2 h), the farthest particle, the height at the wall (largest y within h of it), the
largest volume ratio V / V0, the deposit's volume over the column's, the front's advance over the last 10 % of the run, and two measures
of the deposit's body that converge where the front does not: where the deposit is 0.1 L0 deep and
how far the centre of mass moved. Prints one markdown row per run and writes study.csv. The frames
are read through examples/frames.py.

The floor is the case's fixed one (its nodes held in x and y) or, with --floor coulomb, a Coulomb
interface of zero thickness at y = 0 that acts at the particles touching it: a `friction` condition on
the grid's bottom side when --floor-offset is 0, otherwise a polyline obstacle with acts_at
"particles" that lies that fraction of a cell above a grid line (the grid then reaches a cell and the
offset below the floor, so that the floor cuts through cells as it would in a mesh not fitted to it).

Laws (planar collapses, experiments with sand, sugar, rice and glass beads): (L_f - L0) / L0 =
1.2 a for a < 2.3 and 1.9 a^(2/3) above; H_f / L0 = a for a < 1.15 and a^(2/5) above.
"""
import argparse
import concurrent.futures
import copy
import json
import math
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from frames import frames, read_vtu  # noqa: E402


def law_runout(a):
    return 1.2 * a if a < 2.3 else 1.9 * a ** (2.0 / 3.0)


def law_height(a):
    return a if a < 1.15 else a ** 0.4


def deposit(vtu, h):
    a = read_vtu(vtu)
    n, pts = a["n"], a["Points"]
    xs = sorted(pts[3 * i] for i in range(n))
    front = xs[0]
    for x in xs[1:]:
        if x - front > 2 * h:
            break
        front = x
    height = max(pts[3 * i + 1] for i in range(n) if pts[3 * i] < h)
    return front, xs[-1], height, a


def thick_point(vtu, thickness):
    """The largest x at which the deposit is at least `thickness` deep: the particles as the boxes of
    their half sizes, the right edge of the farthest box whose top is that high. Unlike the front it
    does not follow a tail thinner than a cell or two, which every refinement resolves further."""
    a = read_vtu(vtu)
    n, pts, hs = a["n"], a["Points"], a["half_size"]
    k = len(hs) // n
    best = 0.0
    for i in range(n):
        if pts[3 * i + 1] + hs[k * i + 1] >= thickness:
            best = max(best, pts[3 * i] + hs[k * i])
    return best


def centre_x(vtu):
    a = read_vtu(vtu)
    n, m, pts = a["n"], a["mass"], a["Points"]
    return sum(m[i] * pts[3 * i] for i in range(n)) / sum(m)


def coulomb_floor(c, mu, offset, h, hy):
    """Replace the fixed floor by a Coulomb interface at y = 0 (see the module's text); returns how far
    the grid reaches below the floor."""
    c["boundary_conditions"] = [b for b in c["boundary_conditions"] if b["boundary"] != "y_min"]
    if offset == 0:
        c["boundary_conditions"].append({"type": "friction", "boundary": "y_min", "coefficient": mu})
        return 0.0
    below = (1.0 + offset) * hy
    width = c["grid"]["size"][0]
    c["obstacles"] = [{"name": "floor", "type": "polyline", "points": [[-h, 0.0], [width + h, 0.0]],
                       "material_side": "left", "friction": mu, "acts_at": "particles"}]
    return below


def make_case(base, a, cells, flip, fbar=False, transfer=None, material=None, cells_y=None, xpic_order=None,
              floor=None, end_time=None, interval=None):
    c = copy.deepcopy(base)
    if fbar:
        c["analysis"]["fbar"] = "cell"
    if transfer:
        c["analysis"]["transfer"] = transfer
    if xpic_order:
        c["analysis"]["xpic_order"] = xpic_order
    if material:
        mat = c["materials"][0]
        if "model" in material and material["model"] != mat["model"]:
            # another model takes only the keys every model shares; its own come from `material`
            mat = {k: mat[k] for k in ("name", "density", "youngs_modulus", "poisson_ratio")}
            c["materials"][0] = mat
        mat.update(material)
    L0, h = 1.0, 1.0 / cells
    hy = 1.0 / cells_y if cells_y else h
    H = a * L0
    reach = law_runout(a) + 1.0
    width = max(1.6 * reach + 0.5, 3.0)
    height = H + 0.5
    c["title"] = "granular column a = %g, h = L0/%d" % (a, cells) + (", h_y = L0/%d" % cells_y if cells_y else "")
    c["grid"]["cells"] = [math.ceil(width / h), math.ceil(height / hy)]
    c["grid"]["size"] = [c["grid"]["cells"][0] * h, c["grid"]["cells"][1] * hy]
    if floor:
        below = coulomb_floor(c, floor[0], floor[1], h, hy)
        if below > 0:
            c["grid"]["origin"] = [0.0, -below]
            c["grid"]["cells"][1] = math.ceil((height + below) / hy)
            c["grid"]["size"][1] = c["grid"]["cells"][1] * hy
    body = c["bodies"][0]
    body["shape"]["max"] = [L0, H]
    body["surface_y"] = H
    # free fall of the column's top plus the spreading of the deposit, with a margin to come to rest
    c["analysis"]["end_time"] = end_time or round(3.0 * math.sqrt(H / 9.81) + 1.5 * math.sqrt(reach / 9.81) + 0.5, 3)
    if flip is not None:
        c["analysis"]["flip"] = flip
    c["output"] = {"directory": "out", "interval": interval or round(c["analysis"]["end_time"] / 20, 4)}
    c.pop("probes", None)
    return c


def run_one(pmech, work, a, cells, flip, keep, fbar=False, transfer=None, material=None, cells_y=None,
            xpic_order=None, floor=None, end_time=None, interval=None):
    name = "a%g_h%d%s%s%s%s%s" % (a, cells, "_y%d" % cells_y if cells_y else "", "_fbar" if fbar else "",
                                  "_" + transfer if transfer else "", "%d" % xpic_order if xpic_order else "",
                                  "_mu%g_off%g" % floor if floor else "")
    d = work / name
    d.mkdir(parents=True, exist_ok=True)
    base = json.loads((HERE / "case.json").read_text())
    case = make_case(base, a, cells, flip, fbar, transfer, material, cells_y, xpic_order, floor, end_time, interval)
    (d / "case.json").write_text(json.dumps(case, indent=1))
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    t0 = time.time()
    proc = subprocess.run([pmech, "run", "case.json", "--threads", "1", "--quiet"], cwd=d, env=env,
                          capture_output=True, text=True)
    secs = time.time() - t0
    h = 1.0 / cells
    fr = frames(d / "out")
    t_end, last = fr[-1]
    front, xmax, hw, arr = deposit(last, h)
    t_before, before = min(fr, key=lambda f: abs(f[0] - 0.9 * t_end))
    front_before = deposit(before, h)[0]
    body = thick_point(last, 0.1) - 1.0
    dx_cm = centre_x(last) - centre_x(fr[0][1])
    vol, v0 = arr.get("volume"), (h * (1.0 / cells_y if cells_y else h)) / 4
    jmax = max(vol) / v0 if vol else float("nan")
    vdep = sum(vol) / (a * 1.0 * 1.0) if vol else float("nan")
    row = dict(a=a, cells=cells, cells_y=cells_y or cells, t_end=t_end, end_time=case["analysis"]["end_time"], ok=proc.returncode == 0,
               runout=front - 1.0, law_runout=law_runout(a), body=body, dx_cm=dx_cm, height=hw,
               law_height=law_height(a),
               stray=xmax / front, creep=front - front_before, jmax=jmax, vdep=vdep, seconds=secs,
               message=(proc.stderr.strip().splitlines() or ["exit %d" % proc.returncode])[-1] if proc.returncode else "")
    if not keep:
        shutil.rmtree(d / "out", ignore_errors=True)
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("pmech")
    ap.add_argument("--aspect", default="0.5,1,2,4,8")
    ap.add_argument("--cells", default="10,20")
    ap.add_argument("--cells-y", type=int, default=None,
                    help="cells per L0 vertically (flat cells); default: as --cells")
    ap.add_argument("--flip", type=float, default=None)
    ap.add_argument("--fbar", action="store_true", help="analysis.fbar = cell")
    ap.add_argument("--transfer", default=None, help="analysis.transfer (flip, apic or xpic)")
    ap.add_argument("--xpic-order", type=int, default=None, help="analysis.xpic_order (with --transfer xpic)")
    ap.add_argument("--material", default=None,
                    help="JSON object of material keys to set; with a \"model\" other than the case's, the "
                         "case's model keys are dropped (density and the elastic pair kept), e.g. "
                         "'{\"model\": \"viscoplastic_drucker_prager\", \"friction_angle\": 25.11, "
                         "\"viscosity\": 820}'")
    ap.add_argument("--end-time", type=float, default=None,
                    help="analysis.end_time (s); default: the fall and spreading times of the column, scaled "
                         "with a (a shorter run measures the failure, not the deposit)")
    ap.add_argument("--interval", type=float, default=None,
                    help="output interval (s); default: a twentieth of the end time (band.py wants finer frames)")
    ap.add_argument("--floor", default="fixed", choices=["fixed", "coulomb"],
                    help="fixed: the case's floor, its nodes held; coulomb: a zero-thickness Coulomb interface "
                         "acting at the particles that touch it")
    ap.add_argument("--floor-mu", type=float, default=None,
                    help="the Coulomb floor's coefficient (default: tan of the material's friction angle)")
    ap.add_argument("--floor-offset", type=float, default=0.0,
                    help="the Coulomb floor's height above the grid line below it, in cells, in [0, 1): 0 puts "
                         "it on the grid's bottom side (a friction condition), more inside a cell (an obstacle)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--work", default="study.out")
    ap.add_argument("--keep", action="store_true")
    o = ap.parse_args()
    pmech = str(Path(o.pmech).resolve())
    floor = None
    if o.floor == "coulomb":
        if not 0.0 <= o.floor_offset < 1.0:
            ap.error("--floor-offset %g: allowed [0, 1)" % o.floor_offset)
        mu = o.floor_mu
        if mu is None:
            phi = json.loads(o.material or "{}").get("friction_angle")
            if phi is None:
                phi = json.loads((HERE / "case.json").read_text())["materials"][0]["friction_angle"]
            mu = math.tan(math.radians(phi))
        if mu < 0:
            ap.error("--floor-mu %g: allowed >= 0" % mu)
        floor = (mu, o.floor_offset)
    work = Path(o.work).resolve()
    runs = [(float(a), int(n)) for n in o.cells.split(",") for a in o.aspect.split(",")]
    rows = []
    with concurrent.futures.ThreadPoolExecutor(o.jobs) as ex:
        futs = [ex.submit(run_one, pmech, work, a, n, o.flip, o.keep, o.fbar, o.transfer,
                          json.loads(o.material) if o.material else None, o.cells_y, o.xpic_order, floor,
                          o.end_time, o.interval)
                for a, n in runs]
        for f in concurrent.futures.as_completed(futs):
            r = f.result()
            rows.append(r)
            print("a = %g, L0/h = %d, L0/h_y = %d: run-out %.3f (law %.3f, %+.1f %%), 0.1 L0 deep at %.3f, centre of mass "
                  "moved %.3f m, V/V0 %.3f, height %.3f (law %.3f, %+.1f %%), farthest/front %.3f, creep %.3f, "
                  "J max %.1f, %s, %.0f s" %
                  (r["a"], r["cells"], r["cells_y"], r["runout"], r["law_runout"], 100 * (r["runout"] / r["law_runout"] - 1),
                   r["body"], r["dx_cm"], r["vdep"],
                   r["height"], r["law_height"], 100 * (r["height"] / r["law_height"] - 1), r["stray"], r["creep"],
                   r["jmax"], "finished" if r["ok"] else "STOPPED: " + r["message"], r["seconds"]), flush=True)
    rows.sort(key=lambda r: (r["a"], r["cells"]))
    keys = list(rows[0].keys())
    with open(work / "study.csv", "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(str(r[k]) for k in keys) + "\n")
    print("| a | L0/h | (L_f - L0)/L0 | law | error | 0.1 L0 deep | centre moved | H_f/L0 | law | error | "
          "farthest/front | finished |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %g | %d | %.2f | %.2f | %+.0f %% | %.3f | %.3f | %.2f | %.2f | %+.0f %% | %.2f | %s |" %
              (r["a"], r["cells"], r["runout"], r["law_runout"], 100 * (r["runout"] / r["law_runout"] - 1),
               r["body"], r["dx_cm"],
               r["height"], r["law_height"], 100 * (r["height"] / r["law_height"] - 1), r["stray"],
               "yes" if r["ok"] else "no"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
