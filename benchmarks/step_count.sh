#!/bin/bash
# What the number of load steps buys and costs in accuracy and time: the light
# paper scene to its end with several step counts, through lever_sweep.sh
# (wall time, Newton iterations, cut-backs, final density, forces, volume).
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
exec bash "$root/benchmarks/lever_sweep.sh" "$scene" \
  "Time stepping/Number of steps" "${counts[@]}"
