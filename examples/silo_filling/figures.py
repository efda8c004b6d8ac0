"""Seed 004's Figs. 7 and 8 for the silo filling, from the output directory of a run of case.json
(Python 3 standard library; ffmpeg for the picture strip).

    python3 examples/silo_filling/figures.py RUN_DIR [OUT_DIR] [--every SECONDS]

Instants: the frames every SECONDS of simulated time (default 5.6 s, i.e. every 28 portions, seven
groups of four) and the run's last frame.

Fig. 7 (the deposit after each group of portions): the run's own pictures at those instants (the case
draws the pressure on one fixed range, 0-40 kPa), copied as deposit_t<T>.png and set side by side,
320 pixels wide each, in fig7_deposit.png; printed per instant, the portions released, the
deposit's mass, its height at the axis and at the wall (the top of the highest point's domain in the
outer 50 mm columns) and its mean height (its area over the width); points still falling (up to
five portions at a time) are not the deposit's.

Fig. 8 (wall and bottom tractions): the wall's and the floor's normal and tangential tractions
(wall_boundary_conditions1.csv and wall_boundary_conditions2.csv, each averaged over the frame interval
before the instant) against Janssen's for the plane-strain half silo, one wall per half width b:
sigma_v(z) = rho g b / (mu K) (1 - exp(-mu K z / b)), on the wall K sigma_v and mu K sigma_v (friction
fully mobilised), on the floor sigma_v(H) and no shear; z the depth below the deposit's mean height H,
rho its mass over its area, K = 1 - sin(phi) (Jaky), mu = tan 20 deg. Written as fig8_tractions.svg
(thick lines normal, thin tangential, dashed Janssen's, one colour per instant; fig8_tractions.png from
it when ffmpeg can read SVG) and fig8_tractions.csv; printed per instant, the resultants against
Janssen's (while portions land, the floor also takes the stream's momentum, about 30 kg / 0.2 s at
10 m/s: 1.5 kN/m).
"""
import csv
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from frames import frames, read_vtu  # noqa: E402

WIDTH, CELL, G, PHI, MU_W = 1.0, 0.05, 9.81, 30.0, 0.364
K_J = 1 - math.sin(math.radians(PHI))
PORTION_PERIOD, PORTION_MASS = 0.2, 30.0   # s, kg per metre of depth
WALL, FLOOR = "wall_boundary_conditions1.csv", "wall_boundary_conditions2.csv"
COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
           "#bcbd22", "#17becf"]


def instants(run, every):
    """[(time, frame path, picture path or None)] at every `every` seconds and the last frame."""
    fr = frames(run)
    chosen, k = [], 1
    for i, (t, path) in enumerate(fr):
        if t >= k * every - 1e-6 or i == len(fr) - 1:
            if t > 0:
                chosen.append((t, path))
            while t >= k * every - 1e-6:
                k += 1
    out = []
    for t, path in chosen:
        png = path[:-4] + ".png"
        out.append((t, path, png if os.path.exists(png) else None))
    return out


def connected(n, pts, hs):
    """Which points belong to the deposit: those joined to the floor through points less than a cell
    apart (the portions still falling, up to five at a time, do not)."""
    cells = {}
    for i in range(n):
        cells.setdefault((int(math.floor(pts[3 * i] / CELL)), int(math.floor(pts[3 * i + 1] / CELL))), []).append(i)
    inside = [False] * n
    queue = [i for i in range(n) if pts[3 * i + 1] - hs[2 * i + 1] < 0.5 * CELL]
    for i in queue:
        inside[i] = True
    while queue:
        i = queue.pop()
        cx, cy = int(math.floor(pts[3 * i] / CELL)), int(math.floor(pts[3 * i + 1] / CELL))
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in cells.get((cx + dx, cy + dy), ()):
                    if not inside[j] and math.hypot(pts[3 * j] - pts[3 * i], pts[3 * j + 1] - pts[3 * i + 1]) < CELL:
                        inside[j] = True
                        queue.append(j)
    return inside


def deposit(path):
    """Mass, area under the columns' tops, top at the axis and at the wall, from one frame: the
    deposit's points only."""
    f = read_vtu(path)
    n, pts, m, hs = f["n"], f["Points"], f["mass"], f["half_size"]
    ncol = int(round(WIDTH / CELL))
    top = [0.0] * ncol
    mass = 0.0
    inside = connected(n, pts, hs)
    for i in range(n):
        if not inside[i]:
            continue
        x = pts[3 * i]
        j = int(x / CELL)
        if 0 <= j < ncol:
            top[j] = max(top[j], pts[3 * i + 1] + hs[2 * i + 1])
        mass += m[i]
    return mass, sum(t * CELL for t in top), top[0], top[-1], top


def profiles(path, t):
    """The rows (s, x, y, normal, tangent) of one wall CSV at time t (the frame nearest to it)."""
    rows = list(csv.DictReader(open(path)))
    times = sorted({float(r["time"]) for r in rows})
    if not times:
        return []
    tt = min(times, key=lambda v: abs(v - t))
    return [(float(r["s"]), float(r["x"]), float(r["y"]), float(r["normal"]), float(r["tangent"]))
            for r in rows if float(r["time"]) == tt]


def janssen_v(rho, z):
    return rho * G * WIDTH / (MU_W * K_J) * (1 - math.exp(-MU_W * K_J * max(z, 0.0) / WIDTH))


def integrate(st, col):
    """Trapezoidal integral of column col along s."""
    return sum(0.5 * (st[i][col] + st[i + 1][col]) * (st[i + 1][0] - st[i][0]) for i in range(len(st) - 1))


def fig7(run, out, chosen):
    print("Fig. 7: the deposit at each instant")
    print("| t (s) | portions released | mass (kg/m) | height at the axis (m) | at the wall (m) | mean (m) |")
    print("|---:|---:|---:|---:|---:|---:|")
    pictures, rows = [], []
    for t, path, png in chosen:
        mass, area, h_axis, h_wall, _ = deposit(path)
        released = min(int(math.floor(t / PORTION_PERIOD + 1e-9)) + 1, 210)
        print("| %.1f | %d | %.0f | %.2f | %.2f | %.2f |" % (t, released, mass, h_axis, h_wall, area / WIDTH))
        rows.append((t, mass, area))
        if png:
            dst = os.path.join(out, "deposit_t%05.1f.png" % t)
            shutil.copyfile(png, dst)
            pictures.append(dst)
    if len(pictures) > 1 and shutil.which("ffmpeg"):
        cmd = ["ffmpeg", "-loglevel", "error", "-y"]
        for p in pictures:
            cmd += ["-i", p]
        scaled = ";".join("[%d]scale=320:-2[p%d]" % (k, k) for k in range(len(pictures)))
        stack = "".join("[p%d]" % k for k in range(len(pictures))) + "hstack=inputs=%d" % len(pictures)
        cmd += ["-filter_complex", scaled + ";" + stack, os.path.join(out, "fig7_deposit.png")]
        subprocess.run(cmd, check=True)
    elif pictures:
        print("(ffmpeg not found or one picture only: no strip; the pictures are in %s)" % out)
    else:
        print("(the run wrote no pictures: set output.pictures, or draw them with pmech render)")
    return rows


def nice_step(span):
    """A tick step of 1, 2 or 5 times a power of ten giving four to ten ticks over span."""
    base = 10 ** math.floor(math.log10(span / 4))
    for f in (1, 2, 5, 10):
        if span / (f * base) <= 10:
            return f * base
    return 10 * base


def svg_panel(x0, y0, w, h, xr, yr, xlabel, ylabel, series):
    """One panel: axes with ticks and labels, and polylines [(points, colour, width, dashed)]."""
    def X(v):
        return x0 + (v - xr[0]) / (xr[1] - xr[0]) * w

    def Y(v):
        return y0 + h - (v - yr[0]) / (yr[1] - yr[0]) * h

    s = ['<rect x="%g" y="%g" width="%g" height="%g" fill="none" stroke="black"/>' % (x0, y0, w, h)]
    for ax, rng in (("x", xr), ("y", yr)):
        step = nice_step(rng[1] - rng[0])
        for k in range(int(math.ceil(rng[0] / step - 1e-9)), int(math.floor(rng[1] / step + 1e-9)) + 1):
            v = k * step
            if ax == "x":
                s.append('<line x1="%g" y1="%g" x2="%g" y2="%g" stroke="black"/>' % (X(v), y0 + h, X(v), y0 + h + 4))
                s.append('<text x="%g" y="%g" font-size="11" text-anchor="middle">%g</text>' % (X(v), y0 + h + 16, round(v, 3)))
            else:
                s.append('<line x1="%g" y1="%g" x2="%g" y2="%g" stroke="black"/>' % (x0 - 4, Y(v), x0, Y(v)))
                s.append('<text x="%g" y="%g" font-size="11" text-anchor="end">%g</text>' % (x0 - 6, Y(v) + 4, round(v, 3)))
    s.append('<text x="%g" y="%g" font-size="12" text-anchor="middle">%s</text>' % (x0 + w / 2, y0 + h + 34, xlabel))
    s.append('<text x="%g" y="%g" font-size="12" text-anchor="middle" transform="rotate(-90 %g %g)">%s</text>'
             % (x0 - 42, y0 + h / 2, x0 - 42, y0 + h / 2, ylabel))
    for pts, colour, width, dashed in series:
        if len(pts) < 2:
            continue
        d = " ".join("%.1f,%.1f" % (X(px), Y(py)) for px, py in pts)
        s.append('<polyline points="%s" fill="none" stroke="%s" stroke-width="%g"%s/>'
                 % (d, colour, width, ' stroke-dasharray="6,4"' if dashed else ""))
    return s


def fig8(run, out, chosen, deposits):
    wall_path, floor_path = os.path.join(run, WALL), os.path.join(run, FLOOR)
    if not (os.path.exists(wall_path) and os.path.exists(floor_path)):
        print("no %s or %s in %s: no Fig. 8" % (WALL, FLOOR, run))
        return
    print()
    print("Fig. 8: resultants (N/m) at each instant against Janssen's (rho: mass / area; H: area / width)")
    print("| t (s) | H (m) | rho (kg/m^3) | wall normal | Janssen | wall tangential | Janssen | floor normal | Janssen | floor tangential |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    wall_series, floor_series, table = [], [], []
    t_max, h_max = 0.0, 0.0
    for k, ((t, _, _), (_, mass, area)) in enumerate(zip(chosen, deposits)):
        colour = COLOURS[k % len(COLOURS)]
        H = area / WIDTH
        rho = mass / area if area > 0 else 0.0
        wall, floor = profiles(wall_path, t), profiles(floor_path, t)
        fw_n, fw_t = integrate(wall, 3), integrate(wall, 4)
        ff_n, ff_t = integrate(floor, 3), integrate(floor, 4)
        # Janssen: wall force = the weight less the floor's, the floor's uniform sigma_v(H) over b
        jf = WIDTH * janssen_v(rho, H)
        jw_t = rho * G * H * WIDTH - jf
        jw_n = jw_t / MU_W
        print("| %.1f | %.2f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f |"
              % (t, H, rho, fw_n, jw_n, fw_t, jw_t, ff_n, jf, ff_t))
        wall_series += [([(r[3] / 1e3, r[2]) for r in wall], colour, 2.5, False),
                        ([(r[4] / 1e3, r[2]) for r in wall], colour, 1.0, False)]
        ys = [H * q / 40 for q in range(41)]
        wall_series += [([(K_J * janssen_v(rho, H - y) / 1e3, y) for y in ys], colour, 1.5, True)]
        floor_series += [([(r[1], r[3] / 1e3) for r in floor], colour, 2.5, False),
                         ([(r[1], r[4] / 1e3) for r in floor], colour, 1.0, False),
                         ([(0.0, janssen_v(rho, H) / 1e3), (WIDTH, janssen_v(rho, H) / 1e3)], colour, 1.5, True)]
        t_max = max([t_max] + [abs(v) / 1e3 for r in wall + floor for v in (r[3], r[4])] + [janssen_v(rho, H) / 1e3])
        h_max = max(h_max, max([r[2] for r in wall if r[3] != 0 or r[4] != 0] + [H]))
        for r in wall:
            table.append((t, "wall", r[1], r[2], r[3], r[4], K_J * janssen_v(rho, H - r[2]) if r[2] < H else 0.0,
                          MU_W * K_J * janssen_v(rho, H - r[2]) if r[2] < H else 0.0))
        for r in floor:
            table.append((t, "floor", r[1], r[2], r[3], r[4], janssen_v(rho, H), 0.0))
    top = nice_step(t_max) * math.ceil(t_max / nice_step(t_max)) if t_max > 0 else 10
    hgt = math.ceil(h_max * 2 + 1e-9) / 2
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="980" height="470" font-family="sans-serif">',
           '<rect width="980" height="470" fill="white"/>',
           '<text x="490" y="20" font-size="14" text-anchor="middle">Silo filling: tractions on the wall and the floor '
           '(thick: normal, thin: tangential, dashed: Janssen, K = %.2f, mu = %.3f)</text>' % (K_J, MU_W)]
    svg += svg_panel(70, 40, 380, 360, (-top / 4, top), (0, hgt), "wall traction (kPa)", "height y (m)", wall_series)
    svg += svg_panel(560, 40, 380, 360, (0, WIDTH), (-top / 4, top), "distance from the axis x (m)",
                     "floor traction (kPa)", floor_series)
    for k, (t, _, _) in enumerate(chosen):
        svg.append('<text x="%g" y="%g" font-size="11" fill="%s">t = %.1f s</text>'
                   % (80 + 85 * (k % 10), 455, COLOURS[k % len(COLOURS)], t))
    svg.append("</svg>")
    svg_path = os.path.join(out, "fig8_tractions.svg")
    open(svg_path, "w").write("\n".join(svg) + "\n")
    if shutil.which("ffmpeg"):  # a PNG beside it, through ffmpeg's librsvg decoder
        subprocess.run(["ffmpeg", "-loglevel", "error", "-y", "-i", svg_path, svg_path[:-4] + ".png"], check=False)
    with open(os.path.join(out, "fig8_tractions.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time", "surface", "x", "y", "normal", "tangent", "janssen_normal", "janssen_tangent"])
        w.writerows(table)


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    every = 5.6
    if "--every" in argv:
        every = float(argv[argv.index("--every") + 1])
        args.remove(argv[argv.index("--every") + 1])
    if not args:
        print(__doc__)
        return 2
    run = args[0]
    out = args[1] if len(args) > 1 else run
    os.makedirs(out, exist_ok=True)
    chosen = instants(run, every)
    if not chosen:
        print("no frames after t = 0 in %s" % run)
        return 1
    rows = fig7(run, out, chosen)
    fig8(run, out, chosen, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
