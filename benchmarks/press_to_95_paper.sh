#!/bin/bash
# The paper's layer (prm/single_layer_MATERIAL.prm: 43 spheres of 2.5 mm in
# the 20 mm die, the 0.3 mm mesh) pressed on past the paper's 1.28 mm to
# 95 % relative density: 263 load steps at the paper's rate (End time
# 0.8416 s, stroke 1.34656 mm; step 250 is the paper's 1.28 mm), one
# material after another, by explicit dynamics (Explicit/Contact stiffness =
# auto, Explicit/Ramp fraction = 0.2, 25,250 explicit steps: 96 a station,
# the 20,000 steps of the paper's 250 stations with the contact springs'
# extra mass) or by the implicit method, on RANKS MPI ranks (default 2).
# An implicit run can press on from a finished run of the paper's 250
# steps instead of starting afresh: with FROM_Sn=DIR (FROM_Fe, FROM_Cu) the
# run DIR (an Output/Directory holding a checkpoint) is copied and resumed
# with the longer schedule (densify --resume, doc/user_guide.md, "Pressing
# further"). Writes OUT/MATERIAL_METHOD/ (the run), .log and .seconds.
# Usage (from the source root):
#   bash benchmarks/press_to_95_paper.sh OUT "MATERIALS" METHOD [--set ...]
# e.g. bash benchmarks/press_to_95_paper.sh /tmp/p95 "Fe Cu" explicit
# then python3 benchmarks/press_to_95_table.py OUT "MATERIALS" for the
# pressures at 80-95 % and python3 benchmarks/paper_stations.py
# OUT/MATERIAL_METHOD/statistics.csv MATERIAL defaults at the paper's
# strokes.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=$1; materials=$2; method=$3; shift 3
densify=${DENSIFY:-$root/build/densify}
ranks=${RANKS:-2}
schedule=(--set "Time stepping/End time=0.8416"
          --set "Time stepping/Number of steps=263"
          --set "Tools/Upper punch/Displacement history=0:0, 0.8416:1.34656")
case $method in
  explicit) options=(--set Solver/Method=explicit
                     --set "Explicit/Number of steps=25250"
                     --set "Explicit/Contact stiffness=auto"
                     --set "Explicit/Ramp fraction=0.2") ;;
  implicit) options=(--set Solver/Method=implicit --set "Output/Checkpoint interval=5") ;;
  *) echo "METHOD must be explicit or implicit" >&2; exit 2 ;;
esac
mkdir -p "$out"
for material in $materials; do
  scene=$root/prm/single_layer_$(echo "$material" | tr 'A-Z' 'a-z').prm
  name=${material}_$method
  from_variable=FROM_$material
  resume=()
  if [ "$method" = implicit ] && [ -n "${!from_variable:-}" ]; then
    rm -rf "$out/$name"
    cp -r "${!from_variable}" "$out/$name"
    resume=(--resume)
  fi
  start=$(date +%s.%N)
  mpirun -np "$ranks" "$densify" "$scene" --set "Output/Directory=$out/$name" \
    --set Output/Interval=0 "${schedule[@]}" "${options[@]}" "$@" \
    "${resume[@]}" > "$out/$name.log" 2>&1 || echo "$name: exit $?" >> "$out/$name.log"
  echo "$(date +%s.%N) - $start" | bc > "$out/$name.seconds"
done
