#!/bin/sh
# Runs the default example and says where its results are and how to look at them.
set -e
PMECH=${1:-build/pmech}
CASE=${2:-examples/elastic_disks/case.json}
name=$(basename "$(dirname "$CASE")")
out="demo-output/$name"
echo "pmech demo: running $CASE"
"$PMECH" run "$CASE" -o "$out" --overwrite
echo
echo "Results are in $out/:"
echo "  particles.pvd   open it in ParaView (File > Open), then press Apply and Play"
echo "  grid.vtu        the background grid"
echo "  probes.csv      probe time histories; energy.csv energies; run.json what ran"
last=$(ls "$out"/particles_*.png 2>/dev/null | tail -n 1)
if [ -n "$last" ]; then
  n=$(ls "$out"/particles_*.png | wc -l)
  echo "  particles_NNNNNN.png   a picture of each of the $n frames; the last: $last"
fi
echo "Redraw the pictures coloured by another field, and make an animation (needs ffmpeg):"
echo "  $PMECH render $out --field pressure --animation $out/pressure.gif"
