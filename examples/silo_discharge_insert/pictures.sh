#!/bin/sh
# The README's pictures, animation and column table from a run of discharge_insert_rectangle.json:
#   sh examples/silo_discharge_insert/pictures.sh RUN_DIR
# The pictures are the run's own (output.pictures: grid_speed, fixed range 0-1, one per 0.05 s frame):
# at the opening (frame 20, t = 1 s) and 0.25, 0.5, 0.75, 1, 1.5 and 2 s after it, and the animation of
# every frame of the discharge. Writes into this directory; the column table goes to standard output.
set -eu
run=$1
here=$(dirname "$0")
for k in 20:0.00 25:0.25 30:0.50 35:0.75 40:1.00 50:1.50 60:2.00; do
  png=$run/particles_0000${k%:*}.png
  if [ -f "$png" ]; then cp "$png" "$here/grid_speed_after_${k#*:}s.png"; fi
done
ffmpeg -loglevel error -y -framerate 8 -start_number 20 -i "$run/particles_%06d.png" \
  -vf "scale=240:-1,split[a][b];[a]palettegen=max_colors=48[p];[b][p]paletteuse" "$here/silo_discharge_insert.gif"
python3 "$here/column_speed.py" "$run"
