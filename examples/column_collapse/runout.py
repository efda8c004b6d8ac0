#!/usr/bin/env python3
"""Run-out and height at the wall of the column in every frame of a pmech output directory.

    python3 runout.py column_collapse.out [times...]

Reads particles.pvd and its frames through examples/frames.py; prints
t, run-out (largest x of the soil) and height at the wall (largest y of the points within 0.1 m of
x = 0), the figures of the README's tables. With times, only the frames nearest to them.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames as run_frames, read_vtu  # noqa: E402


def points(vtu):
    v = read_vtu(vtu)
    xyz = v["Points"]
    return [(xyz[3 * i], xyz[3 * i + 1]) for i in range(v["n"])]


def main():
    frames = run_frames(sys.argv[1])
    wanted = [float(a) for a in sys.argv[2:]]
    if wanted:
        frames = [min(frames, key=lambda fr: abs(fr[0] - w)) for w in wanted]
    print("t_s,runout_m,height_at_wall_m")
    for t, f in frames:
        p = points(f)
        runout = max(x for x, _ in p)
        height = max((y for x, y in p if x < 0.1), default=float("nan"))
        print("%.4g,%.4f,%.4f" % (t, runout, height))


if __name__ == "__main__":
    main()
