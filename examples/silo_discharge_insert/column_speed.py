"""The points on the axis above the insert's apex: how fast they sink (from their positions), against
their own speed (`velocity`, FLIP's) and the speed their positions moved with (`grid_velocity`, what the
`grid_speed` pictures draw), and the same for their neighbours a little off the axis.

    python3 examples/silo_discharge_insert/column_speed.py silo_discharge_insert_rectangle.out

For each 0.25 s window after the opening (t = 1 s): the points with r below 10 mm (the column) or
r = 10-100 mm (the neighbours) and z = 1.8-2.6 m at the window's start, followed by their ids to its
end; their mean downward speed over the window from the two positions, and the mean of their speed and
grid speed over every frame of the window (both ends included). Standard library only.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, read_vtu  # noqa: E402

OPENING = 1.0
WINDOWS = [(0.0, 0.25), (0.25, 0.5), (0.5, 0.75), (0.75, 1.0), (1.0, 1.25), (1.25, 1.5), (1.5, 1.75),
           (1.75, 2.0)]
BANDS = [("column, r < 10 mm", 0.0, 0.01), ("neighbours, r = 10-100 mm", 0.01, 0.1)]


def by_id(f):
    """{id: (r, z, speed, grid speed)} of a frame read by read_vtu."""
    out = {}
    x, v, vg, ids = f["Points"], f["velocity"], f["grid_velocity"], f["id"]
    for i in range(f["n"]):
        out[ids[i]] = (x[3 * i], x[3 * i + 1], math.hypot(v[3 * i], v[3 * i + 1]),
                       math.hypot(vg[3 * i], vg[3 * i + 1]))
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    fr = frames(sys.argv[1])
    cache = {}

    def frame(k):
        if k not in cache:
            cache[k] = by_id(read_vtu(fr[k][1]))
        return cache[k]

    def index_at(t):
        return min(range(len(fr)), key=lambda k: abs(fr[k][0] - t))

    print("| window after the opening (s) | points | sink speed from positions (m/s) | own speed (m/s) "
          "| grid speed (m/s) |")
    print("|---|---|---|---|---|")
    for w0, w1 in WINDOWS:
        k0, k1 = index_at(OPENING + w0), index_at(OPENING + w1)
        if abs(fr[k1][0] - (OPENING + w1)) > 0.01 or k1 <= k0:
            continue
        dt = fr[k1][0] - fr[k0][0]
        start = frame(k0)
        for name, r0, r1 in BANDS:
            ids = [i for i, (r, z, _, _) in start.items() if r0 <= r < r1 and 1.8 <= z <= 2.6]
            ids = [i for i in ids if i in frame(k1)]
            if not ids:
                continue
            sink = sum(start[i][1] - frame(k1)[i][1] for i in ids) / len(ids) / dt
            own, grid, cnt = 0.0, 0.0, 0
            for k in range(k0, k1 + 1):
                f = frame(k)
                for i in ids:
                    if i in f:
                        own += f[i][2]
                        grid += f[i][3]
                        cnt += 1
            print("| %.2f-%.2f, %s | %d | %.3f | %.3f | %.3f |" % (w0, w1, name, len(ids), sink, own / cnt, grid / cnt))


if __name__ == "__main__":
    main()
