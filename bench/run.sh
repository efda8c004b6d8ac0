#!/bin/sh
# pmech's benchmark suite (not timed tests): particle-steps per second of the time loop (from run.json,
# which excludes set-up and file output) and peak memory per particle, on 1 and 2 threads, for
#   - an elastic 2-D block (linear quad4, MUSL, 2 x 2 particles per cell) at 1e4, 1e5, 1e6, 4e6 particles,
#   - the same block with Mohr-Coulomb (it yields under its own weight) at 1e5 and 1e6,
#   - examples/column_collapse (Mohr-Coulomb, 12,800 points, to t = 2 s),
#   - a seed-004 silo-discharge-sized workload (31,212 points, 77,000 steps, viscoplastic
#     Drucker-Prager, axisymmetric), 2 threads, timed end to end (skip with QUICK=1).
# Prints a Markdown table; with --write it also rewrites the table in docs/performance.md.
# PMECH_SCATTER=buffers in the environment measures the per-thread-buffer scatter instead of colours.
# usage: bench/run.sh [path/to/pmech] [--write]
set -e
PMECH=${1:-build/pmech}
WRITE=${2:-}
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
table="$dir/table.md"
{
  echo "| case | particles | steps | threads | particle-steps/s | loop s | wall s | peak memory (bytes/particle) |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
} > "$table"

run_case() { # name case.json threads
  /usr/bin/time -f "%M" -o "$dir/mem" "$PMECH" run "$2" -o "$dir/out" --overwrite --quiet --threads "$3"
  python3 - "$dir/out/run.json" "$1" "$3" "$(cat "$dir/mem")" >> "$table" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
kb = float(sys.argv[4])
print(f"| {sys.argv[2]} | {r['particles']} | {r['steps']} | {sys.argv[3]} | "
      f"{r['particle_steps_per_second']/1e6:.2f} M | {r['loop_seconds']:.2f} | {r['wall_seconds']:.1f} | "
      f"{kb*1024/r['particles']:.0f} |")
PY
  tail -1 "$table"
}

for n in 1e4 1e5 1e6 4e6; do
  case $n in 1e4) steps=3000;; 1e5) steps=300;; 1e6) steps=40;; *) steps=10;; esac
  python3 "$here/block_case.py" $n $steps > "$dir/block.json"
  for t in 1 2; do run_case "elastic block" "$dir/block.json" $t; done
done
for n in 1e5 1e6; do
  case $n in 1e5) steps=300;; *) steps=40;; esac
  python3 "$here/block_case.py" $n $steps musl mohr_coulomb > "$dir/block_mc.json"
  for t in 1 2; do run_case "Mohr-Coulomb block" "$dir/block_mc.json" $t; done
done
for t in 1 2; do run_case "column collapse" "$here/../examples/column_collapse/case.json" $t; done
if [ -z "$QUICK" ]; then
  python3 "$here/silo_workload.py" 77000 > "$dir/silo.json"
  run_case "silo discharge workload (seed 004: 24.5 h)" "$dir/silo.json" 2
fi
echo
cat "$table"
if [ "$WRITE" = "--write" ]; then
  doc="$here/../docs/performance.md"
  {
    sed -n '1,/<!-- BENCH START -->/p' "$doc"
    echo
    echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')),"
    echo "$(cc --version | head -1), CMake Release build (-O3 -fopenmp), pmech $("$PMECH" --version | cut -d' ' -f2),"
    echo "parallel scatter: ${PMECH_SCATTER:-colour} (PMECH_SCATTER)."
    echo
    cat "$table"
    echo
    sed -n '/<!-- BENCH END -->/,$p' "$doc"
  } > "$dir/doc.md"
  mv "$dir/doc.md" "$doc"
  echo "rewrote $doc"
fi
