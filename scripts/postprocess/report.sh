#!/usr/bin/env bash
# Everything scripts/postprocess/ makes of one run, into its output directory:
# density.png, forces.png, curves.csv, and with a die compaction.png and for
# a press cycle that ejects ejection.png (plot_statistics.py), the per-particle
# table of the last output step (particle_table.py), view_top.png and
# view_oblique.png coloured by plastic strain (render.py), then the summary
# (summary.py). Usage: bash scripts/postprocess/report.sh OUTPUT_DIR
set -euo pipefail
if [ $# -ne 1 ]; then
  echo "usage: bash scripts/postprocess/report.sh OUTPUT_DIR" >&2
  exit 2
fi
dir=$1
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
python=${PYTHON:-/usr/bin/python3}
"$python" "$here/plot_statistics.py" "$dir"
"$python" "$here/particle_table.py" "$dir" --step -1
"$python" "$here/render.py" "$dir"
echo
"$python" "$here/summary.py" "$dir"
