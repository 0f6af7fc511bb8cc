#!/bin/bash
# A scene pressed past the paper's 90 % to 95 % relative density by both
# methods, one material at a time: the implicit and the explicit run side by
# side (one rank each, the two cores), then for each the upper punch
# pressure (F_upper / die area) at given relative densities (interpolated
# between the stations), the difference between the methods, the smallest
# cell volume ratio V/V0 and the wall time. The pressure-density curves go to
# OUT/MATERIAL_METHOD.csv (density in %, pressure in MPa).
# Usage (from the source root):
#   bash benchmarks/press_to_95.sh OUT STROKE "MATERIALS" [--set ...]...
# e.g. the light paper layer on a 0.4 mm mesh to 95 % (doc/verification.md,
# "Pressed to 95 %"):
#   bash benchmarks/press_to_95.sh /tmp/p95 1.366 "Sn Fe Cu" \
#     --set "Mesh/Element size=0.4"
# STROKE is the upper punch's travel (mm) over the scene's end time: for a
# density rho of the meshed particles, 2.5 mm - V / (rho die area) with the
# particle volume V that a run prints as "Initial relative density"; the
# --set options apply to both methods; EXPLICIT_STEPS (default 20000) sets
# the explicit run's Explicit/Number of steps and IMPLICIT_STEPS (default
# 128 per 1.28 mm) the implicit load steps. IMPLICIT_FROM=DIR takes the
# implicit runs from an earlier OUT instead of running them (to compare
# explicit variants, e.g. --set "Explicit/Contact stiffness=2", with one
# implicit reference; the --set options then apply to the explicit runs).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=$1; stroke=$2; materials=$3; shift 3
scene=${SCENE:-$root/prm/single_layer_sn_light.prm}
densify=${DENSIFY:-$root/build/densify}
explicit_steps=${EXPLICIT_STEPS:-20000}
implicit_steps=${IMPLICIT_STEPS:-$(echo "($stroke * 100 + 0.5) / 1" | bc)}
mkdir -p "$out"
run() { # name, extra options
  local name=$1; shift
  local start=$(date +%s.%N)
  "$densify" "$scene" --set "Output/Directory=$out/$name" \
    --set "Output/Interval=0" --set "Output/Checkpoint interval=0" \
    --set "Tools/Upper punch/Displacement history=0:0, 0.8:$stroke" \
    "$@" > "$out/$name.log" 2>&1 || echo "$name: exit $?" >> "$out/$name.log"
  echo "$(date +%s.%N) - $start" | bc > "$out/$name.seconds"
}
for material in $materials; do
  if [ -n "${IMPLICIT_FROM:-}" ]; then
    for f in "" .log .seconds; do
      ln -sfn "$(cd "$IMPLICIT_FROM" && pwd)/${material}_implicit$f" \
        "$out/${material}_implicit$f"
    done
    run "${material}_explicit" --set "Particles/Materials=$material" \
      --set "Solver/Method=explicit" \
      --set "Explicit/Number of steps=$explicit_steps" "$@"
    continue
  fi
  run "${material}_implicit" --set "Particles/Materials=$material" \
    --set "Time stepping/Number of steps=$implicit_steps" "$@" &
  first=$!
  run "${material}_explicit" --set "Particles/Materials=$material" \
    --set "Solver/Method=explicit" \
    --set "Explicit/Number of steps=$explicit_steps" "$@"
  wait $first
done
/usr/bin/python3 "$root/benchmarks/press_to_95_table.py" "$out" "$materials"
