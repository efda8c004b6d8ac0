#!/bin/sh
# The cantilever mesh-convergence study of seed 000 Fig. 7: runs the case at h = 0.5 ... 0.03125 and
# prints the tip deflection (the particle nearest (8, 0.5)), Newton iterations and wall time.
# usage: sh examples/cantilever/convergence.sh [path/to/pmech] [method shape_function]
#   e.g. sh examples/cantilever/convergence.sh build/pmech gmm mls
set -e
PMECH=${1:-build/pmech}
METHOD=${2:-mpm}
SHAPE=${3:-bspline2}
DIR=$(dirname "$0")
TMP=$(mktemp -d)
printf '%-9s %-12s %-8s %-10s %s\n' h cells tip_uy newton seconds
for h in 0.5 0.25 0.125 0.0625 0.03125; do
    nx=$(python3 -c "print(round(9/$h))")
    ny=$(python3 -c "print(round(2.5/$h))")
    python3 - "$DIR/case.json" "$TMP/case_$h.json" "$nx" "$ny" "$METHOD" "$SHAPE" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["method"], c["shape_function"] = sys.argv[5], sys.argv[6]
c["grid"]["cells"] = [int(sys.argv[3]), int(sys.argv[4])]
c["output"].pop("pictures", None)
c["output"]["interval"] = 1.0
json.dump(c, open(sys.argv[2], "w"))
PY
    "$PMECH" run "$TMP/case_$h.json" -o "$TMP/out_$h" --quiet
    tip=$(tail -1 "$TMP/out_$h/probes.csv" | cut -d, -f3)
    its=$(python3 -c "import json; r = json.load(open('$TMP/out_$h/run.json')); print(r['newton_iterations'], '%.2f' % r['wall_seconds'])")
    printf '%-9s %-12s %-8.5f %s\n' "$h" "${nx}x${ny}" "$tip" "$its"
done
rm -rf "$TMP"
