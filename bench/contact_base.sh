#!/bin/sh
# Cost of frictional contact at a base: the elastic block of bench/block_case.py (about N particles,
# MUSL, fixed step) resting on a fixed base (its y_min held), on a `friction` grid side (mu = 0.3) and on
# a rigid `obstacles[]` polyline under it (mu = 0.3, the grid one cell deeper). The three run in turn,
# ROUNDS times, on one thread; each run's time per step is its run.json loop_seconds / steps (the time
# loop only: no set-up, no output), and the ratios to the fixed base are taken round by round and their
# median printed, so that a machine whose speed drifts still gives a fair ratio.
# usage: bench/contact_base.sh [path/to/pmech] [N] [STEPS] [ROUNDS]
set -e
PMECH=${1:-build/pmech}
N=${2:-1e6}
STEPS=${3:-20}
ROUNDS=${4:-3}
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 "$here/block_case.py" "$N" "$STEPS" > "$dir/fixed.json"
python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
c = json.load(open(d + "/fixed.json"))
f = json.loads(json.dumps(c))
f["boundary_conditions"] = [{"type": "friction", "boundary": "y_min", "coefficient": 0.3}]
json.dump(f, open(d + "/friction.json", "w"))
o = json.loads(json.dumps(c))
h = o["grid"]["size"][0] / o["grid"]["cells"][0]
o["grid"]["origin"][1] -= h
o["grid"]["size"][1] += h
o["grid"]["cells"][1] += 1
o["boundary_conditions"] = []
o["obstacles"] = [{"name": "base", "type": "polyline", "points": [[-2 * h, 0.0], [1.0 + 2 * h, 0.0]],
                   "friction": 0.3}]
json.dump(o, open(d + "/obstacle.json", "w"))
PY
for r in $(seq "$ROUNDS"); do
  for v in fixed friction obstacle; do
    OMP_NUM_THREADS=1 "$PMECH" run "$dir/$v.json" -o "$dir/out_$v" --overwrite --quiet --threads 1
    python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(sys.argv[2], r['particles'], r['loop_seconds']/r['steps'])" \
      "$dir/out_$v/run.json" "$v" >> "$dir/times"
  done
done
python3 - "$dir/times" "$ROUNDS" <<'PY'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
by = {}
for name, n, t in rows:
    by.setdefault(name, []).append(float(t))
print("particles %s, %s rounds; seconds per step (median): %s" % (rows[0][1], sys.argv[2],
      ", ".join("%s %.4f" % (k, statistics.median(v)) for k, v in by.items())))
for k in ("friction", "obstacle"):
    ratios = [a / b for a, b in zip(by[k], by["fixed"])]
    print("%s / fixed: median %.3f (each round: %s)" % (k, statistics.median(ratios), " ".join("%.3f" % x for x in ratios)))
PY
