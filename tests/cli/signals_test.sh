#!/bin/sh
# Output directories and signals: -o "" refused; a directory holding an earlier run's outputs refused
# (nothing in it touched) unless --overwrite; a directory another run is writing refused; SIGINT and
# SIGTERM stop the run after its step with exit 130 / 143, run.json saying so and every frame readable;
# a second signal ends the process at once, leaving the files written so far whole.
# usage: signals_test.sh PMECH SOURCE_DIR WORK_DIR
set -u
PMECH=$1; SRC=$2; WORK=$3
. "$SRC/tests/cli/test_lib.sh"
# a run of about 10 s on one core: long enough to be interrupted after its first frames
sed 's/"end_time": 3.5/"end_time": 30/; s/"interval": 0.05/"interval": 0.2/; s/, "pictures": "speed"//' \
  "$SRC/examples/elastic_disks/case.json" > long.json
sed 's/"end_time": 30/"end_time": 0.1/' long.json > short.json

# ---- output directories
expect_exit 2 '-o ""' "$PMECH" run short.json -o "" --quiet
check "says the directory is empty" has "output directory is empty" err.txt
check "wrote nothing into the current directory" sh -c '! ls | grep -q "particles\|run.json"'
expect_exit 0 "a first run" "$PMECH" run short.json -o a.out --quiet
echo "my notes" > a.out/notes.txt
cp a.out/run.json first_run.json
expect_exit 2 "a second run into the same directory" "$PMECH" run short.json -o a.out --quiet
check "names the directory, an output and --overwrite" sh -c 'grep -q "a.out" err.txt && grep -q "run.json" err.txt && grep -q -- "--overwrite" err.txt'
check "the earlier outputs are untouched" cmp -s a.out/run.json first_run.json
expect_exit 0 "with --overwrite" "$PMECH" run short.json -o a.out --quiet --overwrite
check "the user's own file is kept" has "my notes" a.out/notes.txt
"$PMECH" run long.json -o busy.out --quiet --threads 1 2>/dev/null & busy=$!
i=0; while [ ! -f busy.out/particles_000001.vtu ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
expect_exit 2 "a directory another run is writing" "$PMECH" run short.json -o busy.out --quiet --overwrite
check "names the other process" has "in use by another pmech run (process $busy)" err.txt
kill -TERM $busy; wait $busy

# ---- signals
interrupt() { # signal, directory: start a run, wait for its second frame, send the signal
  "$PMECH" run long.json -o "$2" --quiet --threads 1 >out.txt 2>err.txt & pid=$!
  i=0; while [ ! -f "$2/particles_000001.vtu" ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
  kill -"$1" $pid; wait $pid; rc=$?
}
for sig in INT:130 TERM:143; do
  s=${sig%%:*}; code=${sig#*:}
  interrupt "$s" "$s.out"
  check "SIG$s: exit $code" [ "$rc" -eq "$code" ]
  check "SIG$s: says so and where the results are" sh -c "grep -q 'interrupted by SIG$s after step' err.txt && grep -q 'results written so far are in $s.out' err.txt"
  check "SIG$s: run.json records it" python3 -c "
import json, sys
r = json.load(open('$s.out/run.json'))
sys.exit(0 if r['exit_status'] == $code and r['interrupted'] == 'SIG$s' and 0 < r['end_time'] < 30 else 1)"
  n=$(python3 -c "import json; print(json.load(open('$s.out/run.json'))['particles'])")
  check "SIG$s: every frame reads back, no temporary file" python3 "$SRC/tests/io/vtk_readback.py" "$s.out" "$n"
done
# a second signal: out at once; what is on disk is whole (particles.pvd lists complete frames only)
"$PMECH" run long.json -o twice.out --quiet --threads 1 >out.txt 2>err.txt & pid=$!
i=0; while [ ! -f twice.out/particles_000001.vtu ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
kill -INT $pid; kill -INT $pid; wait $pid; rc=$?
check "two SIGINTs: exit 130" [ "$rc" -eq 130 ]
check "two SIGINTs: particles.pvd parses and every frame it lists is complete" python3 -c "
import os, sys, xml.etree.ElementTree as ET
pvd = ET.parse('twice.out/particles.pvd').getroot()
files = [d.get('file') for d in pvd.iter('DataSet')]
whole = all(open(os.path.join('twice.out', f), 'rb').read().rstrip().endswith(b'</VTKFile>') for f in files)
sys.exit(0 if whole and len(files) >= 2 else 1)"
# (the second signal may reach a run still in its step, or one already writing its checkpoint and
# run.json: either way run.json must say what happened)
check "two SIGINTs: run.json says the run was interrupted" python3 -c "
import json, sys
r = json.load(open('twice.out/run.json'))
sys.exit(0 if r['exit_status'] == 130 and r['interrupted'] == 'SIGINT' else 1)"
# a second signal while the first is handled, for certain: two different signals (same ones would merge)
# made pending in a stopped process arrive one after the other when it continues; the second ends the
# run at once, and its run.json says so
"$PMECH" run long.json -o second.out --quiet --threads 1 >out.txt 2>err.txt & pid=$!
i=0; while [ ! -f second.out/particles_000001.vtu ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
kill -STOP $pid; kill -INT $pid; kill -TERM $pid; kill -CONT $pid; wait $pid; rc=$?
check "SIGINT then SIGTERM: out at once with 128 + the second (exit $rc)" sh -c "[ $rc -eq 143 ] || [ $rc -eq 130 ]"
check "SIGINT then SIGTERM: run.json says a second signal stopped the run" python3 -c "
import json, sys
r = json.load(open('second.out/run.json'))
sys.exit(0 if r['exit_status'] == $rc and r['interrupted'] in ('SIGINT', 'SIGTERM') and 'a second' in r['message'] else 1)"
# (a file being written at that moment stays behind as NAME.tmp, beside the whole one it would have
# replaced; the next run into the directory removes it)
check "SIGINT then SIGTERM: every frame in particles.pvd is whole" python3 -c "
import os, sys, xml.etree.ElementTree as ET
pvd = ET.parse('second.out/particles.pvd').getroot()
files = [d.get('file') for d in pvd.iter('DataSet')]
whole = all(open(os.path.join('second.out', f), 'rb').read().rstrip().endswith(b'</VTKFile>') for f in files)
sys.exit(0 if whole and files else 1)"

finish "all output-directory and signal checks passed"
