# Every prm/*.prm runs in a shrunk form (coarse P1 mesh, two steps, a shorter
# stroke for the slowest scenes) and writes
# statistics.csv with the documented columns plus a readable .pvd.
set -eu
cd "$WORK_DIR"
columns="step,time,punch_displacement,upper_punch_force,lower_punch_force,die_wall_force,relative_density,newton_iterations,linear_iterations,wall_seconds"
for scene in "$SOURCE_DIR"/prm/*.prm; do
  name=$(basename "$scene" .prm)
  echo "== $name"
  # scenes that take minutes even on the coarse mesh also get a shorter stroke
  extra=()
  case "$name" in
    seven_spheres_sn) extra=(--set "Tools/Upper punch/Displacement history=0:0, 1:0.04") ;;
    # the paper's 43-sphere layer shrunk to its middle seven (die 7.52 mm),
    # and 500 explicit steps for the short stroke
    single_layer_*) extra=(--set "Tools/Die wall/Diameter=7.52"
                           --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.04"
                           --set "Explicit/Number of steps=500") ;;
    # the poured beds shrunk to their first 12 spheres, and 500 explicit
    # steps for the short stroke
    # the press cycle's loading only, without its pressure window
    # (tests/cli/press_cycle.sh runs the cycle)
    press_cycle_*) extra=(--set "Tools/Upper punch/Displacement history=0:0, 1.25:0.04"
                          --set "Tools/Upper punch/Pressure history="
                          --set "Tools/Lower punch/Displacement history=0:0") ;;
    multi_layer_*) extra=(--set "Particles/Number of particles=12"
                          --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.04"
                          --set "Explicit/Number of steps=500") ;;
  esac
  "$DENSIFY" "$scene" "${extra[@]}" \
    --set "Output/Directory=out_$name" \
    --set "Mesh/Polynomial degree=1" \
    --set "Mesh/Element size=0.6" \
    --set "Mesh/Refined element size=0.2" \
    --set "Time stepping/Number of steps=2" > "log_$name.txt"
  tail -n 3 "log_$name.txt"
  head -n 1 "out_$name/statistics.csv" | grep -q "^$columns"
  [ "$(wc -l < "out_$name/statistics.csv")" -eq 3 ]
  grep -q "solution_00002.pvtu" "out_$name/solution.pvd"
  [ -s "out_$name/log.txt" ]
done
