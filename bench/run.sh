#!/bin/sh
# Throughput of explicit MPM: particle-steps per second of the time loop (from run.json, which excludes
# set-up and file output) for an elastic 2-D block (linear quad4, musl, 2 x 2 particles per cell) at
# 1e4, 1e5 and 1e6 particles, on 1 and 2 threads. Prints a Markdown table; with --write it also
# rewrites the table in docs/performance.md between the BENCH markers.
# usage: bench/run.sh [path/to/pmech] [--write]
set -e
PMECH=${1:-build/pmech}
WRITE=${2:-}
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
table="$dir/table.md"
{
  echo "| particles | steps | threads | particle-steps/s | loop s | peak memory (bytes/particle) |"
  echo "|---:|---:|---:|---:|---:|---:|"
} > "$table"
for n in 1e4 1e5 1e6; do
  case $n in 1e4) steps=3000;; 1e5) steps=300;; *) steps=40;; esac
  python3 "$here/block_case.py" $n $steps > "$dir/block.json"
  for t in 1 2; do
    /usr/bin/time -f "%M" -o "$dir/mem" "$PMECH" run "$dir/block.json" -o "$dir/out" --quiet --threads $t
    python3 - "$dir/out/run.json" $t "$(cat "$dir/mem")" >> "$table" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
kb = float(sys.argv[3])
print(f"| {r['particles']} | {r['steps']} | {sys.argv[2]} | {r['particle_steps_per_second']/1e6:.2f} M "
      f"| {r['loop_seconds']:.2f} | {kb*1024/r['particles']:.0f} |")
PY
  done
done
cat "$table"
if [ "$WRITE" = "--write" ]; then
  doc="$here/../docs/performance.md"
  {
    sed -n '1,/<!-- BENCH START -->/p' "$doc"
    echo
    echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')),"
    echo "$(cc --version | head -1), Release build (-O3), pmech $("$PMECH" --version | cut -d' ' -f2)."
    echo
    cat "$table"
    echo
    sed -n '/<!-- BENCH END -->/,$p' "$doc"
  } > "$dir/doc.md"
  mv "$dir/doc.md" "$doc"
  echo "rewrote $doc"
fi
