# Packings from the .prm (Particles/Packing): the hexagonal layer of the
# reference paper (d = 2.5 mm, die 20 mm) has 43 particles at 44.79 %; a
# seeded random layer is valid (build_scene checks overlaps and the die fit),
# the same for the same seed; a layer that cannot be placed is a one-line
# error naming the parameter (exit 2). A shrunk paper scene (19 spheres,
# elastic, coarse): the relative density rises at every step and equals the
# particle volume over the die area times the punch gap; upper = lower + die
# wall; the particle volume changes only by the elastic compression.
set -eu
cd "$WORK_DIR"
paper=(--set "Particles/Packing=hexagonal layer" --set "Tools/Die wall/Diameter=20")
"$DENSIFY" --validate "$SOURCE_DIR/prm/default.prm" "${paper[@]}" | tee hex.txt
grep -q "valid (43 particle(s), relative density 44.79 % " hex.txt

random=(--set "Particles/Packing=random layer" --set "Tools/Die wall/Diameter=20"
        --set "Particles/Number of particles=35" --set "Particles/Packing seed=3")
"$DENSIFY" --validate "$SOURCE_DIR/prm/default.prm" "${random[@]}" | tee random.txt
grep -q "valid (35 particle(s)" random.txt

set +e
"$DENSIFY" --validate "$SOURCE_DIR/prm/default.prm" "${random[@]}" \
  --set "Particles/Number of particles=60" > full.txt 2> full.err
rc=$?
set -e
cat full.err
[ "$rc" -eq 2 ]
# one error line (besides the warning that default.prm's Centres are unused)
[ "$(grep -vc '^densify: warning: ' full.err)" -eq 1 ]
grep -q "Particles/Number of particles" full.err

# the shrunk paper scene
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" \
  --set "Particles/Packing=hexagonal layer" --set "Tools/Die wall/Diameter=12.6" \
  --set "Mesh/Element size=0.6" --set "Output/Directory=out19" --set "Output/Interval=0" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.1" \
  --set "Time stepping/Number of steps=3" > run19.txt
grep -q "Densify: 19 particle(s)" run19.txt
/usr/bin/python3 - out19/statistics.csv <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 3, len(rows)
area = math.pi * 6.3 ** 2
v0 = None
last = 0.0
for r in rows:
    rho = float(r["relative_density"])
    gap = 2.5 - float(r["punch_displacement"])
    V = float(r["particle_volume"])
    expected = V / (area * gap)
    assert abs(rho - expected) < 1e-9 * expected, (rho, expected)
    assert rho > last, (rho, last)
    last = rho
    up, low, die = (float(r[k]) for k in ("upper_punch_force", "lower_punch_force", "die_wall_force"))
    assert abs(up - low - die) < 1e-6 * up, (up, low, die)
V0 = float(rows[0]["particle_volume"])
change = (float(rows[-1]["particle_volume"]) - V0) / V0
# elastic compression only (measured: see the printed value)
assert -5e-3 < change < 0, change
print("density rises and equals V / (A gap); upper = lower + die wall: yes;"
      " particle volume change from step 1 to 3: %.3g" % change)
PY
