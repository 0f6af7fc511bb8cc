# Checkpoints of explicit runs (Solver/Method = explicit): the shrunk light
# layer stopped after step 3 (--stop-after) and continued with --resume ends
# with the same statistics.csv and particles.csv as the run without a stop
# (velocities, the friction and plastic history, the mass-scaling factors
# and the energy account are in the checkpoint); and --resume refuses a
# checkpoint of the other method.
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/shrunk_light_scene.bash"
explicit=(--set "Solver/Method=explicit" --set "Explicit/Number of steps=2000"
  --set "Time stepping/Number of steps=6")
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" \
  --set "Output/Directory=whole" > whole.log 2>&1
rc=0
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" \
  --set "Output/Directory=pieces" --stop-after 3 > pieces.log 2>&1 || rc=$?
[ $rc -eq 3 ] || { echo "expected exit 3, got $rc"; exit 1; }
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" \
  --set "Output/Directory=pieces" --resume > resumed.log 2>&1
# every column but the wall times (10, 16)
cut -d, -f1-9,11-15,17- whole/statistics.csv > a.csv
cut -d, -f1-9,11-15,17- pieces/statistics.csv > b.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' a.csv b.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' whole/particles.csv pieces/particles.csv
echo "stopped and resumed explicit run = uninterrupted run (1e-9): yes"
# the checkpoint of an explicit run is refused by an implicit one
rc=0
err=$("$DENSIFY" "$scene" "${common[@]}" --set "Time stepping/Number of steps=6" \
  --set "Explicit/Number of steps=2000" \
  --set "Output/Directory=pieces" --resume 2>&1 >/dev/null) || rc=$?
echo "implicit --resume of the explicit checkpoint: exit $rc"
[ $rc -eq 2 ] || { echo "$err"; exit 1; }
echo "$err" | grep -q "Solver/Method" || { echo "$err"; exit 1; }
