#!/usr/bin/env python3
"""Figures of merit of the plane-strain extrusion, from the frames and forces.csv a run wrote (Python 3
standard library only).

    python3 analyse.py extrusion.out [time from which the extrusion is steady, default 0.4 ms]

Prints: the die's, container's and ram's axial forces averaged over 0.1 ms windows, and their means over
the steady part, against the slab-method estimate; the plastic strain across the extruded strip (beyond
the die exit) in bands of height, which shows the strain growing away from the axis."""
import csv, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, last_frame, read_vtu  # noqa: E402  (examples/frames.py)

SIGMA0, MU = 20e6, 0.1                  # von Mises yield stress (Pa), tool friction
H0, H1, ALPHA = 0.010, 0.005, math.radians(30.0)   # container and exit half-heights (m), die semi-angle
X_DIE, X_EXIT = 0.020, 0.030660254      # die entry, end of its land (m)


def slab():
    """Slab-method extrusion pressure through a wedge die (plane strain, Coulomb friction on the die,
    no redundant work): p = 2k (1 + B)/B (R^B - 1), B = mu cot(alpha); frictionless: 2k ln R."""
    k, R, B = SIGMA0 / math.sqrt(3), H0 / H1, MU / math.tan(ALPHA)
    return 2 * k * (1 + B) / B * (R ** B - 1), 2 * k * math.log(R)


def forces(d, t_steady):
    rows = list(csv.DictReader(open(os.path.join(d, "forces.csv"))))
    t = [float(r["time"]) for r in rows]
    if "die_x" in rows[0]:   # case_rectangle.json: die and container are obstacles
        cols = {"die": ["die_x"], "container": ["container_x"], "ram": ["ram_x"]}
    else:                    # case.json: friction conditions 1 (container), 2 and 3 (die face and land)
        cols = {"die": ["boundary_conditions2_x", "boundary_conditions3_x"],
                "container": ["boundary_conditions1_x"], "ram": ["ram_x"]}

    def fx(i, k):
        return sum(float(rows[i][c]) for c in cols[k])
    p_slab, p_ideal = slab()
    print("axial forces on the half model (kN/m; die and container: the force the material exerts on them, "
          "ram: the force it exerts on the material)")
    print("  slab method (friction %.2f, no redundant work): p H0 = %.1f kN/m; frictionless ideal work "
          "2k ln R H0 = %.1f kN/m" % (MU, p_slab * H0 / 1e3, p_ideal * H0 / 1e3))
    w, t0 = 1e-4, 0.0
    print("  window (ms)      die   container     ram   die/slab")
    while t0 < t[-1] - 1e-12:
        sel = [i for i in range(len(t)) if t0 < t[i] <= t0 + w + 1e-12]
        if sel:
            m = {k: -sum(fx(i, k) for i in sel) / len(sel) / 1e3 for k in cols}
            m["ram"] = -m["ram"]
            print("  %5.2f-%5.2f  %8.1f  %8.1f  %8.1f   %.3f" % (t0 * 1e3, (t0 + w) * 1e3, m["die"], m["container"],
                                                            m["ram"], m["die"] / (p_slab * H0 / 1e3)))
        t0 += w
    sel = [i for i in range(len(t)) if t[i] > t_steady]
    die = -sum(fx(i, "die") for i in sel) / len(sel)
    ram = sum(fx(i, "ram") for i in sel) / len(sel)
    print("  mean after %.2f ms: die %.1f kN/m = %.3f x slab, ram %.1f kN/m" % (t_steady * 1e3, die / 1e3,
                                                                             die / (p_slab * H0), ram / 1e3))


def strain_profile(d):
    t, path = last_frame(d)
    f = read_vtu(path)
    x, e = f["Points"], f["plastic_strain"]
    xs = [x[3 * i] for i in range(f["n"])]
    front = max(xs)
    lo, hi = X_EXIT + 0.001, front - 0.002     # the strip beyond the land, without its nose
    print("plastic strain across the extruded strip at t = %.2f ms (x from %.1f to %.1f mm), bands of y/h1:"
          % (t * 1e3, lo * 1e3, hi * 1e3))
    if hi <= lo:
        print("  the strip is too short yet")
        return
    # material that started in the container has passed the whole deformation zone; the strip's head
    # started inside the die and was deformed only in part
    u = f["displacement"]
    whole = [xs[i] - u[3 * i] < X_DIE for i in range(f["n"])]
    bands = [0.0, 0.2, 0.4, 0.6, 0.8, 1.2]
    print("  y/h1      all of the strip        from the container")
    for b in range(len(bands) - 1):
        band = [i for i in range(f["n"]) if lo <= xs[i] <= hi and bands[b] <= x[3 * i + 1] / H1 < bands[b + 1]]
        both = [[e[i] for i in band], [e[i] for i in band if whole[i]]]
        cells = ["%.3f (%3d points)" % (sum(v) / len(v), len(v)) if v else "      -         " for v in both]
        print("  %.1f-%.1f   %s    %s" % (bands[b], bands[b + 1], cells[0], cells[1]))
    print("  plane-strain homogeneous strain (2/sqrt 3) ln R = %.3f" % (2 / math.sqrt(3) * math.log(H0 / H1)))


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "extrusion.out"
    t_steady = float(sys.argv[2]) if len(sys.argv) > 2 else 4e-4
    forces(d, t_steady)
    strain_profile(d)


if __name__ == "__main__":
    main()
