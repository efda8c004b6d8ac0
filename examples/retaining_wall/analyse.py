#!/usr/bin/env python3
"""Figures of merit of the retaining-wall failure, from the frames and probes.csv a run wrote (Python 3
standard library only).

    python3 analyse.py retaining_wall.out [cell size, default 0.125 m]

The wall is held until T_RELEASE = 1 s (gravity ramps up over that second); times below are counted
from the release. Prints, per frame: the wall's rotation (from the probes on its axis at the top and
just above the cracked base), the run-out (how far the stored material's front has moved out past the
wall's original outer face, x = 3.0 m) and the shear band behind the wall: in each 0.2 m row of the
stored material's initial positions, the farthest point from the wall whose displacement is at least
half that of the material next to the wall in the same row; a line fitted through those points from
the wall's heel gives the band's angle with the horizontal, against Rankine's 45 + phi/2."""
import csv, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, last_frame, read_vtu  # noqa: E402  (examples/frames.py)

T_RELEASE = 1.0
WALL_FACE, WALL_BACK, BASE_Y, TOP_Y = 3.0, 3.5, 1.0, 4.0
PHI_STORED = 30.0
STORED_BODY = 3                       # bodies: soil, wall_base, wall, stored


def rotation(d):
    """(time, wall rotation in degrees, positive outward, i.e. the top moving towards -x, and the
    top's outward displacement in m) over time."""
    out, x0 = [], None
    for r in csv.DictReader(open(os.path.join(d, "probes.csv"))):
        dx = float(r["wall_top.x"]) - float(r["wall_foot.x"])
        dy = float(r["wall_top.y"]) - float(r["wall_foot.y"])
        x0 = float(r["wall_top.x"]) if x0 is None else x0
        out.append((float(r["time"]), math.degrees(math.atan2(-dx, dy)), x0 - float(r["wall_top.x"])))
    return out


def shear_band(f, h):
    """(angle of the band in degrees from the horizontal, [(x, y) of the band per row]) or None."""
    x, u, body = f["Points"], f["displacement"], f["body"]
    rows = {}
    for i in range(f["n"]):
        if body[i] != STORED_BODY:
            continue
        x0, y0 = x[3 * i] - u[3 * i], x[3 * i + 1] - u[3 * i + 1]
        k = int((y0 - BASE_Y) / 0.2)
        rows.setdefault(k, []).append((x0, math.hypot(u[3 * i], u[3 * i + 1])))
    pts = []
    for k in sorted(rows):
        y = BASE_Y + 0.2 * (k + 0.5)
        if y > TOP_Y - 0.2:
            continue
        row = sorted(rows[k])
        near = [s for x0, s in row if x0 < WALL_BACK + 1.5 * h]
        if not near:
            continue
        ref = sum(near) / len(near)
        if ref < 0.05:
            continue
        far = max(x0 for x0, s in row if s >= 0.5 * ref)
        pts.append((far, y))
    if len(pts) < 3:
        return None
    # least squares through the heel (WALL_BACK, BASE_Y): x - xh = (y - yh) / tan(angle)
    num = sum((x0 - WALL_BACK) * (y - BASE_Y) for x0, y in pts)
    den = sum((y - BASE_Y) ** 2 for _, y in pts)
    cot = num / den
    return math.degrees(math.atan2(1.0, cot)), pts


def run_out(f):
    """How far the stored material's front has gone past the wall's original outer face (m)."""
    x, body = f["Points"], f["body"]
    front = min(x[3 * i] for i in range(f["n"]) if body[i] == STORED_BODY)
    return max(0.0, WALL_FACE - front)


def main():
    d = sys.argv[1]
    h = float(sys.argv[2]) if len(sys.argv) > 2 else 0.125
    rot = rotation(d)
    print("Rankine active wedge: 45 + phi/2 = %.1f degrees from the horizontal (phi = %g)" %
          (45 + PHI_STORED / 2, PHI_STORED))
    print("t after release (s) | wall rotation (deg) | wall top moved out (m) | run-out (m) | band angle (deg) | "
          "band top x (m)")
    for t, p in frames(d):
        tt = t - T_RELEASE
        if tt < -1e-9:
            continue
        f = read_vtu(p)
        r = min(rot, key=lambda a: abs(a[0] - t))
        band = shear_band(f, h)
        ang = "%.1f" % band[0] if band else "-"
        top = "%.2f" % max(band[1], key=lambda a: a[1])[0] if band else "-"
        print("%6.2f | %6.2f | %5.2f | %5.2f | %s | %s" % (tt, r[1], r[2], run_out(f), ang, top))


if __name__ == "__main__":
    main()
