# The quasi-static guard of explicit runs (Explicit/Maximum kinetic energy
# ratio, Explicit/Maximum force imbalance) and the advice of failed explicit
# runs whose mass scaling sets the step:
# - prm/default.prm in 10 explicit steps (the smallest accepted) ended with
#   exit 0, F_lower 0 N under F_upper 481 N and KE/IE 55-300 %: now exit 1 at
#   step 4, the first station whose upper punch force (354 N) reaches the
#   guard's load floor (a mean stress of a tenth of E / 1000, the stress of
#   an elastic strain of 1e-3, over the 10 mm die's bore: 339 N), by
#   the force balance (nothing reaches the lower punch), one error line
#   naming Explicit/Number of steps, no checkpoint (no station was judged
#   within the limits), and the penetration warning of implicit runs
#   (7.4 um against Contact/Gap tolerance);
# - the light layer in copper in 300 steps with Time step safety 0.3 ended
#   with exit 0 and 494 kN against 27 kN: now exit 1 naming Number of steps
#   and, as it stops in the first fifth of the load, Ramp fraction;
# - the same at the default safety stops unstable: its line names Number of
#   steps (a lower safety only adds mass), not the safety;
# - a shrunk light layer whose punch speeds up 22-fold after step 6, in 1,000
#   steps: it stops at step 7 (the kinetic energy gained since the guard
#   armed is 32 % of the internal work done since) with a checkpoint of a station within the
#   limits (step 6, or an earlier one on a loaded machine), and --resume with
#   Explicit/Number of steps = 8000 (the mass scaling starts anew) runs to
#   the end within the limits.
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
source "$SOURCE_DIR/tests/cli/lib/shrunk_light_scene.bash"
rm -rf def10 cu_safe cu_unstable jump

expect_error "default.prm in 10 explicit steps" 1 "raise Explicit/Number of steps (now 10)" \
  "$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Solver/Method=explicit" \
  --set "Explicit/Number of steps=10" --set "Output/Directory=def10"
out=$("$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Solver/Method=explicit" \
  --set "Explicit/Number of steps=10" --set "Output/Directory=def10" 2>&1)
for pattern in "no longer quasi-static at step 4" "against F_lower + F_die 0 N" "no checkpoint is written" \
    "warning: penetration .* mm above Contact/Gap tolerance"; do
  printf '%s\n' "$out" | grep -q -- "$pattern" ||
    { echo "FAIL: default.prm, 10 steps: no '$pattern' in"; printf '%s\n' "$out"; fails=$((fails + 1)); }
done
[ -d def10/checkpoint ] && { echo "FAIL: a checkpoint of a station outside the limits"; fails=$((fails + 1)); }

copper=(--set "Solver/Method=explicit" --set "Particles/Materials=Cu"
  --set "Explicit/Number of steps=300" --set "Output/Interval=0")
# it stops at step 1, in the first fifth of the load: the line also names
# a slower start (Explicit/Ramp fraction); the later stops below do not
expect_error "Cu light layer, 300 steps, safety 0.3" 1 "raise Explicit/Number of steps (now 300) or Explicit/Ramp fraction (now 0.05" \
  "$DENSIFY" "$scene" "${copper[@]}" --set "Explicit/Time step safety=0.3" \
  --set "Output/Directory=cu_safe"
expect_error "Cu light layer, 300 steps, unstable" 1 "raise Explicit/Number of steps (now 300" \
  "$DENSIFY" "$scene" "${copper[@]}" --set "Output/Directory=cu_unstable"

jump=(--set "Solver/Method=explicit" --set "Output/Directory=jump"
  --set "Tools/Upper punch/Displacement history=0:0, 0.6:0.06, 0.8:0.6")
# the station kept is the last one within the limits, or an earlier one
# where keeping each would cost more than 2 % of the run time (a loaded
# machine): the error line and the checkpoint name the same station <= 6
rc=0
"$DENSIFY" "$scene" "${common[@]}" "${jump[@]}" --set "Explicit/Number of steps=1000" \
  > jump.log 2> jump.err || rc=$?
line=$(grep "^densify: error: " jump.err)
kept=$(printf '%s' "$line" | sed -n 's/.*that was kept (step \([0-9]*\)) is in jump\/checkpoint\/.*/\1/p')
echo "punch 22 times faster after step 6, 1000 steps: exit $rc: $line"
if [ $rc -ne 1 ] || [ "$(printf '%s\n' "$line" | grep -c .)" -ne 1 ] ||
  ! printf '%s' "$line" | grep -q "no longer quasi-static at step 7" ||
  printf '%s' "$line" | grep -q "Ramp fraction" ||
  [ -z "$kept" ] || [ "$kept" -lt 1 ] || [ "$kept" -gt 6 ] ||
  ! grep -q "^load step $kept of 8" jump/checkpoint/info.txt; then
  echo "FAIL: expected a stop at step 7 with the checkpoint of a station <= 6"
  cat jump.err jump/checkpoint/info.txt
  fails=$((fails + 1))
fi
"$DENSIFY" "$scene" "${common[@]}" "${jump[@]}" --set "Explicit/Number of steps=8000" \
  --resume > resumed.log 2>&1 ||
  { echo "FAIL: resumed with 8000 steps"; cat resumed.log; fails=$((fails + 1)); }
grep -q "the mass scaling starts anew" resumed.log ||
  { echo "FAIL: the resumed run kept the old mass scaling"; fails=$((fails + 1)); }
rows=$(tail -n +2 jump/statistics.csv | wc -l)
[ "$rows" -eq 8 ] || { echo "FAIL: $rows rows after the resumed run"; fails=$((fails + 1)); }
grep "^step [78]/8" resumed.log | cut -c1-160

echo "$fails failure(s)"
[ "$fails" -eq 0 ]
