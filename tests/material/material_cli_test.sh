#!/bin/sh
# `pmech material` end to end, and invalid material parameters rejected with exit 2 and the key
# path by both `pmech material` and `pmech run`.
# usage: material_cli_test.sh PMECH SOURCE_DIR WORK_DIR
set -u
PMECH=$1; SRC=$2; WORK=$3
. "$SRC/tests/cli/test_lib.sh"

TRI="$SRC/examples/triaxial/triaxial.json"
expect_exit 0 "triaxial to stdout" "$PMECH" material "$TRI"
check "CSV header" sh -c 'head -1 out.txt | grep -qx "step,exx,eyy,ezz,exy,sxx,syy,szz,sxy,p,q,eps_p"'
check "one row per step including step 0" sh -c '[ $(wc -l < out.txt) -eq 502 ]'
check "peak q = q_f within 0.5 %" python3 -c "
import csv, math, sys
q = max(float(r['q']) for r in csv.DictReader(open('out.txt')))
s = math.sin(math.radians(30)); qf = 2 * (1e4 * math.cos(math.radians(30)) + 1e5 * s) / (1 - s)
sys.exit(0 if abs(q - qf) <= 0.005 * qf else 1)"
expect_exit 0 "triaxial with -o" "$PMECH" material "$TRI" -o tri.csv
check "-o writes the file, not stdout" sh -c '[ -s tri.csv ] && [ ! -s out.txt ]'
expect_exit 2 "no driver file" "$PMECH" material
expect_exit 2 "missing driver file" "$PMECH" material does-not-exist.json
expect_exit 2 "bad option" "$PMECH" material "$TRI" --frob

# a step the model cannot take: exit 1 naming the step, the model and the trial stress; the rows written
# before it are complete and finite (no inf/NaN rows)
cat > blowup.json <<'EOF'
{ "material": { "model": "mohr_coulomb", "density": 2000, "youngs_modulus": 2e7, "poisson_ratio": 0.3,
                "cohesion": 1e4, "friction_angle": 30, "dilatancy_angle": 0 },
  "initial_stress": [-1e5, -1e5, -1e5, 0],
  "path": { "type": "strain_increments", "increments": [[0, -0.001, 0, 0], [1e300, 0, 0, 1e300], [0, 0, 0, 0]] } }
EOF
expect_exit 1 "a strain increment of 1e300" "$PMECH" material blowup.json -o blowup.csv
check "names the step, the model and the trial stress" sh -c 'grep -q "driver step 2" err.txt && grep -q "mohr_coulomb" err.txt && grep -q "elastic trial stress = (2.69231e+307" err.txt'
check "rows before it are finite, none after" python3 -c "
import csv, math, sys
rows = list(csv.DictReader(open('blowup.csv')))
sys.exit(0 if len(rows) == 2 and all(math.isfinite(float(v)) for r in rows for v in r.values()) else 1)"

# invalid parameters: pmech material
bad_driver() { # description, sed expression, key expected in the message
  sed "$2" "$TRI" > bad.json
  expect_exit 2 "material: $1" "$PMECH" material bad.json
  check "material: message names $3" has "$3" err.txt
}
bad_driver "friction angle 90" 's/"friction_angle": 30/"friction_angle": 90/' "material.friction_angle"
bad_driver "negative cohesion" 's/"cohesion": 1e4/"cohesion": -1/' "material.cohesion"
bad_driver "dilatancy above friction" 's/"dilatancy_angle": 0/"dilatancy_angle": 35/' "material.dilatancy_angle"
sed 's/"cone_fit": -1/"cone_fit": 1.5/' "$SRC/examples/triaxial/triaxial_dp.json" > bad.json
expect_exit 2 "material: cone_fit 1.5" "$PMECH" material bad.json
check "material: message names material.cone_fit" has "material.cone_fit" err.txt

# invalid parameters: pmech run
CASE="$SRC/examples/column_collapse/case.json"
bad_case() {
  sed "$2" "$CASE" > badcase.json
  expect_exit 2 "run: $1" "$PMECH" run badcase.json -o bad.out --quiet
  check "run: message names $3" has "$3" err.txt
}
bad_case "friction angle 95" 's/"friction_angle": 25/"friction_angle": 95/' "materials\[0\].friction_angle"
bad_case "negative cohesion" 's/"cohesion": 5.0e3/"cohesion": -5/' "materials\[0\].cohesion"
bad_case "dilatancy above friction" 's/"dilatancy_angle": 0/"dilatancy_angle": 30/' "materials\[0\].dilatancy_angle"

finish "all material CLI checks passed"
