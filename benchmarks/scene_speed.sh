#!/bin/bash
# Speed of one scene on 1 and 2 MPI ranks: wall time, time per step, Newton
# and linear iterations per step, peak memory per rank and the largest
# sections of the timer table (from log.txt).
# Usage (from the source root):
#   bash benchmarks/scene_speed.sh [scene.prm] [--set "..."]... [--stop-after N]
# Default scene: prm/seven_spheres_sn.prm. Needs build/densify (or the
# executable named by DENSIFY, e.g. to compare two builds). The paper's
# scene at full fidelity takes hours; time its first steps with, e.g.,
#   bash benchmarks/scene_speed.sh prm/single_layer_sn.prm --stop-after 3
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
scene=${1:-$root/prm/seven_spheres_sn.prm}
shift || true
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mktemp -d)
for np in 1 2; do
  dir=$out/np$np
  # exit code 3: stopped by --stop-after, as asked
  rc=0
  /usr/bin/time -v mpirun --oversubscribe -np $np "${DENSIFY:-$root/build/densify}" "$scene" "$@" \
    --set "Output/Directory=$dir" --set "Output/Interval=0" > "$dir.log" 2> "$dir.time" || rc=$?
  if [ $rc -ne 0 ] && [ $rc -ne 3 ]; then
    echo "densify failed (exit $rc):"; tail -n 3 "$dir.time"; exit $rc
  fi
  rss=$(grep "Maximum resident set size" "$dir.time" | awk '{print $NF}')
  echo "== $np rank(s): $(basename "$scene") $*"
  grep -E "^Densify:" "$dir/log.txt"
  /usr/bin/python3 - "$dir/statistics.csv" "$rss" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
n = len(rows)
wall = float(rows[-1]["wall_seconds"])
newton = sum(int(r["newton_iterations"]) for r in rows)
linear = sum(int(r["linear_iterations"]) for r in rows)
cut = sum(int(r["cutbacks"]) for r in rows)
print(f"steps {n}, wall {wall:.1f} s, {wall / n:.2f} s per step, "
      f"Newton {newton / n:.1f} and linear {linear / n:.1f} iterations per step, "
      f"{cut} cut-backs, peak memory of the largest process {int(sys.argv[2]) / 1024:.0f} MB")
PY
  # the largest timer sections
  grep -E "^\| [A-Z][a-z]+:" "$dir/log.txt" | sort -t'|' -k4 -g -r | head -5
done
