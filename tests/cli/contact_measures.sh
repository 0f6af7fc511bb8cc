# The packing's contact numbers and the particles' mean stresses
# (doc/user_guide.md, "The compaction curve"): the 2 mm cube of
# tests/data/cube.stl standing on a 3 x 3 x 2 mm box (both elastic tin,
# P1, 0.5 mm elements), pressed by 0.01 mm in two steps between punches,
# friction 0.2 everywhere (it holds the cube's sideways motion), on 1 and 2
# ranks.
#   1. statistics.csv: one pair of particles in contact, so the mean
#      coordination number is 2 x 1 / 2 = 1; the contact area fraction is
#      twice the cube's 4 mm^2 face over the two bodies' 66 mm^2 of surface,
#      0.1212, within 10 % (a facet counts whole once one of its points
#      carries a pressure, so the facets that the square's edge cuts add an
#      error of the order of the element size along the 8 mm edge: measured
#      +8.2 % at 0.5 mm, +1.7 % at 0.35 mm, -1.8 % at 0.25 mm).
#   2. particles.csv, by equilibrium (the mean stress of a body is the sum
#      of the moments x (x) f of the forces on it over its volume): the two
#      bodies' mean axial stresses times their volumes sum to minus the
#      punch force times the punches' gap, within 0.5 % (the penalty's
#      penetration and the F-bar; measured 0.01 %); mean_pressure is minus a
#      third of the mean stress's trace; the cube's mean axial stress is
#      -F / 4 mm^2 within 1 % (its height over its volume is 1 / 4 mm^2 to
#      0.1 %); each body's mean von Mises stress is at least the von Mises
#      stress of its mean stress (the mean of a norm is at least the norm of
#      the mean).
#   3. The .vtu has the particles' mean stress fields.
#   4. 1 and 2 ranks write the same rows (all but the wall times) to 1e-6.
set -u
cd "$WORK_DIR"
fails=0
cp "$SOURCE_DIR/tests/data/cube.stl" cube.stl
/usr/bin/python3 - <<'PY'
# a closed 3 x 3 x 2 mm box centred at the origin, facets facing outward
quads = [((0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)),
         ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)),
         ((0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)),
         ((0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)),
         ((0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)),
         ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1))]
half = (1.5, 1.5, 1.0)
with open("base.stl", "w") as f:
    f.write("solid base\n")
    for q in quads:
        for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            f.write("facet normal 0 0 0\n outer loop\n")
            for corner in t:
                f.write("  vertex %g %g %g\n"
                        % tuple((2 * c - 1) * h for c, h in zip(corner, half)))
            f.write(" endloop\nendfacet\n")
    f.write("endsolid base\n")
PY
printf '0,0,1,,Sn,base.stl,0,0,0\n0,0,3,,Sn,cube.stl,0,0,0\n' > bodies.csv
cat > stack.prm <<'PRM'
subsection Particles
  set Particle file = bodies.csv
end
subsection Mesh
  set Polynomial degree = 1
  set Element size      = 0.5
end
subsection Material
  set Model         = elastic
  set Finite strain = false
end
subsection Tools
  subsection Upper punch
    set Displacement history = 0:0, 1:0.01
  end
  subsection Die wall
    set Enabled = false
  end
end
subsection Time stepping
  set End time        = 1
  set Number of steps = 2
end
subsection Output
  set Interval            = 2
  set Checkpoint interval = 0
end
PRM
"$DENSIFY" stack.prm --set "Output/Directory=one" > one.log 2>&1 ||
  { echo "FAIL the 1-rank run"; tail -3 one.log; fails=$((fails + 1)); }
$MPIEXEC -np 2 "$DENSIFY" stack.prm --set "Output/Directory=two" > two.log 2>&1 ||
  { echo "FAIL the 2-rank run"; tail -3 two.log; fails=$((fails + 1)); }

/usr/bin/python3 - <<'PY' || fails=$((fails + 1))
import csv, sys
ok = True
def check(what, good):
    global ok
    print(("ok   " if good else "FAIL ") + what)
    ok = ok and good
stats = list(csv.DictReader(open("one/statistics.csv")))
for row in stats:
    check("step %s: %s pair(s) in contact, coordination number %s (1)"
          % (row["step"], row["contact_pairs"], row["coordination_number"]),
          row["contact_pairs"] == "1" and float(row["coordination_number"]) == 1)
last = stats[-1]
fraction, expected = float(last["contact_area_fraction"]), 2 * 4 / 66
check("contact area fraction %.4f against %.4f (%+.1f %%, within 10 %%)"
      % (fraction, expected, 100 * (fraction / expected - 1)),
      abs(fraction / expected - 1) < 0.1)
F = float(last["upper_punch_force"])
gap = 4 - float(last["punch_displacement"])
rows = [r for r in csv.DictReader(open("one/particles.csv"))
        if r["step"] == last["step"]]
moment = sum(float(r["mean_stress_zz"]) * float(r["volume"]) for r in rows)
check("sum of mean axial stress x volume %.2f N mm against -F x gap %.2f "
      "N mm (within 0.5 %%)" % (moment, -F * gap),
      abs(moment / (-F * gap) - 1) < 0.005)
for r in rows:
    trace = sum(float(r["mean_stress_" + c]) for c in ("xx", "yy", "zz"))
    check("particle %s: mean_pressure %s = -trace / 3 (%.6g)"
          % (r["particle"], r["mean_pressure"], -trace / 3),
          abs(float(r["mean_pressure"]) + trace / 3) <= 1e-6 * abs(trace))
    s = {c: float(r["mean_stress_" + c])
         for c in ("xx", "yy", "zz", "xy", "yz", "xz")}
    of_mean = (0.5 * ((s["xx"] - s["yy"]) ** 2 + (s["yy"] - s["zz"]) ** 2
                      + (s["zz"] - s["xx"]) ** 2)
               + 3 * (s["xy"] ** 2 + s["yz"] ** 2 + s["xz"] ** 2)) ** 0.5
    check("particle %s: mean von Mises stress %s MPa >= that of the mean "
          "stress %.6g MPa" % (r["particle"], r["mean_von_mises"], of_mean),
          float(r["mean_von_mises"]) >= of_mean * (1 - 1e-9))
cube = float(rows[1]["mean_stress_zz"])
check("the cube's mean axial stress %.2f MPa against -F / A = %.2f MPa "
      "(within 1 %%)" % (cube, -F / 4), abs(cube / (-F / 4) - 1) < 0.01)
sys.exit(0 if ok else 1)
PY

for field in particle_mean_pressure particle_mean_von_mises; do
  grep -q "Name=\"$field\"" one/solution_00002.0.vtu ||
    { echo "FAIL no $field in the .vtu"; fails=$((fails + 1)); }
done
for table in statistics particles; do
  for dir in one two; do
    cut -d, -f1-9,11-15,17- $dir/$table.csv > $dir/$table.compared
  done
  [ "$table" = particles ] && for dir in one two; do
    cp $dir/particles.csv $dir/particles.compared
  done
  "$NUMDIFF" -q -r 1e-6 -a 1e-8 -s ', \n' one/$table.compared \
    two/$table.compared ||
    { echo "FAIL $table.csv differs between 1 and 2 ranks"; fails=$((fails + 1)); }
done
[ $fails -eq 0 ] && echo "contact_measures: all checks passed"
exit $fails
