# The plastic_strain field of the graphics belongs to the right cells: three
# equal J2 tin spheres (finite strain, P1 with the nodal-averaged F-bar, whose
# plastic history is kept per cell corner) pressed side by side between the
# punches deform alike, so the per-particle mean and maximum of the written
# plastic_strain (particle_table.py) must agree to 2 % and be above zero.
# Reading the history with the quadrature-point layout put another cell's
# strain on each cell and none on the last sphere.
set -eu
cd "$WORK_DIR"
rm -rf out
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Output/Directory=out" \
  --set "Material/Model=J2 plasticity" --set "Material/Finite strain=true" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.06" \
  --set "Mesh/Element size=0.5" --set "Mesh/Refined element size=0.2" \
  --set "Solver/Linear solver=direct" --set "Time stepping/Number of steps=2" > run.txt
grep -q "nodal-averaged F-bar" run.txt
/usr/bin/python3 "$SOURCE_DIR/scripts/postprocess/particle_table.py" out --step -1 --out table
/usr/bin/python3 - table/particle_table_00002.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 3, rows
for key in ("mean_plastic_strain", "max_plastic_strain"):
    values = [float(r[key]) for r in rows]
    print(key, values)
    assert min(values) > 0, (key, values)
    assert max(values) - min(values) <= 0.02 * max(values), (key, values)
PY
