#!/bin/bash
# What one parameter (a lever: step count, penalty, tolerance...) buys and
# costs: runs one scene to its end once per value of the parameter and prints
# wall time, Newton iterations, cut-backs, augmentations, the largest
# penetration, the final relative density, punch forces and particle volume
# change, so that accuracy can be set against time.
# Usage (from the source root):
#   bash benchmarks/lever_sweep.sh SCENE.prm "Subsection/Name" VALUE... [-- --set ...]
# e.g.
#   bash benchmarks/lever_sweep.sh prm/single_layer_sn_light.prm \
#     "Contact/Penalty factor" 100 30 10
# Arguments after "--" are passed to every run. Needs build/densify; 1 rank;
# run it alone on the machine.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
usage='usage: bash benchmarks/lever_sweep.sh SCENE.prm "Subsection/Name" VALUE... [-- --set ...]'
scene=${1:?$usage}
parameter=${2:?$usage}
shift 2
values=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  values+=("$1")
  shift
done
[ $# -gt 0 ] && shift
[ ${#values[@]} -gt 0 ] || { echo "$usage"; exit 2; }
out=$(mktemp -d)
echo "scene $(basename "$scene"), 1 rank, '$parameter' swept; values at the end of the stroke${*:+; also $*}"
printf "%10s %9s %7s %9s %6s %15s %10s %12s %12s %10s\n" value wall newton cutbacks aug "max penetration" density F_upper F_lower "volume %"
i=0
for value in "${values[@]}"; do
  i=$((i + 1))
  dir=$out/run$i
  rc=0
  /usr/bin/time -f "%e" -o "$dir.time" "$root/build/densify" "$scene" \
    --set "$parameter=$value" --set "Output/Directory=$dir" \
    --set "Output/Interval=0" --set "Output/Checkpoint interval=0" "$@" \
    > "$dir.log" 2>&1 || rc=$?
  if [ $rc -ne 0 ]; then
    echo "$value: densify failed (exit $rc): $(tail -n 1 "$dir.log")"
    continue
  fi
  /usr/bin/python3 - "$dir/statistics.csv" "$(tail -n 1 "$dir.time")" "$value" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
first, last = rows[0], rows[-1]
total = lambda key: sum(int(r[key]) for r in rows)
penetration = max(float(r["max_penetration"]) for r in rows)
# the volume before the first step is not in the file: the change is
# measured from step 1 (elastic, tiny)
dv = 100 * (float(last["particle_volume"]) / float(first["particle_volume"]) - 1)
print("%10s %8.1fs %7d %9d %6d %12.2e mm %9.3f%% %11.2fN %11.2fN %+9.3f%%" % (
    sys.argv[3], float(sys.argv[2]), total("newton_iterations"),
    total("cutbacks"), total("augmentations"), penetration,
    100 * float(last["relative_density"]), float(last["upper_punch_force"]),
    float(last["lower_punch_force"]), dv))
PY
done
rm -rf "$out"
