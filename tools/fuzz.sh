#!/bin/sh
# Long fuzzing runs (make fuzz): every libFuzzer target of a PMECH_FUZZ build runs for SECONDS, all at
# once (nice -n 10), growing its corpus in BUILD/fuzz-work/<target>. Inputs that crash, leak, hang or
# trip a sanitizer are saved as BUILD/fuzz-crashes/<target>-crash-<sha1> (or leak-, timeout-, oom-)
# and listed at the end; the exit status is 1 when there is one, 77 when BUILD has no fuzz targets
# (no clang or libFuzzer: ctest reports the test as skipped).
# usage: tools/fuzz.sh BUILD SECONDS TARGET...
set -u
build=$1 seconds=$2
shift 2
for t in "$@"; do
  if [ ! -x "$build/tests/fuzz_$t" ]; then
    echo "fuzz: $build/tests/fuzz_$t was not built (no clang with libFuzzer, see test fuzz.build): skipped"
    exit 77
  fi
done
src=$(cd "$(dirname "$0")/.." && pwd)
crashes="$build/fuzz-crashes"
mkdir -p "$crashes"
# libFuzzer also saves slow-unit-* files (an input slower than 10 s): information, not a failure
failures() { ls -t "$crashes" | grep -v -e '-slow-unit-'; }
before=$(failures | wc -l)
# Dictionaries: the case and driver keys and words are every quoted identifier of the readers' sources
# (always current) after tests/fuzz/json.dict; the Gmsh one is tests/fuzz/gmsh.dict.
mkdir -p "$build/fuzz-dict"
grep -oh '"[a-z][a-z0-9_]*"' "$src"/src/io/case_*.c "$src"/src/io/json_read.c "$src"/src/io/material_read.c \
  "$src"/src/io/driver_file.c "$src"/src/material/*.c | sort -u | sed 's/"/\\"/g; s/.*/"&"/' >"$build/fuzz-dict/words.dict"
cat "$src/tests/fuzz/json.dict" "$build/fuzz-dict/words.dict" >"$build/fuzz-dict/case_sim.dict"
cp "$build/fuzz-dict/case_sim.dict" "$build/fuzz-dict/driver.dict"
cp "$src/tests/fuzz/gmsh.dict" "$build/fuzz-dict/gmsh.dict"
# One input may take 120 s before it counts as a hang: the stepping case target needs up to 45 s for
# one Newton step under the sanitizers on a machine loaded 25-fold, and a busy CI machine must not
# report that as a failure. A real hang never ends, so the limit still catches it.
pids=""
for t in "$@"; do
  mkdir -p "$build/fuzz-work/$t"
  echo "fuzz: $t for $seconds s (log: $build/fuzz-$t.log)"
  nice -n 10 "$build/tests/fuzz_$t" -max_total_time="$seconds" -timeout="${PMECH_FUZZ_UNIT_TIMEOUT:-120}" -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$crashes/$t-" -dict="$build/fuzz-dict/$t.dict" \
    "$build/fuzz-work/$t" "$build/fuzz-seeds/$t" "$src/tests/fuzz/corpus/$t" >"$build/fuzz-$t.log" 2>&1 &
  pids="$pids $!"
done
status=0
for p in $pids; do
  wait "$p" || status=1
done
for t in "$@"; do
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$build/fuzz-$t.log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$build/fuzz-$t.log" | tail -1)
  echo "fuzz: $t: ${runs:-?} inputs, $cov, corpus $(ls "$build/fuzz-work/$t" | wc -l) files"
done
after=$(failures | wc -l)
if [ "$status" -ne 0 ] || [ "$after" -ne "$before" ]; then
  echo "fuzz: FAILED: inputs saved in $crashes:"
  failures | head -n $((after - before + 1)) | sed 's/^/  /'
  echo "fuzz: reproduce with $build/tests/fuzz_TARGET FILE; add the input to tests/fuzz/corpus/TARGET once fixed"
  exit 1
fi
echo "fuzz: no crash, leak, hang or sanitizer report"
