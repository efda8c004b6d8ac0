#!/bin/sh
# Mesh study of the Griffiths & Lane slope: the factor of safety by strength reduction with MPM
# (linear, 2 x 2 points per cell) at h = H/10, H/20, H/40 and RKPM (one node per cell) at node spacing
# H/10, H/20. Prints one row per run; the H/40 MPM and H/20 RKPM rows take several minutes each.
# usage: sh examples/slope_fos/study.sh [path/to/pmech]
set -e
PMECH=${1:-build/pmech}
DIR=$(dirname "$0")
TMP=$(mktemp -d)
printf '%-5s %-6s %-9s %-8s %-17s %-7s %s\n' method h points fos bracket trials seconds
for run in "mpm 1" "mpm 0.5" "mpm 0.25" "rkpm 1" "rkpm 0.5"; do
    set -- $run
    name="$1_$2"
    python3 - "$DIR" "$TMP/$name.json" "$1" "$2" <<'PY'
import json, sys
d, out, method, h = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
c = json.load(open(d + ("/case_rkpm.json" if method == "rkpm" else "/case.json")))
c["grid"]["cells"] = [round(c["grid"]["size"][0] / h), round(c["grid"]["size"][1] / h)]
c["output"].pop("pictures", None)
json.dump(c, open(out, "w"))
PY
    start=$(date +%s.%N)
    fos=$("$PMECH" run "$TMP/$name.json" -o "$TMP/out_$name" --quiet | sed 's/factor of safety \([0-9.]*\) (holds at \([0-9.]*\), fails at \([0-9.]*\))/\1 \2-\3/')
    end=$(date +%s.%N)
    n=$(python3 -c "import json; print(json.load(open('$TMP/out_$name/srf_1.2000/run.json'))['particles'])")
    trials=$(($(wc -l < "$TMP/out_$name/strength_reduction.csv") - 1))
    printf '%-5s %-6s %-9s %-8s %-17s %-7s %.0f\n' "$1" "$2" "$n" $fos "$trials" "$(echo "$end - $start" | bc)"
done
rm -rf "$TMP"
