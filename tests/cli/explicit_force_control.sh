# Force control by explicit dynamics (doc/theory.md, "Force control"): the
# light layer (seven J2 tin spheres, 0.6 mm mesh, friction 0.2) pressed by
# the displacement history 0.1 mm per station (8 stations of 0.1 s, 6,000
# explicit steps) until t = 0.4 s, then held at the mean pressure
# 13 MPa (Tools/Upper punch/Pressure history=0.4:13, 0.8:13). In the window
# the punch is a rigid body pushed by the target less its contact force,
# step by step (PunchControl::drive()).
#   1. From the window's second station on the upper punch stress is within
#      0.5 % of the target (measured: -0.05, +0.002, +0.01 %; the first
#      station, whose force rises from 11.8 MPa, +2.3 %).
#   2. The punch comes to rest: the travel over the last two stations is
#      below a third of the displacement history's 0.1 mm (measured:
#      0.00004 mm).
#   3. On 2 ranks, stopped after the window's second station and resumed
#      from its checkpoint, the same stresses within 1 % (the explicit
#      forces are sums in another order, and the resumed station restarts
#      the explicit step; measured: within 1.4e-5).
#   4. With Explicit/Maximum force control error = 1e-4, below the second
#      station's miss, the quasi-static guard stops the run there (exit 1)
#      with one line that names the miss and the limit and advises more
#      steps.
# Each run is a part of its own (tests/cli/lib/parts.bash).
# ctest parts: one tight two:2
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
fails=0
scene=("$SOURCE_DIR/prm/single_layer_sn_light.prm" --set "Mesh/Element size=0.6"
  --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.8"
  --set "Tools/Upper punch/Pressure history=0.4:13, 0.8:13"
  --set "Time stepping/Number of steps=8" --set "Solver/Method=explicit"
  --set "Explicit/Number of steps=6000" --set "Output/Interval=0"
  --set "Output/Checkpoint interval=0")
if part one; then
  rm -rf one
  "$DENSIFY" "${scene[@]}" --set "Output/Directory=one" > one.log 2>&1 ||
    { echo "FAIL the 1-rank run"; tail -n 3 one.log; exit 1; }
fi
# the guard's limit on the miss, set below the second station's 5e-4
if part tight; then
  "$DENSIFY" "${scene[@]}" --set "Output/Directory=tight" \
    --set "Explicit/Maximum force control error=1e-4" > tight.log 2>&1
  status=$?
  line=$(grep "error:" tight.log)
  echo "Maximum force control error = 1e-4: exit $status: $line"
  [ "$status" = 1 ] &&
    echo "$line" | grep -q "at step 6 .*upper punch's force missed its target by .* above Explicit/Maximum force control error = 0.01 %" &&
    echo "$line" | grep -q "raise Explicit/Number of steps (now 6000)" ||
    { echo "FAIL the miss above the limit does not stop the run"; exit 1; }
fi
# on 2 ranks, stopped within the window and resumed from its checkpoint
# (exit code 3: stopped by --stop-after)
if part two; then
  rm -rf two
  "$MPIEXEC" -np 2 "$DENSIFY" "${scene[@]}" --set "Output/Directory=two" \
    --stop-after 6 > two.log 2>&1
  status=$?
  [ "$status" = 3 ] &&
    "$MPIEXEC" -np 2 "$DENSIFY" "${scene[@]}" --set "Output/Directory=two" \
      --resume >> two.log 2>&1 ||
    { echo "FAIL the 2-rank run (stop: exit $status)"; tail -n 3 two.log; exit 1; }
fi
part check || exit 0
check() { # statistics.csv
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    function abs(x) { return x < 0 ? -x : x }
    { t = $c["time"]; p = $c["upper_punch_stress"]; d[NR] = $c["punch_displacement"]
      printf "station %d: t %.2f s, punch %.4f mm, %.3f MPa\n", NR - 1, t, d[NR], p
      e = abs(p / 13 - 1)
      if (t > 0.45 && t < 0.55) first = e
      if (t > 0.55) { held++; if (e > 0.005) { print "FAIL off the target by more than 0.5 %"; bad++ } }
      last = NR }
    END {
      if (held != 3) { print "FAIL " held " stations in the window after its first, not 3"; bad++ }
      if (first == "") { print "FAIL no station at the window start"; bad++ }
      travel = d[last] - d[last - 2]; if (travel < 0) travel = -travel
      printf "travel over the last two stations %.4f mm\n", travel
      if (!(travel < 0.1 / 3)) { print "FAIL the punch still moves"; bad++ }
      exit bad > 0 }' "$1"
}
echo "1 rank:"; check one/statistics.csv || fails=$((fails + 1))
echo "2 ranks:"; check two/statistics.csv || fails=$((fails + 1))
paste -d, one/statistics.csv two/statistics.csv | awk -F, '
  NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) c[$i] = i; next }
  { p = c["upper_punch_stress"]; d = $p / $(p + n) - 1; if (d < 0) d = -d
    if (d > worst) worst = d }
  END { printf "1 and 2 ranks: stresses within %.2g\n", worst
    if (worst > 0.01) { print "FAIL the ranks differ"; exit 1 } }' ||
  fails=$((fails + 1))
[ "$fails" -eq 0 ] || { echo "$fails check(s) failed"; exit 1; }
echo "all checks passed"
