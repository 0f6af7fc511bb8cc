# Explicit dynamics: a punch withdrawn from a sphere within one station. An
# elastic sphere of prm/default.prm on a 0.6 mm mesh, pressed by 0.02 mm in
# two stations (2,000 explicit steps in all), then lifted to 0.01 mm above
# its start in the third: the contacts open within that station. Each
# station's force is the least-squares line through its interval's values;
# through a falling force and then zeros that line runs below zero at the
# station's end (-2.1 N on the upper and -5.0 N on the lower punch,
# measured without the bound). Contact only presses: every punch and
# particle contact force in statistics.csv is >= 0, and the unloaded
# stations carry 0 N on the upper punch.
set -eu
cd "$WORK_DIR"
rm -rf out
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Output/Directory=out" \
  --set "Output/Interval=0" --set "Solver/Method=explicit" \
  --set "Particles/Centres=0,0,1.25" --set "Mesh/Element size=0.6" \
  --set "Time stepping/Number of steps=4" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.5:0.02, 0.75:-0.01, 1:-0.01" \
  --set "Explicit/Number of steps=2000" > run.log 2>&1 ||
  { tail -n 5 run.log; echo "FAIL the run"; exit 1; }
awk -F, 'BEGIN { split("upper_punch_force lower_punch_force particle_contact_force", names, " ") }
  NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { for (k in names) if ($c[names[k]] < 0) {
      print "FAIL step " $1 ": " names[k] " = " $c[names[k]]; bad++ }
    if ($1 >= 3 && $c["upper_punch_force"] != 0) {
      print "FAIL step " $1 ": the withdrawn punch carries " $c["upper_punch_force"] " N"; bad++ }
    if ($1 == 2 && $c["upper_punch_force"] <= 0) {
      print "FAIL step 2: the pressed sphere carries nothing"; bad++ } }
  END { if (NR != 5) { print "FAIL " NR - 1 " rows"; bad++ }
    if (!bad) print "explicit_unload: contact forces >= 0 at every station, 0 N once withdrawn"
    exit bad > 0 }' out/statistics.csv
