# Force control of the upper punch (Tools/Upper punch/Force history;
# doc/theory.md, "Force control"). The three elastic spheres of
# prm/default.prm in 10 steps of 0.1 s: the displacement history (0.002 mm
# a step) to t = 0.4, then the force history 0.4:100, 0.6:150, 0.8:150 N
# (targets 125, 150, 150, 150 N at steps 5-8), then the displacement
# history again, with Maximum speed = 1 mm/s (0.1 mm a step: never
# reached here). Implicit, on 1 and 2 ranks.
#   1. Steps 5-8 carry their target within Force tolerance (1e-3 of the
#      larger of the target and the largest force so far).
#   2. While the target holds (steps 6-8), the punch stays where it is
#      (elastic spheres: the same force at the same place, to 1e-9 mm).
#   3. After the window the displacement history goes on from where the
#      force control left the punch: 0.002 mm a step, no jump.
#   4. 1 and 2 ranks agree (forces to 1e-6, travel to 1e-9 mm).
#   5. With the default Maximum speed (the displacement history's, 0.02
#      mm/s: 0.002 mm a step) the target of step 5 needs more travel than
#      that: the punch moves by exactly 0.002 mm and carries less than 125 N;
#      by step 7 it has caught up with the held 150 N.
#   6. The lower punch under force control (Tools/Lower punch/Force
#      history 0:0, 0.5:100, 1:100 N) with the upper punch standing, on 1
#      and 2 ranks: each step's lower punch force is its target within the
#      tolerance, the upper punch carries the same (no die friction here),
#      the lower punch rises while the target does and then stays (to 1e-9
#      mm), the rows are in the phase load and then hold, and the ranks
#      agree.
#   7. Bad input stops with exit 2 and one line naming the parameter: a
#      force and a pressure history together, a negative force, a pressure
#      without the die (for either punch), force windows out of time order,
#      a window of one pair.
#   8. Two force windows (Force history 0.2:100, 0.4:100; 0.6:150,
#      0.8:150, Maximum speed = 1 mm/s): steps 3-4 carry 100 N and steps
#      7-8 150 N within the tolerance; between and after the windows
#      (steps 5-6, 9-10) the displacement history moves the punch by 0.002
#      mm a step.
# Each run is a part of its own (tests/cli/lib/parts.bash).
# ctest parts: one slow lower_one windows two:2 lower_two:2
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
fails=0
control=(--set "Output/Interval=0" --set "Time stepping/Number of steps=10"
  --set "Tools/Upper punch/Force history=0.4:100, 0.6:150, 0.8:150")
fast=(--set "Tools/Upper punch/Maximum speed=1")
scene="$SOURCE_DIR/prm/default.prm"
# the runs: the fast punch on 1 and 2 ranks, the default speed (item 5),
# the lower punch on 1 and 2 ranks (item 6) and two force windows (item 8)
lower=(--set "Output/Interval=0" --set "Time stepping/Number of steps=10"
  --set "Tools/Upper punch/Displacement history=0:0"
  --set "Tools/Lower punch/Force history=0:0, 0.5:100, 1:100")
run_part() { # part, launcher and options
  local name=$1
  shift
  part "$name" || return 0
  "$@" --set "Output/Directory=$name" > "$name.log" 2>&1 ||
    { echo "FAIL the run $name"; tail -n 5 "$name.log"; exit 1; }
}
run_part one "$DENSIFY" "$scene" "${control[@]}" "${fast[@]}"
run_part slow "$DENSIFY" "$scene" "${control[@]}"
run_part lower_one "$DENSIFY" "$scene" "${lower[@]}"
run_part windows "$DENSIFY" "$scene" --set "Output/Interval=0" --set "Time stepping/Number of steps=10" \
  --set "Tools/Upper punch/Force history=0.2:100, 0.4:100; 0.6:150, 0.8:150" "${fast[@]}"
run_part two "$MPIEXEC" -np 2 "$DENSIFY" "$scene" "${control[@]}" "${fast[@]}"
run_part lower_two "$MPIEXEC" -np 2 "$DENSIFY" "$scene" "${lower[@]}"
part check || exit 0
for run in one two; do
  awk -F, -v run=$run 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    { d[$1] = $c["punch_displacement"]; f[$1] = $c["upper_punch_force"]
      if (f[$1] > fmax) fmax = f[$1] }
    function abs(x) { return x < 0 ? -x : x }
    END {
      split("125 150 150 150", target, " ")
      for (k = 1; k <= 4; ++k) {
        s = k + 4; scale = target[k] > fmax ? target[k] : fmax
        if (abs(f[s] - target[k]) > 1e-3 * scale) {
          print "FAIL " run " step " s ": " f[s] " N, target " target[k]; bad++ } }
      for (s = 7; s <= 8; ++s) if (abs(d[s] - d[6]) > 1e-9) {
        print "FAIL " run " the held punch moved: " d[6] " -> " d[s] " mm"; bad++ }
      for (s = 9; s <= 10; ++s) if (abs(d[s] - d[s - 1] - 0.002) > 1e-9) {
        print "FAIL " run " step " s " moved " d[s] - d[s - 1] " mm, not 0.002"; bad++ }
      printf "%s: forces at steps 5-8 %.6g %.6g %.6g %.6g N, travel %.6g mm held, then +%.6g +%.6g mm\n",
        run, f[5], f[6], f[7], f[8], d[6], d[9] - d[8], d[10] - d[9]
      exit bad > 0 }' $run/statistics.csv || fails=$((fails + 1))
done
# agree DIR1 DIR2 FORCE TRAVEL WHAT: the columns FORCE (to 1e-6) and TRAVEL
# (to 1e-9 mm) of the two runs' statistics.csv agree at every step
agree() {
  paste -d, "$1/statistics.csv" "$2/statistics.csv" | awk -F, -v force="$3" \
    -v travel="$4" -v what="$5" 'NR == 1 { n = NF / 2
      for (i = 1; i <= n; ++i) c[$i] = i; next }
    function abs(x) { return x < 0 ? -x : x }
    { a = c[force]; b = c[travel]
      if (abs($a - $(a + n)) > 1e-6 * (1 + abs($a)) || abs($b - $(b + n)) > 1e-9) {
        print "FAIL ranks differ at step " $1 ": " $a " / " $(a + n) " N, " $b " / " $(b + n) " mm"; bad++ } }
    END { if (!bad) print what ": 1 and 2 ranks agree"; exit bad > 0 }' || fails=$((fails + 1))
}
agree one two upper_punch_force punch_displacement "upper punch"

awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { d[$1] = $c["punch_displacement"]; f[$1] = $c["upper_punch_force"] }
  function abs(x) { return x < 0 ? -x : x }
  END {
    if (abs(d[5] - d[4] - 0.002) > 1e-9 || !(f[5] < 125 * (1 - 1e-3))) {
      print "FAIL at the default speed step 5 moved " d[5] - d[4] " mm to " f[5] " N"; bad++ }
    if (abs(f[7] - 150) > 0.15) { print "FAIL at the default speed step 7 carries " f[7] " N"; bad++ }
    printf "default speed: step 5 moved %.6g mm to %.6g N (target 125), step 7 %.6g N\n", d[5] - d[4], f[5], f[7]
    exit bad > 0 }' slow/statistics.csv || fails=$((fails + 1))

# the lower punch under force control
for run in lower_one lower_two; do
  awk -F, -v run=$run 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    function abs(x) { return x < 0 ? -x : x }
    { s = $1; target = (s <= 5 ? 20 * s : 100)
      f = $c["lower_punch_force"]; u = $c["upper_punch_force"]
      r[s] = $c["lower_punch_displacement"]; ph = $c["phase"]
      if (abs(f - target) > 1e-3 * 100) { print "FAIL " run " step " s ": " f " N, target " target; bad++ }
      if (abs(u - f) > 1e-6 * f) { print "FAIL " run " step " s ": upper " u " N, lower " f " N"; bad++ }
      if (ph != (s <= 5 ? 0 : 1)) { print "FAIL " run " step " s " in phase " ph; bad++ } }
    END {
      for (s = 2; s <= 5; ++s) if (!(r[s] > r[s - 1])) { print "FAIL " run " no rise at step " s; bad++ }
      for (s = 6; s <= 10; ++s) if (abs(r[s] - r[5]) > 1e-9) { print "FAIL " run " the held lower punch moved at step " s; bad++ }
      printf "%s: lower punch at 100 N after a rise of %.6g mm, held\n", run, r[5]
      exit bad > 0 }' $run/statistics.csv || fails=$((fails + 1))
done
agree lower_one lower_two lower_punch_force lower_punch_displacement "lower punch"

bad_input() {
  local expect="$1"
  shift
  "$DENSIFY" "$scene" --set "Output/Directory=bad" "$@" > bad.log 2>&1
  local code=$?
  if [ $code -ne 2 ] || ! grep -q "$expect" bad.log || [ "$(grep -c "error" bad.log)" -ne 1 ]; then
    echo "FAIL bad input ($*): exit $code"; cat bad.log; fails=$((fails + 1))
  else
    echo "refused with exit 2: $(grep error bad.log)"
  fi
}
bad_input "Tools/Upper punch/Pressure history: give either" \
  --set "Tools/Upper punch/Force history=0.4:100, 0.8:150" \
  --set "Tools/Upper punch/Pressure history=0.4:1, 0.8:2"
bad_input "Tools/Upper punch/Force history: -5.* is negative" \
  --set "Tools/Upper punch/Force history=0.4:100, 0.8:-5"
bad_input "Tools/Upper punch/Pressure history: a mean stress needs the die" \
  --set "Tools/Die wall/Enabled=false" \
  --set "Tools/Upper punch/Pressure history=0.4:1, 0.8:2"
bad_input "Tools/Lower punch/Pressure history: give either" \
  --set "Tools/Lower punch/Force history=0.4:100, 0.8:150" \
  --set "Tools/Lower punch/Pressure history=0.4:1, 0.8:2"
bad_input "Tools/Lower punch/Force history: -5.* is negative" \
  --set "Tools/Lower punch/Force history=0.4:100, 0.8:-5"
bad_input "Tools/Upper punch/Force history: the window .* starts before" \
  --set "Tools/Upper punch/Force history=0.4:100, 0.6:100; 0.5:150, 0.8:150"
bad_input "Tools/Upper punch/Force history: give at least two pairs in each window" \
  --set "Tools/Upper punch/Force history=0.2:100; 0.6:150, 0.8:150"

# two force windows
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { d[$1] = $c["punch_displacement"]; f[$1] = $c["upper_punch_force"]
    if (f[$1] > fmax) fmax = f[$1] }
  function abs(x) { return x < 0 ? -x : x }
  END {
    split("3 4 7 8", step, " "); split("100 100 150 150", target, " ")
    for (k = 1; k <= 4; ++k) { s = step[k]; scale = target[k] > fmax ? target[k] : fmax
      if (abs(f[s] - target[k]) > 1e-3 * scale) { print "FAIL windows step " s ": " f[s] " N, target " target[k]; bad++ } }
    split("5 6 9 10", moved, " ")
    for (k = 1; k <= 4; ++k) { s = moved[k]
      if (abs(d[s] - d[s - 1] - 0.002) > 1e-9) { print "FAIL windows step " s " moved " d[s] - d[s - 1] " mm, not 0.002"; bad++ } }
    printf "two windows: %.6g %.6g N, then +%.6g +%.6g mm; %.6g %.6g N, then +%.6g +%.6g mm\n",
      f[3], f[4], d[5] - d[4], d[6] - d[5], f[7], f[8], d[9] - d[8], d[10] - d[9]
    exit bad > 0 }' windows/statistics.csv || fails=$((fails + 1))
exit $((fails > 0))
