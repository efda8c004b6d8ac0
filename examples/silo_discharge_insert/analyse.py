#!/usr/bin/env python3
"""Figures of merit of the silo discharge with the conical insert, from the frames and removals.csv a
run wrote (Python 3 standard library only).

    python3 analyse.py silo_discharge_insert.out [cell size, default 0.02 m]

Prints the discharge rate per 0.1 s window against Beverloo's law and the wall traction at rest (both
as examples/silo_discharge/analyse.py: the wall's own and the particles' next to it), and the flow class over windows of the discharge: for the
points at a height z at the window's start, how far they sink by its end, next to the wall (r > 0.9
m) against on the axis (r < 0.1 m), and the share of the cross-section that sinks by more than a
tenth of the axis's drop. A time average: the instantaneous velocities of the viscoplastic continuum
are noisy. Mass flow: ratio near 1, share 1; funnel flow: both small. Runs without the insert work too.
"""
import os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from frames import read_vtu as read_vtu_ids  # noqa: E402  (examples/frames.py reads the integer arrays too: id)
sys.path[0] = os.path.join(HERE, "..", "silo_discharge")
from analyse import T_OPEN, R, discharge_rate, frames, wall_traction  # noqa: E402

WINDOWS = ((0.25, 0.8), (0.8, 1.4), (1.4, 2.0))
HEIGHTS = (1.0, 2.0, 2.5)


def flow_class(a, b, z, h):
    start = {}
    for i in range(a["n"]):
        y = a["Points"][3 * i + 1]
        if abs(y - z) < h:
            start[a["id"][i]] = (a["Points"][3 * i], y, a["volume"][i])
    end = {b["id"][i]: b["Points"][3 * i + 1] for i in range(b["n"])}
    rows = [(r, y - end.get(k, 0.0), v) for k, (r, y, v) in start.items()]   # removed: dropped to the floor
    axis = [d for r, d, _ in rows if r < 0.1]
    wall = [d for r, d, _ in rows if r > R - 0.1]
    if not axis or not wall:
        return None
    da, dw = sum(axis) / len(axis), sum(wall) / len(wall)
    total = sum(v for _, _, v in rows)
    moving = sum(v for _, d, v in rows if d > 0.1 * da)
    return da, dw, dw / da if da > 0 else float("nan"), moving / total


def main():
    d = sys.argv[1]
    h = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02
    fr = {round(t - T_OPEN, 3): p for t, p in frames(d)}
    discharge_rate(d)
    if 0.0 in fr:
        wall_traction(d, read_vtu_ids(fr[0.0]), T_OPEN, "at rest, at the opening", h)
    print("flow class: drop over a window of the points at height z at its start (m); wall/axis; "
          "share of the section sinking")
    for t0, t1 in WINDOWS:
        if t0 not in fr or t1 not in fr:
            continue
        a, b = read_vtu_ids(fr[t0]), read_vtu_ids(fr[t1])
        for z in HEIGHTS:
            c = flow_class(a, b, z, max(h, 0.025))
            if c:
                print("  %.2f-%.2f s, z = %.1f m: axis %.3f, wall %.3f, wall/axis %.2f, share %.2f" %
                      ((t0, t1, z) + c))


if __name__ == "__main__":
    main()
