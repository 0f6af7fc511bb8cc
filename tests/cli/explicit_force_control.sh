# Force control by explicit dynamics (doc/theory.md, "Force control"): the
# light layer (seven J2 tin spheres, 0.6 mm mesh, friction 0.2) pressed by
# the displacement history 0.1 mm per station (8 stations of 0.1 s, 6,000
# explicit steps) until t = 0.4 s, then held at the mean pressure
# 13 MPa (Tools/Upper punch/Pressure history=0.4:13, 0.8:13). The explicit
# method corrects each station's travel from the last station's force.
#   1. In the window the upper punch stress approaches the target from
#      station to station (measured: -5.3, -2.8, -1.4, -0.5 %): its error
#      never grows, is within 3 % from the window's second station on and
#      within 1 % at the last (Force tolerance's 0.1 % is the implicit
#      method's; the explicit one corrects the travel once per station).
#   2. The punch moves less and less: the travel over the last two
#      stations is below a third of the displacement history's 0.1 mm.
#   3. On 2 ranks the same stresses within 1 % (the explicit forces are
#      sums in another order, the window's corrections follow them;
#      measured: equal in every printed digit).
set -u
cd "$WORK_DIR"
rm -rf one two
fails=0
scene=("$SOURCE_DIR/prm/single_layer_sn_light.prm" --set "Mesh/Element size=0.6"
  --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.8"
  --set "Tools/Upper punch/Pressure history=0.4:13, 0.8:13"
  --set "Time stepping/Number of steps=8" --set "Solver/Method=explicit"
  --set "Explicit/Number of steps=6000" --set "Output/Interval=0"
  --set "Output/Checkpoint interval=0")
"$DENSIFY" "${scene[@]}" --set "Output/Directory=one" > one.log 2>&1 ||
  { echo "FAIL the 1-rank run"; tail -n 3 one.log; fails=$((fails + 1)); }
"$MPIEXEC" -np 2 "$DENSIFY" "${scene[@]}" --set "Output/Directory=two" \
  > two.log 2>&1 ||
  { echo "FAIL the 2-rank run"; tail -n 3 two.log; fails=$((fails + 1)); }
check() { # statistics.csv
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    function abs(x) { return x < 0 ? -x : x }
    { t = $c["time"]; p = $c["upper_punch_stress"]; d[NR] = $c["punch_displacement"]
      printf "station %d: t %.2f s, punch %.4f mm, %.3f MPa\n", NR - 1, t, d[NR], p
      e = abs(p / 13 - 1)
      if (t > 0.45 && t < 0.55) first = e
      if (t > 0.55 && e > 0.03) { print "FAIL off the target by more than 3 %"; bad++ }
      if (t > 0.55 && e > previous) { print "FAIL the error grew"; bad++ }
      previous = e; last = NR }
    END {
      if (!(previous <= 0.01)) { print "FAIL the last station off by more than 1 %"; bad++ }
      if (first == "") { print "FAIL no station at the window start"; bad++ }
      travel = d[last] - d[last - 2]
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
