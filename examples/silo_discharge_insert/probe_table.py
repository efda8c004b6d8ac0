#!/usr/bin/env python3
"""The 0.2 s windows of the README's diagnostics table from probe.c's CSV files.

    python3 probe_table.py RUN.csv [RUN.csv ...]

Per window after the opening: the outflow rate over Beverloo's (C = 0.58, k d = 0, D = 0.4 m,
rho_b = 1500 kg/m^3: 276 kg/s), the part of it that started above the insert's base, the density and
downward speed of the points in the outlet's bottom cell row, the density above the outlet, FLIP's
hidden velocity at rest (RMS, largest, largest near the floor, m/s), the kinetic energy of the points'
own velocities over that of the interpolated ones, the points above z = 0.3 m faster than 3 m/s (free
fall from the insert's rim, 0.7 m higher, reaches 3.7 m/s there) and the fastest point,
the points under the insert's base (r < 0.4 m, 0.8 < z < 1 m: 128 at rest at 50 mm), the insert's
vertical load (kN) and the removed mass so far (kg)."""
import csv
import math
import sys

BEVERLOO = 0.58 * 1500 * math.sqrt(9.81) * 0.4 ** 2.5


def table(path):
    rows = list(csv.DictReader(open(path)))
    print(f"{path} (Beverloo {BEVERLOO:.0f} kg/s)")
    print("| window (s) | W / Beverloo | from above the insert | outlet density (kg/m^3) | outlet speed (m/s) "
          "| density above the outlet | hidden RMS at rest | hidden max at rest | hidden max near the floor "
          "| KE points / grid | points above z = 0.3 m faster than 3 m/s | fastest point (m/s) | points under the "
          "insert's base | insert load (kN) | removed (kg) |")
    print("|" + "---|" * 15)
    removed = 0.0
    for k in range(0, 100):
        a, b = 0.2 * k, 0.2 * (k + 1)
        # a row covers the 0.05 s before its time: rows 4k+1 .. 4k+4 after the opening make window k
        win = [r for r in rows if (round(float(r["t"]) / 0.05) - 1) // 4 == k and float(r["t"]) > 0]
        if not win:
            if a > 0:
                break
            continue
        mean = lambda key: sum(float(r[key]) for r in win) / len(win)
        top = lambda key: max(float(r[key]) for r in win)
        removed += sum(float(r["W"]) * 0.05 for r in win)
        print(f"| {a:.1f}-{b:.1f} | {mean('W') / BEVERLOO:.2f} | {mean('W_above_insert') / BEVERLOO:.2f} "
              f"| {mean('outlet_rho'):.0f} | {mean('outlet_vz'):.2f} | {mean('zone_rho'):.0f} "
              f"| {mean('hid_rms_rest'):.3f} | {top('hid_max_rest'):.2f} | {top('hid_max_floor'):.2f} "
              f"| {mean('ke_p') / max(mean('ke_g'), 1e-12):.2f} | {mean('n_fast_far'):.1f} | {top('max_speed'):.1f} "
              f"| {mean('under_cone_n'):.0f} | {mean('insert_fy') / 1e3:.1f} | {removed:.0f} |")


if __name__ == "__main__":
    for p in sys.argv[1:]:
        table(p)
