# An STL particle meshed and pressed: the 2 mm cube of tests/data/cube.stl,
# elastic tin on the lower punch, compressed by 0.01 mm between frictionless
# punches in two load steps on one rank, once as in the file and once turned
# by 45 degrees about z. Linear tetrahedra represent the uniform uniaxial
# stress exactly, so the punch force must be E A delta / L = 862.4 N within
# 1 % (the contact penalty's penetration) for both, the lower punch must
# carry it, and the two orientations must agree to 1e-6. Measured: 858.88 N.
# ctest processors: 1
set -eu
cd "$WORK_DIR"
cp "$SOURCE_DIR/tests/data/cube.stl" cube.stl
cat > cube.prm <<'PRM'
subsection Particles
  set Particle file = cube.csv
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
subsection Contact
  set Friction coefficient = 0
end
subsection Time stepping
  set End time        = 1
  set Number of steps = 2
end
subsection Output
  set Interval            = 0
  set Checkpoint interval = 0
end
PRM
echo "0,0,1,,Sn,cube.stl,0,0,0" > cube.csv
echo "0,0,1,,Sn,cube.stl,0,0,45" > turned.csv
"$DENSIFY" cube.prm --set "Output/Directory=cube" > cube.log
"$DENSIFY" cube.prm --set "Particles/Particle file=turned.csv" \
  --set "Output/Directory=turned" > turned.log
/usr/bin/python3 - <<'PY'
import csv, sys
E = 43120.0  # the Sn preset
expected = E * 2 * 2 * 0.01 / 2
ok = True
forces = []
for name in ("cube", "turned"):
    row = list(csv.DictReader(open(name + "/statistics.csv")))[-1]
    upper, lower = float(row["upper_punch_force"]), float(row["lower_punch_force"])
    good = abs(upper / expected - 1) < 0.01 and abs(lower - upper) < 1e-6 * upper
    print("%s: punch force %.2f N (E A delta / L = %.2f N), lower punch %.2f N: %s"
          % (name, upper, expected, lower, "yes" if good else "NO"))
    forces.append(upper)
    ok = ok and good
same = abs(forces[0] - forces[1]) < 1e-6 * forces[0]
print("both orientations agree: %s" % ("yes" if same else "NO"))
sys.exit(0 if ok and same else 1)
PY
