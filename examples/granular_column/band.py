#!/usr/bin/env python3
"""How wide the failing column's shear zones are, from a run's particle frames.

    python3 band.py RUN_OUT_DIR [RUN_OUT_DIR ...] [--t0 0.15] [--t1 0.5] [--rows 0.1,0.2,0.3]

Each RUN_OUT_DIR is a run's output directory (the one holding particles.pvd, e.g. study.py's
`a0.5_h16/out` kept with --keep); the cell size is read from the case.json beside it. For every pair
of consecutive frames whose middle lies in [t0, t1] it takes each particle's plastic strain increment
(matched by id) and its plastic dissipation rate q d(eps_p)/dt V (q from the later frame, so
stress-free points at the apex, which collect plastic strain without carrying stress, do not count),
sums the rates over the grid's cells (see `cells`) and reports, per pair:

- w_half: the smallest area of cells that carries half the total dissipation rate, divided by the
  length of the main failure surface (taken as H / sin 60 deg, from the floor to the column's top at
  the active-wedge angle 45 + phi/2 of phi = 30 deg), then by h. A zone whose width scales with h
  gives the same w_half on every mesh; a zone of a fixed physical width gives w_half doubling with
  every halving of h.
- fwhm: along the row of cells at each given height (y / H), the width in x over which the
  dissipation rate per area stays above half its peak, around the peak (linear between cell
  centres, so a zone of one cell shows as 1), divided by h. A horizontal cut: the zone's normal
  width is this times the sine of its inclination.
- the share of the dissipation in the lowest row of cells (the basal layer) and the total
  dissipation rate (W per metre of depth), which a well-posed problem would give the same on every
  fine enough mesh.

At the end, one line per run: the mean dissipation rate, the medians of w_half and of every cut's
fwhm over the pairs, in h and in L0, and how many points are stress-free (p <= 0: the cohesionless
models' apex) and what share of the plastic strain rate they carry: a rate term that scales with the
pressure, as Perzyna's overstress m p (d eps_p/dt)/gamma and mu(I)'s do, cannot act there.
"""
import argparse
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from frames import frames, read_vtu  # noqa: E402


def cell_size(out_dir):
    case = json.load(open(os.path.join(out_dir, "..", "case.json")))
    g = case["grid"]
    hx = g["size"][0] / g["cells"][0]
    hy = g["size"][1] / g["cells"][1]
    H = case["bodies"][0]["shape"]["max"][1]
    return hx, hy, H


def pair_rates(f0, f1, dt):
    """[(x, y, V, dissipation rate per volume)] of the particles of both frames, and the stress-free
    points' (p <= 0) share of the points and of the sum of V d(eps_p)/dt."""
    a, b = read_vtu(f0), read_vtu(f1)
    eps0 = {a["id"][i]: a["plastic_strain"][i] for i in range(a["n"])}
    out = []
    free_n, flow, free_flow = 0, 0.0, 0.0
    for i in range(b["n"]):
        e0 = eps0.get(b["id"][i])
        if e0 is None:
            continue
        rate = (b["plastic_strain"][i] - e0) / dt
        v = b["volume"][i]
        out.append((b["Points"][3 * i], b["Points"][3 * i + 1], v, b["q"][i] * rate))
        flow += rate * v
        if b["pressure"][i] <= 0:
            free_n += 1
            free_flow += rate * v
    return out, free_n / max(len(out), 1), free_flow / flow if flow > 0 else float("nan")


def cells(parts, hx, hy):
    """The dissipation binned to the grid's cells: {(i, j): (x, y, area, rate per area)}. One point's
    rate alternates with its neighbours' (the return mapping of noisy FLIP velocities), so only a cell's
    sum is a field the grid can carry; a zone one cell wide then shows as one cell, not as a point."""
    acc = {}
    for x, y, v, d in parts:
        k = (math.floor(x / hx), math.floor(y / hy))
        acc[k] = acc.get(k, 0.0) + d * v
    return {k: ((k[0] + 0.5) * hx, (k[1] + 0.5) * hy, hx * hy, w / (hx * hy)) for k, w in acc.items()}


def w_half(grid, length):
    total = sum(c[3] * c[2] for c in grid.values())
    if total <= 0:
        return float("nan"), total
    acc, area = 0.0, 0.0
    for c in sorted(grid.values(), key=lambda c: -c[3]):
        acc += c[3] * c[2]
        area += c[2]
        if acc >= 0.5 * total:
            break
    return area / length, total


def fwhm(grid, y0, hy):
    j = math.floor(y0 / hy)
    row = sorted((c[0], c[3]) for k, c in grid.items() if k[1] == j)
    if len(row) < 3:
        return float("nan")
    k = max(range(len(row)), key=lambda i: row[i][1])
    peak = row[k][1]
    if peak <= 0:
        return float("nan")
    half = 0.5 * peak

    def edge(step):
        i = k
        while 0 <= i + step < len(row) and row[i + step][1] >= half:
            i += step
        j = i + step
        if not 0 <= j < len(row):
            return row[i][0]
        # linear interpolation between the last point above half the peak and the first below
        (x1, d1), (x2, d2) = row[i], row[j]
        return x1 + (x2 - x1) * (d1 - half) / (d1 - d2) if d1 != d2 else x1

    return edge(1) - edge(-1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", help="run output directories (holding particles.pvd)")
    ap.add_argument("--t0", type=float, default=0.15, help="first pair's middle at or after t0 (s)")
    ap.add_argument("--t1", type=float, default=0.5, help="last pair's middle at or before t1 (s)")
    ap.add_argument("--rows", default="0.1,0.2,0.3", help="heights of the horizontal cuts, y / H")
    o = ap.parse_args()
    rows = [float(r) for r in o.rows.split(",")]
    print("| run | h | t (s) | dissipation (W/m) | lowest cells' share | w_half / h | " +
          " | ".join("fwhm / h at y = %g H" % r for r in rows) + " |")
    print("|---|---:|---:|---:|---:|---:|" + "---:|" * len(rows))
    summary = []
    for d in o.runs:
        hx, hy, H = cell_size(d)
        totals, widths, cut_all, frees, free_flows = [], [], [], [], []
        h = math.sqrt(hx * hy)
        length = H / math.sin(math.radians(60.0))
        fr = frames(d)
        for (t0, f0), (t1, f1) in zip(fr, fr[1:]):
            tm = 0.5 * (t0 + t1)
            if not (o.t0 <= tm <= o.t1) or t1 <= t0:
                continue
            parts, free, free_flow = pair_rates(f0, f1, t1 - t0)
            frees.append(free)
            free_flows.append(free_flow)
            grid = cells(parts, hx, hy)
            w, total = w_half(grid, length)
            base = sum(c[3] * c[2] for k, c in grid.items() if k[1] == 0) / total if total > 0 else float("nan")
            cuts = [fwhm(grid, r * H, hy) / hx for r in rows]
            totals.append(total)
            widths.append(w / h)
            cut_all += [c for c in cuts if c == c]
            print("| %s | L0/%.0f | %.3f | %.1f | %.2f | %.2f | %s |" %
                  (os.path.basename(os.path.dirname(os.path.abspath(d))), 1.0 / hx, tm, total, base, w / h,
                   " | ".join("%.1f" % c for c in cuts)))
        summary.append((os.path.basename(os.path.dirname(os.path.abspath(d))), hx, len(totals),
                        sum(totals) / max(len(totals), 1), median(widths), median(cut_all),
                        sum(frees) / max(len(frees), 1), sum(free_flows) / max(len(free_flows), 1)))
    print("\nOver the pairs in [t0, t1]: mean dissipation, medians of w_half / h and of every cut's fwhm / h "
          "(and the same in L0), the mean share of stress-free points (p <= 0) and their mean share of the "
          "plastic strain rate (V d(eps_p)/dt summed)\n")
    print("| run | h | pairs | mean dissipation (W/m) | w_half / h | w_half / L0 | fwhm / h | fwhm / L0 | "
          "stress-free points | their share of the plastic flow |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, hx, n, tot, w, c, fr_, ff in summary:
        print("| %s | L0/%.0f | %d | %.0f | %.2f | %.3f | %.1f | %.3f | %.2f | %.2f |" %
              (name, 1.0 / hx, n, tot, w, w * hx, c, c * hx, fr_, ff))
    return 0


def median(v):
    v = sorted(v)
    if not v:
        return float("nan")
    k = len(v) // 2
    return v[k] if len(v) % 2 else 0.5 * (v[k - 1] + v[k])


if __name__ == "__main__":
    sys.exit(main())
