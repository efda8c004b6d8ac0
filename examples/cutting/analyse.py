#!/usr/bin/env python3
"""Figures of merit of the orthogonal cutting example, from the frames and forces.csv a run wrote
(Python 3 standard library only).

    python3 analyse.py cutting.out [time from which the cut is steady, default 0.3 ms] [cell size, 0.5 mm]

Prints: the cutting force (along the cut) and the thrust force (across it) averaged over 0.1 ms windows
and over the steady part, against Merchant's shear-plane estimate; the roughness of the cut surface in
the last frame (RMS deviation of the top points of the workpiece behind the tool from a fitted line)."""
import csv, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, last_frame, read_vtu  # noqa: E402  (examples/frames.py)

SIGMA0, MU = 50e6, 0.1                   # von Mises yield stress (Pa), tool friction
DEPTH, RAKE = 0.002, math.radians(10.0)  # depth of cut (m), rake angle
X_TIP0, Y_TIP = 0.0405, 0.008            # tool tip at t = 0 (m)
V_TOOL, T_RAMP = -10.0, 5e-5             # tool speed (m/s) reached over T_RAMP
PLATE_END = 0.040                        # the plate's right end (m), where the cut starts
TOP = 0.010                              # the plate's top (m)
H = 0.0005                               # cell size (m); the third argument overrides it


def merchant():
    """Merchant (1945): shear angle phi = 45 deg + rake/2 - beta/2, beta = atan(mu); shear stress on the
    shear plane k = sigma0 / sqrt(3) (von Mises); cutting force per unit width
    F_c = k t cos(beta - rake) / (sin(phi) cos(phi + beta - rake)), thrust F_t = F_c tan(beta - rake)."""
    beta, k = math.atan(MU), SIGMA0 / math.sqrt(3)
    phi = math.pi / 4 + RAKE / 2 - beta / 2
    fc = k * DEPTH * math.cos(beta - RAKE) / (math.sin(phi) * math.cos(phi + beta - RAKE))
    return fc, fc * math.tan(beta - RAKE), phi


def tool_tip_x(t):
    travel = V_TOOL * (t * t / (2 * T_RAMP) if t < T_RAMP else T_RAMP / 2 + (t - T_RAMP))
    return X_TIP0 + travel


def forces(d, t_steady):
    rows = list(csv.DictReader(open(os.path.join(d, "forces.csv"))))
    t = [float(r["time"]) for r in rows]
    fc_m, ft_m, phi = merchant()
    print("tool forces (kN/m): cutting F_c (along the cut) and thrust F_t (into the workpiece)")
    print("  Merchant: shear angle %.1f deg, F_c = %.1f kN/m, F_t = %.1f kN/m"
          % (math.degrees(phi), fc_m / 1e3, ft_m / 1e3))
    w, t0 = 1e-4, 0.0
    while t0 < t[-1] - 1e-12:
        sel = [i for i in range(len(t)) if t0 < t[i] <= t0 + w + 1e-12]
        if sel:
            fc = -sum(float(rows[i]["tool_x"]) for i in sel) / len(sel)
            ft = -sum(float(rows[i]["tool_y"]) for i in sel) / len(sel)
            print("  %4.2f-%4.2f ms (tip at x = %5.1f mm): F_c %7.1f  F_t %7.1f   F_c / Merchant %.3f"
                  % (t0 * 1e3, (t0 + w) * 1e3, tool_tip_x(t0 + w) * 1e3, fc / 1e3, ft / 1e3, fc / fc_m))
        t0 += w
    sel = [i for i in range(len(t)) if t[i] > t_steady]
    fc = -sum(float(rows[i]["tool_x"]) for i in sel) / len(sel)
    ft = -sum(float(rows[i]["tool_y"]) for i in sel) / len(sel)
    print("  mean after %.2f ms: F_c %.1f kN/m = %.3f x Merchant, F_t %.1f kN/m"
          % (t_steady * 1e3, fc / 1e3, fc / fc_m, ft / 1e3))


def roughness(d):
    """RMS deviation from their least-squares line of the highest points of the workpiece, per bin of
    half a cell, between 1 mm behind the tool tip and 2 mm from the plate's end."""
    t, path = last_frame(d)
    f = read_vtu(path)
    x = f["Points"]
    lo, hi = tool_tip_x(t) + 0.001, PLATE_END - 0.002
    nb = int((hi - lo) / (H / 2))
    if nb < 4:
        print("cut surface at t = %.2f ms: too short yet" % (t * 1e3))
        return
    top = [None] * nb
    for i in range(f["n"]):
        px, py = x[3 * i], x[3 * i + 1]
        if lo <= px < hi and py < Y_TIP + 0.002:
            b = min(int((px - lo) / (H / 2)), nb - 1)
            if top[b] is None or py > top[b][1]:
                top[b] = (px, py)
    pts = [p for p in top if p]
    n = len(pts)
    mx, my = sum(p[0] for p in pts) / n, sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    slope = sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx
    rms = math.sqrt(sum((p[1] - my - slope * (p[0] - mx)) ** 2 for p in pts) / n)
    peak = max(abs(p[1] - my - slope * (p[0] - mx)) for p in pts)
    print("cut surface at t = %.2f ms, x from %.1f to %.1f mm (%d bins): mean height %.3f mm (tool tip at %.3f mm), "
          "slope %.4f, RMS roughness %.4f mm = %.3f cell, largest deviation %.4f mm"
          % (t * 1e3, lo * 1e3, hi * 1e3, n, my * 1e3, Y_TIP * 1e3, slope, rms * 1e3, rms / H, peak * 1e3))
    print("chip: highest point %.2f mm above the plate's top" % ((max(x[3 * i + 1] for i in range(f["n"])) - TOP) * 1e3))


def main():
    global H
    d = sys.argv[1] if len(sys.argv) > 1 else "cutting.out"
    t_steady = float(sys.argv[2]) if len(sys.argv) > 2 else 3e-4
    H = float(sys.argv[3]) if len(sys.argv) > 3 else H
    forces(d, t_steady)
    roughness(d)


if __name__ == "__main__":
    main()
