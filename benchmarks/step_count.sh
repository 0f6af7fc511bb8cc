#!/bin/bash
# What the number of load steps buys and costs: runs one scene to its end
# once per step count and prints wall time, Newton iterations, cut-backs,
# the final relative density, punch forces and particle volume change, so
# that accuracy can be set against time (mission item 1).
# Usage (from the source root):
#   bash benchmarks/step_count.sh [scene.prm] [N1 N2 ...]
# Default: prm/single_layer_sn_light.prm with 128 (the scene's), 64, 32 and
# 16 steps. Needs build/densify; 1 rank; run it alone on the machine.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
scene=${1:-$root/prm/single_layer_sn_light.prm}
shift || true
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(128 64 32 16)
out=$(mktemp -d)
echo "scene $(basename "$scene"), 1 rank; final values at the end of the stroke"
printf "%6s %9s %7s %9s %10s %12s %12s %10s\n" steps wall newton cutbacks density F_upper F_lower "volume %"
for n in "${counts[@]}"; do
  dir=$out/n$n
  rc=0
  /usr/bin/time -f "%e" -o "$dir.time" "$root/build/densify" "$scene" \
    --set "Time stepping/Number of steps=$n" --set "Output/Directory=$dir" \
    --set "Output/Interval=0" --set "Output/Checkpoint interval=0" \
    > "$dir.log" 2>&1 || rc=$?
  if [ $rc -ne 0 ]; then
    echo "$n steps: densify failed (exit $rc): $(tail -n 1 "$dir.log")"
    continue
  fi
  /usr/bin/python3 - "$dir/statistics.csv" "$(tail -n 1 "$dir.time")" "$n" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
first, last = rows[0], rows[-1]
newton = sum(int(r["newton_iterations"]) for r in rows)
cutbacks = sum(int(r["cutbacks"]) for r in rows)
# the volume before the first step: step 1's initial value is not in the
# file, so the change is measured from step 1 (elastic, tiny)
dv = 100 * (float(last["particle_volume"]) / float(first["particle_volume"]) - 1)
print("%6s %8.1fs %7d %9d %9.3f%% %11.2fN %11.2fN %+9.3f%%" % (
    sys.argv[3], float(sys.argv[2]), newton, cutbacks,
    100 * float(last["relative_density"]), float(last["upper_punch_force"]),
    float(last["lower_punch_force"]), dv))
PY
done
rm -rf "$out"
