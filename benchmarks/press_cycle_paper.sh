#!/bin/bash
# The paper's layer (prm/single_layer_sn.prm: 43 tin spheres in the 20 mm
# die) through the whole press cycle, by the implicit method on 2 ranks:
# pressed by 1.28 mm over 0.8 s, held 0.05 s, unloaded by 0.03 mm (the punch
# leaves the compact), then ejected: the lower punch rises by 2.7 mm over
# 0.4 s and pushes the compact past the die's top (2.5 mm) while the upper
# punch follows it with a hold-down of 0.5 MPa (the second pressure window of
# prm/press_cycle_sn_light.prm's cycle). 52 steps of 25 ms on the draft mesh
# (0.6 mm); doc/user_guide.md, "A press cycle", has the figures it gives.
# Usage (from the source root): bash benchmarks/press_cycle_paper.sh OUT
#   [--set ...]...  (e.g. --set "Scene/Fidelity=standard" for the 0.3 mm
#   mesh, with the step count of your choice)
set -eu
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:?usage: bash benchmarks/press_cycle_paper.sh OUT [--set ...]...}
shift
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1}
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}
mpirun -np 2 "$root/build/densify" "$root/prm/single_layer_sn.prm" --set Solver/Method=implicit \
  --set "Scene/Fidelity=draft" --set "Time stepping/Number of steps=52" \
  --set "Time stepping/End time=1.3" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.8:1.28, 0.85:1.28, 0.9:1.25" \
  --set "Tools/Upper punch/Pressure history=0.9:0.5, 1.3:0.5" \
  --set "Tools/Upper punch/Maximum speed=10" \
  --set "Tools/Lower punch/Displacement history=0:0, 0.9:0, 1.3:2.7" \
  --set "Tools/Die wall/Top=2.5" \
  --set "Output/Directory=$out" --set "Output/Interval=13" \
  --set "Output/Checkpoint interval=2" "$@"
