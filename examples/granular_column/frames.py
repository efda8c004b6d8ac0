#!/usr/bin/env python3
"""The deposit's front and the point 0.1 L0 deep at every frame of runs study.py kept (--keep), to see
when a front comes to rest, or to read a long run's answer from its frames before it ends.

    python3 frames.py study.out/a0.5_h64:64 [DIR:CELLS ...]

DIR is a run's directory (holding out/particles.pvd), CELLS its cells per L0 (the front's gap is 2 h).
"""
import sys
from pathlib import Path

import study


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    for arg in sys.argv[1:]:
        d, cells = arg.rsplit(":", 1)
        h = 1.0 / int(cells)
        print(d)
        for t, f in study.frames(Path(d) / "out"):
            if f.exists():
                print("  t = %.3f s  front %.3f  0.1 L0 deep %.3f" %
                      (t, study.deposit(f, h)[0] - 1.0, study.thick_point(f, 0.1) - 1.0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
