# Checkpoints of explicit runs (Solver/Method = explicit): the shrunk light
# layer stopped after step 3 (--stop-after) and continued with --resume ends
# with the same statistics.csv and particles.csv as the run without a stop
# (velocities, the friction and plastic history, the mass-scaling factors
# and the energy account are in the checkpoint); and --resume refuses a
# checkpoint of the other method, but accepts a lower Explicit/Time step
# safety. The same with Explicit/Step profile stopped where its factor is
# 0.5 (the mass factors restored for that station's step).
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
profile=(--set "Explicit/Step profile=0:1, 0.2:1, 0.4:0.5")
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" "${profile[@]}" \
  --set "Output/Directory=whole_profile" > whole_profile.log 2>&1
rc=0
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" "${profile[@]}" \
  --set "Output/Directory=pieces_profile" --stop-after 3 > pieces_profile.log 2>&1 || rc=$?
[ $rc -eq 3 ] || { echo "expected exit 3, got $rc"; exit 1; }
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" "${profile[@]}" \
  --set "Output/Directory=pieces_profile" --resume > resumed_profile.log 2>&1
cut -d, -f1-9,11-15,17- whole_profile/statistics.csv > a.csv
cut -d, -f1-9,11-15,17- pieces_profile/statistics.csv > b.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' a.csv b.csv
echo "the same with Explicit/Step profile, stopped at its factor 0.5: yes"
# the checkpoint of an explicit run is refused by an implicit one
rc=0
err=$("$DENSIFY" "$scene" "${common[@]}" --set "Time stepping/Number of steps=6" \
  --set "Explicit/Number of steps=2000" \
  --set "Output/Directory=pieces" --resume 2>&1 >/dev/null) || rc=$?
echo "implicit --resume of the explicit checkpoint: exit $rc"
[ $rc -eq 2 ] || { echo "$err"; exit 1; }
echo "$err" | grep -q "Solver/Method" || { echo "$err"; exit 1; }
# an unstable run's message says to lower Explicit/Time step safety: a
# resumed run may do so (the stable step is measured anew at every station)
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" \
  --set "Output/Directory=safer" --stop-after 3 > safer.log 2>&1 || true
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" \
  --set "Explicit/Time step safety=0.7" \
  --set "Output/Directory=safer" --resume > safer_resumed.log 2>&1 ||
  { cat safer_resumed.log; exit 1; }
rows=$(tail -n +2 safer/statistics.csv | wc -l)
[ "$rows" -eq 6 ] || { echo "resumed with safety 0.7: $rows rows"; exit 1; }
echo "resumed with a lower Explicit/Time step safety: 6 steps, yes"
