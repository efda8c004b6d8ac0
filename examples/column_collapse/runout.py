#!/usr/bin/env python3
"""Run-out and height at the wall of the column in every frame of a pmech output directory.

    python3 runout.py column_collapse.out [times...]

Reads particles.pvd and the frames' appended raw VTU data (the format pmech writes); prints
t, run-out (largest x of the soil) and height at the wall (largest y of the points within 0.1 m of
x = 0), the figures of the README's tables. With times, only the frames nearest to them.
"""
import re
import struct
import sys
from pathlib import Path


def points(vtu):
    data = vtu.read_bytes()
    head, _, tail = data.partition(b'<AppendedData encoding="raw">')
    n = int(re.search(rb'NumberOfPoints="(\d+)"', head).group(1))
    off = int(re.search(rb'Name="Points"[^>]*offset="(\d+)"', head).group(1))
    raw = tail[tail.index(b"_") + 1:]
    size = struct.unpack_from("<Q", raw, off)[0]
    xyz = struct.unpack_from("<%dd" % (size // 8), raw, off + 8)
    return [(xyz[3 * i], xyz[3 * i + 1]) for i in range(n)]


def main():
    out = Path(sys.argv[1])
    frames = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', (out / "particles.pvd").read_text())
    frames = [(float(t), f) for t, f in frames]
    wanted = [float(a) for a in sys.argv[2:]]
    if wanted:
        frames = [min(frames, key=lambda fr: abs(fr[0] - w)) for w in wanted]
    print("t_s,runout_m,height_at_wall_m")
    for t, f in frames:
        p = points(out / f)
        runout = max(x for x, _ in p)
        height = max((y for x, y in p if x < 0.1), default=float("nan"))
        print("%.4g,%.4f,%.4f" % (t, runout, height))


if __name__ == "__main__":
    main()
