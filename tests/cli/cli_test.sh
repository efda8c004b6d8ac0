#!/bin/sh
# End-to-end checks of the pmech program: help/version, exit codes and messages for bad input,
# a diverging run (exit 1, names step and particle, every file written so far still valid), and a
# real run whose VTU files VTK's own reader opens.
# usage: cli_test.sh PMECH SOURCE_DIR WORK_DIR
set -u
PMECH=$1; SRC=$2; WORK=$3
. "$SRC/tests/cli/test_lib.sh"

expect_exit 0 "--version" "$PMECH" --version
check "version printed" has "pmech " out.txt
expect_exit 0 "--help" "$PMECH" --help
check "help names run" has "pmech run" out.txt
expect_exit 0 "run --help" "$PMECH" run --help
check "run --help lists --threads" has "--threads N" out.txt
expect_exit 0 "material --help" "$PMECH" material --help
check "material --help gives usage" has "pmech material DRIVER.json" out.txt
expect_exit 0 "render --help" "$PMECH" render --help
check "render --help lists --field" has "--field F" out.txt
"$PMECH" --help > all.txt
for cmd in run material render; do
  "$PMECH" $cmd --help > sub.txt
  check "pmech --help holds every line of pmech $cmd --help" sh -c 'grep -v "^$" sub.txt | while IFS= read -r l; do grep -qxF -- "$l" all.txt || exit 1; done'
done
# pmech run makes waiting OpenMP threads sleep unless the user chose: the runtime it starts again shows a
# spin count of 0; a policy the user set is kept.
OMP_DISPLAY_ENV=verbose "$PMECH" run nothing.json >/dev/null 2>wait.txt
check "run restarts with passive waiting" sh -c "grep GOMP_SPINCOUNT wait.txt | tail -1 | grep -q \"'0'\""
OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose "$PMECH" run nothing.json >/dev/null 2>wait.txt
check "a policy set by the user is kept" sh -c "grep -c GOMP_SPINCOUNT wait.txt | grep -qx 1 && ! grep GOMP_SPINCOUNT wait.txt | grep -q \"'0'\""
expect_exit 2 "render without a run" "$PMECH" render nowhere --field speed
check "render says what it looked for" has "nowhere" err.txt
expect_exit 2 "render without a field" "$PMECH" render . --quiet
expect_exit 2 "no arguments" "$PMECH"
expect_exit 2 "unknown command" "$PMECH" frobnicate
expect_exit 2 "missing case file" "$PMECH" run does-not-exist.json
expect_exit 2 "bad option" "$PMECH" run "$SRC/examples/elastic_disks/case.json" --frob

printf '{ "dimension": 2,\n  "analysis": { "type": "explicit" "end_time": 1 } }\n' > syntax.json
expect_exit 2 "JSON syntax error" "$PMECH" run syntax.json
check "syntax error names file:line:column" grep -Eq 'syntax.json:2:[0-9]+' err.txt

sed 's/"youngs_modulus": 1000/"youngs_modulus": -5/' "$SRC/examples/elastic_disks/case.json" > negE.json
expect_exit 2 "negative Young's modulus" "$PMECH" run negE.json
check "message names materials[0].youngs_modulus" has "materials\[0\].youngs_modulus" err.txt

sed 's/"particles_per_cell"/"particles_per_cel"/' "$SRC/examples/elastic_disks/case.json" > typo.json
expect_exit 2 "unknown key" "$PMECH" run typo.json
check "did you mean" has "did you mean 'particles_per_cell'" err.txt

sed 's/"center": \[0.25, 0.25\], "radius": 0.2/"center": [5.25, 0.25], "radius": 0.2/' "$SRC/examples/elastic_disks/case.json" > outside.json
expect_exit 2 "body outside the grid" "$PMECH" run outside.json
check "names the body" has "bodies\[0\]" err.txt

sed 's/"radius": 0.2 }, *$/"radius": 0.001 },/; s/"center": \[0.25, 0.25\], "radius": 0.2/"center": [0.26, 0.26], "radius": 0.0001/' "$SRC/examples/elastic_disks/case.json" > tiny.json
expect_exit 2 "body that yields no particle" "$PMECH" run tiny.json
check "says no particle" has "yields no particle" err.txt

# A value that is valid but almost surely a unit mistake: a warning, printed and in run.json; the run goes on.
sed 's/"youngs_modulus": 1000,/"youngs_modulus": 5,/' "$SRC/examples/elastic_disks/case.json" > softE.json
sed -i 's/"end_time": 3.5/"end_time": 0.05/' softE.json
expect_exit 0 "a modulus of 5 Pa runs" "$PMECH" run softE.json -o softE.out
check "with a warning naming the key" has "warning: .*materials\[0\].youngs_modulus" err.txt
check "listed in run.json" python3 -c "import json,sys; w=json.load(open('softE.out/run.json'))['warnings']; sys.exit(0 if len(w)==1 and 'below 1 kPa' in w[0] else 1)"

# With a fixed step of 1e-4 s and an end time a nanosecond past step 500, the last step is cut to 1e-9 s to
# land on it; that is not a collapsing step: no warning, and run.json's smallest step is the fixed one.
sed 's/"end_time": 3.5, "cfl": 0.2/"end_time": 0.050000001, "dt": 1e-4/' "$SRC/examples/elastic_disks/case.json" > lastcut.json
expect_exit 0 "an end time a nanosecond past a step" "$PMECH" run lastcut.json -o lastcut.out --quiet
check "no step-size warning for the cut last step" python3 -c "import json,sys; r=json.load(open('lastcut.out/run.json')); sys.exit(0 if not r['warnings'] and r['dt_min'] == 1e-4 else 1)"

# A misspelt scatter strategy is refused rather than timed as the default.
PMECH_SCATTER=bogus expect_exit 2 "PMECH_SCATTER=bogus" "$PMECH" run "$SRC/examples/elastic_disks/case.json" -o scatter.out --quiet
check "names the variable, the value and the allowed ones" sh -c 'grep -q "PMECH_SCATTER" err.txt && grep -q "bogus" err.txt && grep -q "colour" err.txt && grep -q "buffers" err.txt'

# A run that stops: a disk thrown at 30 m/s leaves the [0, 1] grid after about 0.02 s.
sed 's/"velocity": \[0.1, 0.1\]/"velocity": [30, 0]/; s/"interval": 0.05/"interval": 0.005/' "$SRC/examples/elastic_disks/case.json" > diverge.json
expect_exit 1 "a body leaving the grid" "$PMECH" run diverge.json -o diverge.out --quiet
check "names the step" grep -Eq 'step [0-9]+' err.txt
check "names the particle" grep -Eq 'particle [0-9]+' err.txt
check "run.json records exit 1" python3 -c "import json,sys; r=json.load(open('diverge.out/run.json')); sys.exit(0 if r['exit_status']==1 and 'particle' in r['message'] else 1)"
check "no temporary files left" sh -c '! ls diverge.out | grep -q tmp'
nd=$(python3 -c "import json; print(json.load(open('diverge.out/run.json'))['particles'])")
check "frames written so far are readable" python3 "$SRC/tests/io/vtk_readback.py" diverge.out "$nd"

# A real run, read back by VTK.
expect_exit 0 "elastic disks run" "$PMECH" run "$SRC/examples/elastic_disks/case.json" -o disks.out --quiet
n=$(python3 -c "import json; print(json.load(open('disks.out/run.json'))['particles'])")
check "VTK reads every frame" python3 "$SRC/tests/io/vtk_readback.py" disks.out "$n"
check "probes.csv header" sh -c 'head -1 disks.out/probes.csv | grep -q "^time,lower.vx,lower.vy,upper.vx,upper.vy$"'
check "energy.csv header" sh -c 'head -1 disks.out/energy.csv | grep -q "^time,kinetic,strain,gravity,total$"'
check "energy.csv has one row per time" sh -c '[ -z "$(cut -d, -f1 disks.out/energy.csv | sort | uniq -d)" ]'
check "run.json speed" python3 -c "import json,sys; r=json.load(open('disks.out/run.json')); sys.exit(0 if r['particle_steps_per_second']>0 and r['steps']>0 else 1)"

# The speed of a run whose particle count grows: six portions of 32 points released every 0.03 s from
# t = 0 into a run of 2000 steps of 1e-4 s. The particles actually stepped are, per release, its count
# times the steps left after it (releases.csv): 32 (2000 + 1700 + ... + 500) = 240,000, four times the
# 64,000 the first portion's count alone gives. run.json's speed must be that sum over its loop seconds
# (to rounding, 1e-9) and the progress line's last rate the same to its three printed digits (0.5 %).
cat > fill.json <<'CASE'
{ "dimension": 2,
  "analysis": { "type": "explicit", "scheme": "musl", "end_time": 0.2, "dt": 1.0e-4, "gravity": [0.0, -9.81] },
  "grid": { "type": "rectangle", "origin": [0.0, 0.0], "size": [0.5, 0.5], "cells": [10, 10] },
  "materials": [ { "name": "grain", "model": "linear_elastic", "density": 1500, "youngs_modulus": 1.0e6,
                   "poisson_ratio": 0.3 } ],
  "sources": [ { "name": "hopper", "material": "grain", "shape": { "type": "rectangle", "min": [0.1, 0.3], "max": [0.3, 0.4] },
                 "particles_per_cell": 2, "period": 0.03, "until": 0.15 } ],
  "boundary_conditions": [ { "type": "fixed", "boundary": "y_min", "directions": ["x", "y"] } ],
  "output": { "interval": 0.1 } }
CASE
expect_exit 0 "a filling run" "$PMECH" run fill.json -o fill.out --threads 1
check "the speed counts the particles stepped, not those at the start" python3 -c "
import csv, json, re, sys
r = json.load(open('fill.out/run.json'))
rel = list(csv.DictReader(open('fill.out/releases.csv')))
stepped = sum(int(q['particles']) * round((r['end_time'] - float(q['time'])) / 1e-4) for q in rel)
want = stepped / r['loop_seconds']
line = [l for l in open('err.txt') if 'particle-steps/s' in l][-1]
shown = float(re.search(r'([0-9.e+-]+) M particle-steps/s', line).group(1)) * 1e6
print('stepped %d, run.json %.6g/s, progress %.3g/s, wanted %.6g/s' % (stepped, r['particle_steps_per_second'], shown, want))
sys.exit(0 if stepped == 240000 and abs(r['particle_steps_per_second'] / want - 1) < 1e-9 and abs(shown / want - 1) < 5e-3 else 1)"

# Wall profiles of a quasi-static run: a block 0.4 x 0.2 m of 1000 kg/m^3 on a friction floor, gravity
# in four load steps, frames at loads 0.5 and 1. Each frame's profile is its last load step's (an
# average over the steps since the frame before would give 0.75 of the weight at the first): integrated
# along the floor it is the block's weight at that load, 392.4 and 784.8 N/m, to the Newton tolerance
# (1e-6 relative; the profile only regroups the nodal forces).
cat > qs_block.json <<'CASE'
{ "dimension": 2,
  "analysis": { "type": "quasi_static", "end_time": 1.0, "load_steps": 4, "gravity": [0.0, -9.81] },
  "grid": { "type": "rectangle", "origin": [0.0, 0.0], "size": [0.6, 0.4], "cells": [12, 8] },
  "materials": [ { "name": "block", "model": "linear_elastic", "density": 1000, "youngs_modulus": 1.0e6,
                   "poisson_ratio": 0.3 } ],
  "bodies": [ { "name": "block", "material": "block", "shape": { "type": "rectangle", "min": [0.1, 0.0], "max": [0.5, 0.2] },
                "particles_per_cell": 2 } ],
  "boundary_conditions": [ { "type": "fixed", "boundary": { "x": 0.3 }, "directions": ["x"] },
                           { "type": "friction", "boundary": "y_min", "coefficient": 0.3 } ],
  "output": { "interval": 0.5 } }
CASE
expect_exit 0 "a quasi-static block on a friction floor" "$PMECH" run qs_block.json -o qs_block.out --quiet
check "its floor profile carries the weight of each frame's load" python3 -c "
import csv, sys
rows = list(csv.DictReader(open('qs_block.out/wall_boundary_conditions1.csv')))
ok = True
for t, want in ((0.5, 392.4), (1.0, 784.8)):
    st = [r for r in rows if abs(float(r['time']) - t) < 1e-9]
    h = float(st[1]['s']) - float(st[0]['s'])
    share = [0.5 * h if j in (0, len(st) - 1) else h for j in range(len(st))]
    fn = sum(float(r['normal']) * w for r, w in zip(st, share))
    ft = sum(float(r['tangent']) * w for r, w in zip(st, share))
    print('t = %g: normal %.6g N/m (weight %.6g), tangential %.3g' % (t, fn, want, ft))
    ok &= abs(fn / want - 1) < 1e-6 and abs(ft) < 1e-6 * want
sys.exit(0 if ok else 1)"

# Pictures redrawn from the frames of that run: one per frame, any field.
frames=$(python3 -c "import json; print(json.load(open('disks.out/run.json'))['frames'])")
expect_exit 0 "render q" "$PMECH" render disks.out --field q -o pics --quiet
check "one picture per frame" sh -c "[ \$(ls pics/q_*.png | wc -l) -eq $frames ]"
expect_exit 2 "render an unknown field" "$PMECH" render disks.out --field nonsense -o pics --quiet
check "lists the fields" has "deviatoric_strain" err.txt

# Body-body contact: a pair naming no body is refused with its key path; a short run writes the
# force between the pair.
sed 's/"probes": \[/"contact_pairs": [ { "bodies": ["lower", "uper"], "law": "frictionless" } ],\n  "probes": [/' "$SRC/examples/elastic_disks/case.json" > pair_bad.json
expect_exit 2 "a contact pair naming no body" "$PMECH" run pair_bad.json -o pair_bad.out --quiet
check "names contact_pairs[0].bodies[1] and the groups" sh -c 'grep -q "contact_pairs\[0\].bodies\[1\]" err.txt && grep -q "uper" err.txt && grep -q "lower, upper" err.txt'
sed 's/"probes": \[/"contact_pairs": [ { "bodies": ["lower", "upper"], "law": "coulomb", "friction": 0.2 } ],\n  "probes": [/; s/"end_time": 3.5/"end_time": 1.3/; s/, "pictures": "speed"//' "$SRC/examples/elastic_disks/case.json" > pair.json
expect_exit 0 "disks with a Coulomb contact pair" "$PMECH" run pair.json -o pair.out --quiet
check "contact_forces.csv header" sh -c 'head -1 pair.out/contact_forces.csv | grep -q "^time,first,second,fx,fy$"'
check "the disks push each other apart" python3 -c "
import csv, sys
rows = list(csv.DictReader(open('pair.out/contact_forces.csv')))
sys.exit(0 if rows[0]['first'] == 'lower' and min(float(r['fx']) + float(r['fy']) for r in rows) < 0 else 1)"

finish "all CLI checks passed"
