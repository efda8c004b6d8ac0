#!/bin/sh
# Runs the default example and says where its results are and how to look at them.
set -e
PMECH=${1:-build/pmech}
CASE=${2:-examples/elastic_disks/case.json}
name=$(basename "$(dirname "$CASE")")
out="demo-output/$name"
echo "pmech demo: running $CASE"
"$PMECH" run "$CASE" -o "$out"
echo
echo "Results are in $out/:"
echo "  particles.pvd   open it in ParaView (File > Open), then press Apply and Play"
echo "  grid.vtu        the background grid"
echo "  probes.csv      probe time histories; energy.csv energies; run.json what ran"
if [ -f "$out/particles.png" ]; then echo "  particles.png   a picture of the last frame"; fi
