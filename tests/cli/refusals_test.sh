#!/bin/sh
# Inputs that used to run to a silent wrong answer, for ever, or out of memory: each must now stop within
# seconds with a non-zero exit and a message naming the key, element or value at fault; and a motion with
# no load that used to fail (Newton's absolute tolerance).
# usage: refusals_test.sh PMECH SOURCE_DIR WORK_DIR
set -u
PMECH=$1; SRC=$2; WORK=$3
. "$SRC/tests/cli/test_lib.sh"
DISKS="$SRC/examples/elastic_disks/case.json"
# test_lib.sh's expect_exit with the command bounded: the exit code, within 20 s and 1 GB of address
# space (the address space is not bounded in sanitizer builds, PMECH_NO_VMEM_LIMIT: ASan reserves
# terabytes of it for its shadow memory at start; the release build checks the bound)
expect_exit() {
  code=$1; d=$2; shift 2
  ( [ -n "${PMECH_NO_VMEM_LIMIT:-}" ] || ulimit -v 1000000; timeout 20 "$@" ) >out.txt 2>err.txt; rc=$?
  if [ "$rc" -eq "$code" ]; then echo "ok   $d (exit $rc)"; else echo "FAIL $d: exit $rc, wanted $code"; cat err.txt; fail=1; fi
}

# ---- bounded work
sed 's/"end_time": 3.5/"end_time": 1e300/' "$DISKS" > long.json
expect_exit 2 "end_time 1e300" "$PMECH" run long.json -o long.out --quiet
check "names the estimate and analysis.max_steps" sh -c 'grep -q "steps" err.txt && grep -q "analysis.max_steps" err.txt'
sed 's/"youngs_modulus": 1000,/"youngs_modulus": 1e300,/' "$DISKS" > stiff.json
expect_exit 2 "a modulus of 1e300 Pa (a step of 1e-151 s)" "$PMECH" run stiff.json -o stiff.out --quiet
check "names max_steps" has "max_steps" err.txt
sed 's/"end_time": 3.5, "cfl": 0.2/"end_time": 3.5, "dt": 4e-320/' "$DISKS" > tinydt.json
expect_exit 2 "dt 4e-320" "$PMECH" run tinydt.json -o tinydt.out --quiet
check "names max_steps" has "max_steps" err.txt
sed 's/"end_time": 3.5, "cfl": 0.2/"end_time": 0.1, "cfl": 0.2, "max_steps": 10/' "$DISKS" > few.json
expect_exit 2 "a run of about 26 steps with max_steps 10" "$PMECH" run few.json -o few.out --quiet
check "the estimate is given" grep -Eq "about 2[0-9] steps" err.txt
# an interval below the spacing of doubles near t used to spin in the frame scheduler: now a frame a step
sed 's/"end_time": 3.5/"end_time": 0.02/; s/"interval": 0.05/"interval": 1e-300/; s/, "pictures": "speed"//' "$DISKS" > tinyint.json
expect_exit 0 "output.interval 1e-300 finishes" "$PMECH" run tinyint.json -o tinyint.out --quiet
check "with a frame per step" python3 -c "import json,sys; r=json.load(open('tinyint.out/run.json')); sys.exit(0 if r['frames']==r['steps']+1 else 1)"

# ---- silent wrong answers
sed 's/"end_time": 3.5, "cfl": 0.2/"end_time": 3.5, "dt": 0.03/' "$DISKS" > bigdt.json
expect_exit 2 "explicit fixed dt 1.6 times the stable step" "$PMECH" run bigdt.json -o bigdt.out --quiet
check "names analysis.dt and the stable step" sh -c 'grep -q "analysis.dt: 0.03" err.txt && grep -q "0.0192" err.txt'
sed 's/"end_time": 3.5, "cfl": 0.2/"end_time": 0.05, "dt": 0.019/' "$DISKS" > okdt.json
expect_exit 0 "a fixed dt just below the stable step runs" "$PMECH" run okdt.json -o okdt.out --quiet
sed 's/{ "name": "lower", "body": "lower", "quantity": "velocity" }/{ "name": "far", "point": [1e6, 0.5], "quantity": "velocity" }/' "$DISKS" > far.json
expect_exit 2 "a probe 1e6 m from the material" "$PMECH" run far.json -o far.out --quiet
check "names probes[0].point and the distance" sh -c 'grep -q "probes\[0\].point" err.txt && grep -q "999999 m" err.txt'
sed 's/{ "name": "lower", "body": "lower", "quantity": "velocity" }/{ "name": "edge", "point": [0.25, 0.46], "quantity": "velocity" }/; s/"end_time": 3.5/"end_time": 0.01/' "$DISKS" > near.json
expect_exit 0 "a probe just outside the disk edge (within a cell) runs" "$PMECH" run near.json -o near.out --quiet
sed 's/"directions": \["x", "y"\]/"directions": ["x", "x"]/' "$SRC/examples/cantilever/case.json" > dirs.json
expect_exit 2 "directions [\"x\", \"x\"]" "$PMECH" run dirs.json -o dirs.out --quiet
check "names boundary_conditions[0].directions[1]" has "boundary_conditions\[0\].directions\[1\]" err.txt

sed 's/"origin": \[0.0, 0.0\]/"origin": [1e300, 0.0]/' "$DISKS" > huge.json
expect_exit 2 "a grid origin of 1e300" "$PMECH" run huge.json -o huge.out --quiet
check "names grid.origin" has "grid.origin" err.txt
sed 's/"origin": \[0.0, 0.0\]/"origin": [1e6, 0.0]/; s/"center": \[0.25, 0.25\]/"center": [1000000.25, 0.25]/; s/"center": \[0.75, 0.75\]/"center": [1000000.75, 0.75]/; s/"end_time": 3.5/"end_time": 0.01/; s/, "pictures": "speed"//' "$DISKS" > utm.json
expect_exit 0 "a grid at x = 1e6 m with 0.025 m cells runs" "$PMECH" run utm.json -o utm.out --quiet
polygon() { # file, points
  python3 -c "import json,sys; c=json.load(open(sys.argv[1])); c['bodies'][0]['shape']={'type':'polygon','points':json.loads(sys.argv[2])}; json.dump(c,open(sys.argv[3],'w'))" "$DISKS" "$2" "$1"
}
polygon collinear.json '[[0.1,0.1],[0.2,0.2],[0.3,0.3]]'
expect_exit 2 "a polygon of collinear points" "$PMECH" run collinear.json -o poly.out --quiet
check "says they lie on one line" sh -c 'grep -q "bodies\[0\].shape.points" err.txt && grep -q "one line" err.txt'
polygon bowtie.json '[[0.1,0.1],[0.4,0.1],[0.1,0.3],[0.4,0.4]]'
expect_exit 2 "a self-intersecting polygon" "$PMECH" run bowtie.json -o poly.out --quiet
check "names the crossing edges" has "the edge from point 1 to 2 meets the edge from point 3 to 0" err.txt
polygon closed.json '[[0.1,0.1],[0.4,0.1],[0.4,0.4],[0.1,0.4],[0.1,0.1]]'
sed -i 's/"end_time": 3.5/"end_time": 0.01/' closed.json
expect_exit 0 "a polygon closed by repeating its first point runs" "$PMECH" run closed.json -o poly.out --quiet

# GMM and RKPM points thrown at 20 m/s out of a [0, 1] grid stop the run as MPM particles do
for m in gmm:mls rkpm:rk_cubic; do
  python3 - "$SRC/examples/column_collapse/case_gmm_mls.json" "${m%%:*}" "${m#*:}" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c.update(method=sys.argv[2], shape_function=sys.argv[3], boundary_conditions=[], probes=[], output={"interval": 0.01})
c["grid"] = {"type": "rectangle", "origin": [0, 0], "size": [1, 1], "cells": [10, 10], "element": "quad4"}
c["bodies"] = [{"name": "block", "material": "soil", "particles_per_cell": 2, "velocity": [20, 0],
                "shape": {"type": "rectangle", "min": [0.3, 0.3], "max": [0.6, 0.6]}}]
c["analysis"].update(gravity=[0, 0], end_time=0.2)
json.dump(c, open("leave_%s.json" % sys.argv[2], "w"))
PY
  expect_exit 1 "${m%%:*} points leaving the grid" "$PMECH" run "leave_${m%%:*}.json" -o "leave_${m%%:*}.out" --quiet
  check "names the step and the particle" grep -Eq "step [0-9]+ .*particle [0-9]+ left the grid at \(1\.0" err.txt
done

# ---- Newton's absolute tolerance: a free disk translating at 0.1 m/s with no load used to fail at step 1
# (its residual is round-off over round-off). Newmark's average acceleration keeps a free body's velocity
# exactly, so the probe must read 0.1 m/s and the centre 0.3 + 0.1 t to round-off (1e-9 relative).
expect_exit 0 "implicit free translation converges" "$PMECH" run "$SRC/tests/verification/cases/implicit_free_translation.json" -o free.out --quiet
check "keeps its velocity and moves 0.05 m in 0.5 s" python3 -c "
import csv, sys
rows = list(csv.DictReader(open('free.out/probes.csv')))
last = rows[-1]
ok = abs(float(last['time']) - 0.5) < 1e-12 and len(rows) == 51
ok = ok and all(abs(float(r['disk.vx']) - 0.1) <= 1e-10 and abs(float(r['disk.vy'])) <= 1e-10 for r in rows)
ok = ok and abs(float(last['pos.x']) - 0.35) <= 1e-9 * 0.35 and abs(float(last['pos.y']) - 0.5) <= 1e-9
sys.exit(0 if ok else 1)"

finish "all refusal checks passed"
