#!/usr/bin/env python3
"""Surface profiles of finished column-collapse runs: the highest point of the soil in each 0.2 m strip
from x = 1.6 m (0.1 m strips from 1.4 m with --fine), in the last frame of each run directory.

    python3 surface.py [--fine] column_collapse.out column_collapse_gmm_lme.out ...
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, read_vtu  # noqa: E402


def main():
    args = sys.argv[1:]
    fine = "--fine" in args
    dirs = [a for a in args if a != "--fine"]
    x0, w, nb = (1.4, 0.1, 12) if fine else (1.6, 0.2, 15)
    print("x (m)          " + " ".join("%5.2f" % (x0 + w * (k + 0.5)) for k in range(nb)))
    for d in dirs:
        t, path = frames(d)[-1]
        v = read_vtu(path)
        pts, n = v["Points"], v["n"]
        top = [float("nan")] * nb
        for i in range(n):
            k = int((pts[3 * i] - x0) / w)
            if 0 <= k < nb and not top[k] >= pts[3 * i + 1]:
                top[k] = pts[3 * i + 1]
        print("%-14s " % os.path.basename(d.rstrip("/"))[:14] + " ".join("%5.2f" % h for h in top) + "   t = %.2f s" % t)


if __name__ == "__main__":
    main()
