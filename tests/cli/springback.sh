# Unloading and the compact's envelope (doc/user_guide.md, "The compaction
# curve"): the J2 tin sphere of prm/single_sphere_sn.prm (P1, coarse) pressed
# by 0.3 mm between frictionless punches in 3 steps and unloaded by 0.1 mm in
# 3 more.
#   1. At full load the envelope's height (compact_height) is the punch gap
#      plus at most the penetration into each punch.
#   2. Unloaded, the punch carries no force and the compact is higher than
#      at full load (elastic recovery) and narrower (the bulge contracts
#      with Poisson's ratio); it stays where it is while the punch goes on
#      up.
#   3. The run's summary prints the springback, equal to the file's rows.
# The closed-form recovery of a J2 block is checked in
# tests/plastic_block_uniaxial.cc.
set -u
cd "$WORK_DIR"
fails=0
"$DENSIFY" "$SOURCE_DIR/prm/single_sphere_sn.prm" \
  --set "Mesh/Polynomial degree=1" --set "Mesh/Element size=0.6" \
  --set "Mesh/Refined element size=0.3" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.5:0.3, 1:0.2" \
  --set "Time stepping/Number of steps=6" --set "Output/Directory=out" \
  --set "Output/Interval=0" > run.log 2>&1 || fails=$((fails + 1))
grep "Springback" run.log || { echo "FAIL no springback line"; fails=$((fails + 1)); }
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { s[NR] = $c["punch_displacement"]; F[NR] = $c["upper_punch_force"]
    h[NR] = $c["compact_height"]; d[NR] = $c["compact_diameter"]
    p[NR] = $c["max_penetration"]; n = NR }
  END {
    full = 4; gap = 2.5 - s[full]
    if (!(h[full] >= gap - 1e-9 && h[full] <= gap + 2 * p[full] + 1e-9)) {
      print "FAIL full load: height " h[full] " for a gap of " gap; bad++ }
    if (F[n] != 0) { print "FAIL unloaded: force " F[n] " N"; bad++ }
    if (!(h[n] > h[full])) { print "FAIL no axial recovery: " h[full] " -> " h[n]; bad++ }
    if (!(d[n] < d[full])) { print "FAIL no lateral contraction: " d[full] " -> " d[n]; bad++ }
    if (h[n] != h[n - 1] || d[n] != d[n - 1]) { print "FAIL the free compact moves"; bad++ }
    printf "height %.6f -> %.6f mm (gap at full load %.6f), diameter %.6f -> %.6f mm\n", h[full], h[n], gap, d[full], d[n]
    printf "axial %.4g %%\n", 100 * (h[n] - h[full]) / h[full]
    exit bad > 0
  }' out/statistics.csv > rows.txt || fails=$((fails + 1))
cat rows.txt
axial=$(awk '/^axial/ { print $2 }' rows.txt)
grep "Springback" run.log | grep -q "axial $axial %" ||
  { echo "FAIL the summary's axial springback is not the file's ($axial %)"; fails=$((fails + 1)); }
[ "$fails" -eq 0 ] || { echo "$fails check(s) failed"; exit 1; }
echo "all checks passed"
