#!/bin/sh
# The rolling-disk comparison of seed 000 Table 1: runs examples/rolling_disk/case.json with the steps
# dt1 = 2 dt2 = 4 dt3 (dt1 = the case's analysis.dt) for every row of ROWS and prints a markdown table
# of the eq. 67 error and the wall time next to the paper's values.
#   error = sqrt(sum_i (u(t_i) - u_num(t_i))^2) in mm, t_i = 0.01, 0.02, ..., 1.00 s (the probe rows),
#   u = a t^2 / 2 with a = (2/3) |g| sin(theta), u_num the displacement of the disk's centre of mass
#   along the plane (the "centre" probe: mass-weighted mean over the disk's particles).
# usage: sh examples/rolling_disk/table.sh [path/to/pmech]     (one thread; about 3 minutes for MPM)
set -e
PMECH=${1:-build/pmech}
DIR=$(dirname "$0")
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# label|method|shape_function|lme_gamma ("-": the default)
ROWS='MPM|mpm|linear|-'
export OMP_NUM_THREADS=1
echo "$ROWS" | while IFS='|' read -r label method shape gamma; do
    for k in 1 2 3; do
        python3 - "$DIR/case.json" "$TMP/case.json" "$method" "$shape" "$gamma" "$k" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["method"], c["shape_function"] = sys.argv[3], sys.argv[4]
if sys.argv[5] != "-":
    c["lme_gamma"] = float(sys.argv[5])
c["analysis"]["dt"] /= 2 ** (int(sys.argv[6]) - 1)
c["output"].pop("pictures", None)
c["output"]["interval"] = c["analysis"]["end_time"]
c["output"]["probe_interval"] = 0.01
json.dump(c, open(sys.argv[2], "w"))
PY
        "$PMECH" run "$TMP/case.json" -o "$TMP/out" --overwrite --quiet --threads 1 || true
        python3 - "$TMP/case.json" "$TMP/out" "$label" "$k" >> "$TMP/results" <<'PY'
import csv, json, math, sys
c = json.load(open(sys.argv[1]))
gx, gy = c["analysis"]["gravity"]
a = 2.0 / 3.0 * gx  # (2/3) |g| sin(theta): gx = |g| sin(theta)
run = json.load(open(sys.argv[2] + "/run.json"))
rows = list(csv.DictReader(open(sys.argv[2] + "/probes.csv")))[1:]
e2 = sum((a * float(r["time"]) ** 2 / 2 - float(r["centre.ux"])) ** 2 for r in rows)
fit = sum(float(r["centre.ux"]) * float(r["time"]) ** 2 / 2 for r in rows) / sum((float(r["time"]) ** 2 / 2) ** 2 for r in rows)
stop = "" if run["exit_status"] == 0 else "stopped at t = %.2f s" % float(rows[-1]["time"])
print("%s|%s|%.1f|%.1f|%.3f|%d|%.4f|%s" % (sys.argv[3], sys.argv[4], 1e3 * math.sqrt(e2), run["wall_seconds"],
      fit / a, len(rows), float(rows[-1]["centre.uy"]), stop))
PY
        tail -1 "$TMP/results" >&2
    done
done
python3 - "$TMP/results" "$DIR/case.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[2]))
dt1 = c["analysis"]["dt"]
def cell(f):
    # an incomplete run sums fewer samples: say so next to its error
    return "%s mm%s | %s" % (f[2], " (%s, %s samples)" % (f[7], f[5]) if f[7] else "", f[3])


res = {}
for line in open(sys.argv[1]):
    f = line.rstrip("\n").split("|")
    res.setdefault(f[0], {})[int(f[1])] = f
paper = [("MPM", [(2.34, 232.72), (1.27, 472.92), (0.91, 894.91)]),
         ("GMM-MLS", [(0.84, 264.78), (0.26, 517), (0.20, 981.82)]),
         ("GMM-LME gamma 0.8", [(1.37, 234.32), (0.07, 460.73), (0.06, 971.29)])]
print("| technique | | dt1 error | dt1 t_comp (s) | dt2 error | dt2 t_comp (s) | dt3 error | dt3 t_comp (s) |")
print("|---|---|---|---|---|---|---|---|")
for label, vals in paper:
    print("| %s | paper (h = 0.01) | %s |" % (label, " | ".join("%g | %g" % v for v in vals)))
    r = res.get(label)
    if r:
        cells = " | ".join(cell(r[k]) if k in r else "- | -" for k in (1, 2, 3))
        print("| %s | pmech (dt1 = %g s) | %s |" % (label, dt1, cells))
for label, r in res.items():
    if label not in dict(paper):
        print("| %s | pmech (dt1 = %g s) | %s |" % (label, dt1, " | ".join("%s mm | %s" % (r[k][2], r[k][3]) for k in sorted(r))))
print()
print("fitted acceleration / (2/3) g sin(theta), and centre's rise off the plane at the end (m):")
for label, r in res.items():
    print("- %s: %s" % (label, "; ".join("dt%d: %s, rise %s m" % (k, r[k][4], r[k][6]) for k in sorted(r))))
PY
