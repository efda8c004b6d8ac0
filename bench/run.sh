#!/bin/sh
# Throughput of explicit MPM: particle-steps per second of the time loop (run.json) for an elastic
# block at 1e4, 1e5 and 1e6 particles (linear quad4, musl), 1 and 2 threads.
# Usage: bench/run.sh [path/to/pmech]   (prints a Markdown table)
set -e
PMECH=${1:-build/pmech}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "| particles | steps | threads | particle-steps/s | wall s |"
echo "|---:|---:|---:|---:|---:|"
for n in 1e4 1e5 1e6; do
  case $n in 1e4) steps=2000;; 1e5) steps=300;; *) steps=40;; esac
  python3 "$(dirname "$0")/block_case.py" $n $steps > "$dir/block.json"
  for t in 1 2; do
    "$PMECH" run "$dir/block.json" -o "$dir/out" --quiet --threads $t
    python3 - "$dir/out/run.json" $t <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print(f"| {r['particles']} | {r['steps']} | {sys.argv[2]} | {r['particle_steps_per_second']/1e6:.2f} M | {r['wall_seconds']:.2f} |")
PY
  done
done
