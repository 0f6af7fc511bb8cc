# The press cycle (prm/press_cycle_sn_light.prm; doc/user_guide.md, "A
# press cycle"), shrunk to a 0.6 mm mesh, a 7.52 mm die (the spheres span
# 7.5 mm, so the die wall carries early) and 23 steps of 20 ms: the seven
# tin spheres pressed by 0.7 mm (10 steps, 20.5 MPa), held at 20 MPa by
# pressure control (1 step; Tools/Upper punch/Pressure history), unloaded
# by 0.05 mm
# (2), and pushed up through the die by the lower punch (10 steps of
# 0.1 mm: the compact's top leaves the die's top at 2.5 mm, its particles'
# flattened sides stay in the die) with the upper punch withdrawn ahead of
# them. Implicit, 1 rank.
#   1. The phase column runs load, hold, unload, eject in that order, each
#      present (the held target just below the load's pressure lets the
#      punch relax back elastically: still the phase hold, which under
#      pressure control follows the target); the hold row carries 20 MPa
#      within the force tolerance (1e-3 of the largest force so far); the
#      upper punch carries nothing after the unloading.
#      The first eject row starts from the compact carried up by the lower
#      punch's rise (nothing presses it from above): at most 10 Newton
#      iterations (measured 4; 143 and a continuation from the unloading's
#      increment extrapolated).
#   2. While the compact slides inside the die (the eject rows before it
#      reaches the die's top), the ejection force (lower_punch_force) is the
#      die wall's friction: 0.2 times its radial force within 5 %.
#   3. The compact's envelope density at the end, partly out of the die, is
#      below the one in the die at full load (springback), and the run's
#      springback line measures the compact the unloading left, before the
#      ejection.
#   4. The run's ejection line names the largest lower punch force of the
#      eject rows and the lower punch's rise at it (lower_punch_displacement,
#      which rises by 0.1 mm a step while it ejects).
#      plot_statistics.py draws that curve (ejection.png; needs Debian's
#      python3-matplotlib, which scripts/setup.sh installs).
#   5. The uninterrupted run's last checkpoint (Output/Checkpoint
#      interval = 16: after step 16, the third eject row) resumed in a copy
#      of its output ends with the rows of the uninterrupted run (all but
#      the wall times), in statistics.csv and in particles.csv (with the
#      particles' mean stresses).
#   6. The same cycle ejected by withdrawal (Tools/Die wall/Displacement
#      history lowers the die by 1 mm while the lower punch stands): the
#      same relative motion, so the eject rows' lower punch force is the
#      one of the lower punch's rise within 1e-4 (measured 5e-5 in the first
#      row, 5e-7 after), the rows in the phase eject, and the summary's
#      travel is the rise in the die.
#   7. The summary has the contact line at full load and plot_statistics.py
#      draws contacts.png (coordination number and contact area fraction
#      against density).
#   8. The uninterrupted cycle runs by scripts/run.sh (graphics of the last
#      step only), which writes the cycle's plots into its output directory:
#      density, forces, compaction, ejection and contacts, and the picture
#      of the ejected compact (view_oblique.png).
# The uninterrupted cycle with its resumed copy, and the withdrawal, are
# parts of their own (tests/cli/lib/parts.bash), so ctest runs them side by
# side.
# ctest parts: whole withdrawn
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
fails=0
cycle=(--set "Mesh/Element size=0.6" --set "Output/Interval=23"
  --set "Output/Checkpoint interval=16" --set "Tools/Die wall/Diameter=7.52"
  --set "Tools/Upper punch/Displacement history=0:0, 0.2:0.7, 0.22:0.7, 0.26:0.65, 0.46:-1.5"
  --set "Tools/Upper punch/Pressure history=0.2:20, 0.22:20"
  --set "Tools/Lower punch/Displacement history=0:0, 0.26:0, 0.46:1"
  --set "Time stepping/End time=0.46" --set "Time stepping/Number of steps=23")
scene="$SOURCE_DIR/prm/press_cycle_sn_light.prm"
if part whole; then
  DENSIFY="$DENSIFY" bash "$SOURCE_DIR/scripts/run.sh" "$scene" "${cycle[@]}" \
    --set "Output/Directory=whole" > whole.log 2>&1
  echo $? > whole.status
  # its checkpoint after step 16 (the ejection) resumed in a copy
  rm -rf parts
  cp -r whole parts
  "$DENSIFY" "$scene" "${cycle[@]}" --set "Output/Directory=parts" --resume \
    > resumed.log 2>&1
  echo $? > resumed.status
fi
if part withdrawn; then
  # ejected by withdrawal: the die lowered instead of the lower punch raised
  "$DENSIFY" "$scene" "${cycle[@]}" --set "Output/Directory=withdrawn" \
    --set "Tools/Lower punch/Displacement history=0:0" \
    --set "Tools/Die wall/Displacement history=0:0, 0.26:0, 0.46:-1" \
    > withdrawn.log 2>&1
  echo $? > withdrawn.status
fi
part check || exit 0
[ "$(cat whole.status 2>/dev/null)" = 0 ] ||
  { echo "FAIL the cycle by scripts/run.sh"; tail -n 5 whole.log; fails=$((fails + 1)); }
for picture in density forces compaction ejection contacts view_oblique; do
  [ "$(head -c 4 "whole/$picture.png" 2>/dev/null | tail -c 3)" = "PNG" ] ||
    { echo "FAIL scripts/run.sh drew no $picture.png"; fails=$((fails + 1)); }
done
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { ph = $c["phase"]; n = NR
    if (ph < last) { print "FAIL phase " ph " after " last " at step " $1; bad++ }
    seen[ph]++; last = ph
    if (ph == 0) { full = $c["envelope_density"]; h_full = $c["compact_height"] }
    if ($c["upper_punch_stress"] > largest) largest = $c["upper_punch_stress"]
    if (ph == 1) { held++; dev = $c["upper_punch_stress"] - 20; if (dev < 0) dev = -dev
      if (dev > 1e-3 * largest) { print "FAIL the hold carries " $c["upper_punch_stress"] " MPa"; bad++ } }
    if (ph == 2) h_unloaded = $c["compact_height"]
    if (ph >= 2 && $c["upper_punch_force"] != 0) {
      print "FAIL the upper punch carries " $c["upper_punch_force"] " N at step " $1; bad++ }
    if (ph == 3 && $c["die_wall_radial_force"] > 0 &&
        $c["die_wall_radial_force"] > 0.9 * radial_max) {
      F = $c["lower_punch_force"]; mu_N = 0.2 * $c["die_wall_radial_force"]
      dev = (F - mu_N) / mu_N; if (dev < 0) dev = -dev
      if (dev > worst) worst = dev; checked++ }
    if (ph == 3 && $c["die_wall_radial_force"] > radial_max) radial_max = $c["die_wall_radial_force"]
    if (ph == 3 && $c["lower_punch_force"] > peak) { peak = $c["lower_punch_force"]; rise = $c["lower_punch_displacement"] }
    if (ph == 3 && last_rise != "" && ($c["lower_punch_displacement"] - last_rise - 0.1)^2 > 1e-18) {
      print "FAIL the lower punch rose " $c["lower_punch_displacement"] - last_rise " mm at step " $1; bad++ }
    if (ph == 3 && last_rise == "" && $c["newton_iterations"] > 10) {
      print "FAIL the first eject row took " $c["newton_iterations"] " Newton iterations"; bad++ }
    if (ph == 3) last_rise = $c["lower_punch_displacement"]
    end_density = $c["envelope_density"] }
  END {
    for (p = 0; p < 4; ++p) if (!seen[p]) { print "FAIL no phase " p; bad++ }
    if (!checked) { print "FAIL no ejection row slides in the die"; bad++ }
    else if (worst > 0.05) { print "FAIL ejection force off mu N by " 100 * worst " %"; bad++ }
    if (!(end_density < full)) { print "FAIL envelope density " full " -> " end_density; bad++ }
    printf "phases: load %d, hold %d, unload %d, eject %d steps\n", seen[0], seen[1], seen[2], seen[3]
    printf "the hold at 20 MPa: %d step(s) within 1e-3 of the largest stress\n", held
    printf "ejection force against 0.2 x the radial force: largest deviation %.3g %% over %d steps\n", 100 * worst, checked
    printf "envelope density %.4f at full load, %.4f after the ejection\n", full, end_density
    printf "axial %.4g %%\n", 100 * (h_unloaded - h_full) / h_full
    printf "ejection peak %.4g N at a rise of %.4g mm\n", peak, rise
    exit bad > 0 }' whole/statistics.csv > rows.txt || fails=$((fails + 1))
cat rows.txt
axial=$(awk '/^axial/ { print $2 }' rows.txt)
peak=$(awk '/^ejection peak/ { print $3 " N (.*) at a rise of " $9 " mm" }' rows.txt)
grep "^Ejection" whole.log | grep -q "peak force $peak" ||
  { echo "FAIL the ejection line is not the eject rows' peak ($peak)"; grep "^Ejection" whole.log; fails=$((fails + 1)); }
/usr/bin/python3 "$SOURCE_DIR/scripts/postprocess/plot_statistics.py" whole --out plots > plots.log 2>&1 &&
  [ "$(head -c 4 plots/ejection.png | tail -c 3)" = "PNG" ] ||
  { echo "FAIL plot_statistics.py drew no ejection.png"; cat plots.log; fails=$((fails + 1)); }
[ "$(head -c 4 plots/contacts.png 2>/dev/null | tail -c 3)" = "PNG" ] ||
  { echo "FAIL plot_statistics.py drew no contacts.png"; cat plots.log; fails=$((fails + 1)); }
grep -q "^Contacts at the farthest stroke (0.7 mm, .*): mean coordination number" whole.log ||
  { echo "FAIL no contact line in the summary"; fails=$((fails + 1)); }
grep "Springback" whole.log | grep -q "axial $axial %" ||
  { echo "FAIL the springback line is not the unloaded rows' ($axial %)"; fails=$((fails + 1)); }

# ejected by withdrawal: the die lowered instead of the lower punch raised
[ "$(cat withdrawn.status 2>/dev/null)" = 0 ] ||
  { echo "FAIL the withdrawal"; tail -n 5 withdrawn.log; fails=$((fails + 1)); }
paste -d, whole/statistics.csv withdrawn/statistics.csv | awk -F, '
  NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) c[$i] = i; next }
  function abs(x) { return x < 0 ? -x : x }
  { p = c["phase"]; f = c["lower_punch_force"]
    if ($p != $(p + n)) { print "FAIL step " $1 ": phase " $p " / " $(p + n); bad++ }
    if ($p == 3) { ++rows; d = abs($f - $(f + n)) / $f; if (d > worst) worst = d } }
  END { if (!rows) { print "FAIL no eject rows"; bad++ }
    else if (worst > 1e-4) { print "FAIL withdrawal force off the rise by " worst; bad++ }
    else printf "withdrawal: %d eject rows, lower punch force within %.2g of the rise\n", rows, worst
    exit bad > 0 }' || fails=$((fails + 1))
grep -q "^Ejection over a lower punch rise of 0 -> 1 mm" withdrawn.log ||
  { echo "FAIL the withdrawal's ejection line"; grep "^Ejection" withdrawn.log; fails=$((fails + 1)); }

# the checkpoint in the ejection phase resumed in a copy
phase=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  $1 == 16 { print $c["phase"] }' whole/statistics.csv)
[ "$phase" = 3 ] || { echo "FAIL step 16 is in phase '$phase', not the ejection"; fails=$((fails + 1)); }
[ "$(cat resumed.status 2>/dev/null)" = 0 ] &&
  grep -q "Resumed from the checkpoint after step 16" resumed.log ||
  { echo "FAIL the resumed run"; tail -n 5 resumed.log; fails=$((fails + 1)); }
strip() { awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_seconds" || $i == "step_seconds") skip[i] = 1 }
  { line = ""; for (i = 1; i <= NF; ++i) if (!skip[i]) line = line $i ","; print line }' "$1"; }
if cmp -s <(strip whole/statistics.csv) <(strip parts/statistics.csv) &&
  cmp -s whole/particles.csv parts/particles.csv; then
  echo "resumed after step 16 (ejection): the rows of the uninterrupted run"
else
  echo "FAIL the resumed cycle differs from the uninterrupted one"
  diff <(strip whole/statistics.csv) <(strip parts/statistics.csv) | head -n 6
  fails=$((fails + 1))
fi
[ "$fails" -eq 0 ] || { echo "$fails check(s) failed"; exit 1; }
echo "all checks passed"
