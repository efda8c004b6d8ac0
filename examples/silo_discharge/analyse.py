#!/usr/bin/env python3
"""Figures of merit of the silo discharge, from the frames and removals.csv a run wrote (Python 3
standard library only).

    python3 analyse.py silo_discharge.out [cell size, default 0.02 m]

The outlet opens at T_OPEN = 1 s (the fill settles on it under gravity ramped up over the first
second); times below are counted from the opening. Prints: the discharge rate over successive 0.1 s
windows against Beverloo's law for the axisymmetric outlet; the flow pattern at three heights (the
fraction of the cross-section that moves, the velocity ratio wall/axis); the wall-normal traction
along the wall at rest (at the opening) and during the discharge, against Janssen's: the wall's own
traction (wall_boundary_conditions0.csv, the first friction condition's profile from the contact
impulses, averaged over the frame interval before each instant) and, beside it, the radial stress of
the particles in the cell column next to the wall, both averaged over bands of 0.25 m. The frames are
read through examples/frames.py."""
import csv, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, read_vtu  # noqa: E402

RHO, G, R, H_FILL = 1500.0, 9.81, 1.0, 3.0
PHI, MU_W = math.radians(25.0), math.tan(math.radians(20.0))
D_OUT = 0.4                      # outlet diameter (radius 0.2 m)
C_BEV, K_BEV, D_GRAIN = 0.58, 1.5, 0.0   # Beverloo's constant, edge factor, grain size (a continuum: none)
T_OPEN = 1.0


def beverloo():
    return C_BEV * RHO * math.sqrt(G) * (D_OUT - K_BEV * D_GRAIN) ** 2.5


def discharge_rate(d):
    rows = list(csv.DictReader(open(os.path.join(d, "removals.csv"))))
    t = [float(r["time"]) - T_OPEN for r in rows]
    m = [2 * math.pi * float(r["cumulative_mass"]) for r in rows]   # per radian -> whole silo

    def mass_at(tt):
        v = 0.0
        for ti, mi in zip(t, m):
            if ti > tt + 1e-12:
                break
            v = mi
        return v
    wb = beverloo()
    print("discharge rate (kg/s, whole silo) per 0.1 s window; Beverloo W = C rho_b sqrt(g) (D - k d)^2.5 "
          "= %.1f kg/s (C = %g, k = %g, d = %g m, D = %g m, rho_b = %g kg/m^3)" % (wb, C_BEV, K_BEV, D_GRAIN, D_OUT, RHO))
    t_end = t[-1] if t else 0
    k = 0
    while (k + 1) * 0.1 <= t_end + 1e-9:
        w = (mass_at((k + 1) * 0.1) - mass_at(k * 0.1)) / 0.1
        print("  %.1f-%.1f s: %7.1f kg/s  (%.2f x Beverloo)" % (k * 0.1, (k + 1) * 0.1, w, w / wb))
        k += 1
    print("  total removed by %.3f s: %.1f kg of %.0f kg" % (t_end, m[-1] if m else 0, RHO * math.pi * R * R * H_FILL))


def speed_profile(f, z, dz):
    """(r, downward speed, volume) of the particles within dz of height z."""
    x, v, vol = f["Points"], f["velocity"], f["volume"]
    out = []
    for i in range(f["n"]):
        if abs(x[3 * i + 1] - z) < dz:
            out.append((x[3 * i], -v[3 * i + 1], vol[i]))   # vectors have 3 components
    return out


def flow_pattern(f, t, h):
    print("flow pattern %.2f s after the opening (moving: downward speed above 10 %% of the axis's)" % t)
    for z in (0.5, 1.5, 2.5):
        prof = speed_profile(f, z, h)
        if not prof:
            continue
        axis = [s for r, s, _ in prof if r < 0.1]
        wall = [s for r, s, _ in prof if r > 0.9]
        va = sum(axis) / len(axis) if axis else float("nan")
        vw = sum(wall) / len(wall) if wall else float("nan")
        # the particles' volumes are per radian (r dr dz): their sum is the cross-section's share
        total = sum(w for _, _, w in prof)
        moving = sum(w for _, s, w in prof if s > 0.1 * va)
        print("  z = %.1f m: axis %.3f m/s, wall %.4f m/s, wall/axis %.3f, moving fraction %.2f"
              % (z, va, vw, vw / va if va else float("nan"), moving / total))


def wall_profile(d, t):
    """(z, normal traction in Pa) of the wall's stations in its profile row at time t (the wall is the
    first friction condition; its profile is per radian, divided by the wall's radius)."""
    path = os.path.join(d, "wall_boundary_conditions0.csv")
    if not os.path.exists(path):
        return []
    rows = [r for r in csv.DictReader(open(path)) if abs(float(r["time"]) - t) < 2e-3]
    return [(float(r["y"]), float(r["normal"]) / R) for r in rows]


def wall_traction(d, f, t, label, h):
    """Wall-normal traction in 0.25 m bands of height: the wall's own (its contact impulses) and the
    mean -sigma_rr of the particles in the cell column next to the wall."""
    x, s = f["Points"], f["stress"]
    top = max(x[3 * i + 1] for i in range(f["n"]) if x[3 * i] > R - h)
    prof = wall_profile(d, t)
    print("wall-normal traction (kPa) %s: the wall's own, the particles' -sigma_rr next to it; Janssen with "
          "K = 1 - sin(phi) = %.3f, mu_w = tan 20 deg, depth from the fill's top at the wall (%.2f m)"
          % (label, 1 - math.sin(PHI), top))
    K = 1 - math.sin(PHI)
    y0 = 0.0
    while y0 < H_FILL - 1e-9:
        sel = [-s[4 * i] for i in range(f["n"]) if x[3 * i] > R - h and y0 <= x[3 * i + 1] < y0 + 0.25]
        wall = [p for z, p in prof if y0 <= z < y0 + 0.25]
        if sel:
            depth = top - (y0 + 0.125)
            jans = K * RHO * G * R / (2 * K * MU_W) * (1 - math.exp(-2 * K * MU_W * depth / R)) if depth > 0 else 0
            print("  y %.2f-%.2f m: wall %7.2f  particles %7.2f  Janssen %7.2f"
                  % (y0, y0 + 0.25, sum(wall) / len(wall) / 1e3 if wall else float("nan"),
                     sum(sel) / len(sel) / 1e3, jans / 1e3))
        y0 += 0.25


def main():
    d = sys.argv[1]
    h = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02   # cell size of the run
    fr = frames(d)
    discharge_rate(d)
    for t, p in fr:
        tt = t - T_OPEN
        if abs(tt) < 2e-3:
            wall_traction(d, read_vtu(p), t, "at rest, at the opening", h)
        elif any(abs(tt - ti) < 2e-3 for ti in (0.25, 0.5, 0.75, 1.0, 1.25)):
            f = read_vtu(p)
            flow_pattern(f, tt, h)
            if abs(tt - 0.5) < 2e-3 or abs(tt - 1.25) < 2e-3:
                wall_traction(d, f, t, "%.2f s after the opening" % tt, h)


if __name__ == "__main__":
    main()
