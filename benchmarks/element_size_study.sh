#!/bin/bash
# The discretisation error of a scene's punch pressure: the same scene by the
# implicit method on several element sizes (two runs at a time, one rank
# each), then for each size the upper punch pressure (F_upper / die area) at
# given relative densities of the meshed particles (interpolated between
# the load steps), the force at given strokes, the initial density of the
# mesh, the smallest V/V0 and the wall time. Meshes of different size hold
# different particle volumes (the faceted spheres), so the same stroke
# gives different densities: the pressure at equal density is the
# comparable quantity.
# Usage (from the source root):
#   bash benchmarks/element_size_study.sh OUT STROKE "SIZES" [--set ...]...
# e.g. the light paper layer pressed to 95 % on the 0.4 mm mesh:
#   bash benchmarks/element_size_study.sh /tmp/sizes 1.366 "0.5 0.4 0.35 0.3"
# Load steps: one per 0.01 mm of stroke.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=$1; stroke=$2; sizes=$3; shift 3
scene=${SCENE:-$root/prm/single_layer_sn_light.prm}
densify=${DENSIFY:-$root/build/densify}
steps=$(echo "($stroke * 100 + 0.5) / 1" | bc)
mkdir -p "$out"
run() { # size
  local start=$(date +%s.%N)
  "$densify" "$scene" --set "Output/Directory=$out/h$1" \
    --set "Output/Interval=0" --set "Output/Checkpoint interval=0" \
    --set "Mesh/Element size=$1" \
    --set "Tools/Upper punch/Displacement history=0:0, 0.8:$stroke" \
    --set "Time stepping/Number of steps=$steps" "${@:2}" \
    > "$out/h$1.log" 2>&1 || echo "exit $?" >> "$out/h$1.log"
  echo "$(date +%s.%N) - $start" | bc > "$out/h$1.seconds"
}
set -- $sizes "--" "$@"
list=()
while [ "$1" != "--" ]; do list+=("$1"); shift; done
shift
for ((i = 0; i < ${#list[@]}; i += 2)); do
  run "${list[i]}" "$@" &
  first=$!
  [ $((i + 1)) -lt ${#list[@]} ] && run "${list[i + 1]}" "$@"
  wait $first
done
/usr/bin/python3 - "$out" "${list[*]}" <<'PY'
import csv, re, sys
out, sizes = sys.argv[1], sys.argv[2].split()
densities, strokes = [80.0, 85.0, 90.0, 92.5, 95.0], [0.96, 1.28]
def at(rs, x, key, value):
    for a, b in zip(rs, rs[1:]):
        xa, xb = key(a), key(b)
        if xa <= x <= xb and xb > xa:
            return value(a) + (x - xa) / (xb - xa) * (value(b) - value(a))
    return float("nan")
print("h (mm) | cells | initial density % | "
      + " | ".join("p at %g %% (MPa)" % d for d in densities) + " | "
      + " | ".join("F at %g mm (N)" % s for s in strokes)
      + " | smallest V/V0 | wall s")
for h in sizes:
    log = open(f"{out}/h{h}.log").read()
    cells = re.search(r"(\d+) tetrahedra", log).group(1)
    initial = re.search(r"Initial relative density ([0-9.]+) %", log).group(1)
    rs = list(csv.DictReader(open(f"{out}/h{h}/statistics.csv")))
    rho = lambda r: 100 * float(r["relative_density"])
    p = lambda r: float(r["upper_punch_stress"])
    s = lambda r: float(r["punch_displacement"])
    F = lambda r: float(r["upper_punch_force"])
    vmin = min(float(r["min_cell_volume_ratio"]) for r in rs)
    seconds = float(open(f"{out}/h{h}.seconds").read())
    print(f"{h} | {cells} | {initial} | "
          + " | ".join("%.2f" % at(rs, d, rho, p) for d in densities) + " | "
          + " | ".join("%.1f" % at(rs, x, s, F) for x in strokes)
          + f" | {vmin:.3f} | {seconds:.0f}"
          + ("  (" + log.strip().splitlines()[-1] + ")" if "exit" in log else ""))
PY
