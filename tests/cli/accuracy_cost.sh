# The accuracy-cost study end to end on its tiny grid (a shrunk sphere and a
# shrunk light layer, seconds): one CSV row per run with settings, times,
# Newton iterations and errors against each scene's reference run; then the
# plotting reads the CSV and writes a PNG per scene and the table of the
# Pareto fronts.
set -eu
cd "$WORK_DIR"
rm -rf study
DENSIFY=$DENSIFY bash "$SOURCE_DIR/benchmarks/accuracy_cost.sh" --grid tiny --out study
csv=study/accuracy_cost.csv
head -n 1 "$csv" | grep -q "^scene,label,status,degree,element_size,"
# five runs of the tiny grid, all converged, on two scenes
[ "$(tail -n +2 "$csv" | wc -l)" -eq 5 ]
[ "$(tail -n +2 "$csv" | cut -d, -f3 | sort -u)" = ok ]
[ "$(tail -n +2 "$csv" | cut -d, -f1 | sort -u | tr '\n' ' ')" = "light sphere " ]
/usr/bin/python3 - "$csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
def num(r, k):
    return float(r[k]) if r[k] else math.nan
for scene in ("sphere", "light"):
    runs = [r for r in rows if r["scene"] == scene]
    ref = runs[0]
    # the reference has no error against itself
    assert num(ref, "err_force_percent") == 0, ref
    for r in runs:
        assert num(r, "wall_s") > 0 and num(r, "core_s") > 0, r
        assert int(r["newton_iterations"]) > 0 and int(r["load_steps_done"]) == int(r["load_steps"]), r
        assert num(r, "F100_N") > 0, r
        assert not math.isnan(num(r, "err_force_percent")), r
        assert not math.isnan(num(r, "err_volume_pp")), r
    # a coarser run differs from its reference
    assert all(num(r, "err_force_percent") > 0 for r in runs[1:]), runs
# the light layer has a density and a shape (needs python3-vtk9, as the
# post-processing does)
light = [r for r in rows if r["scene"] == "light"]
assert all(not math.isnan(num(r, "density_percent")) for r in light), light
assert all(num(r, "section_area_mm2") > 0 for r in rows), rows
print("study CSV ok:", len(rows), "runs")
PY
/usr/bin/python3 "$SOURCE_DIR/benchmarks/accuracy_cost_plot.py" "$csv" --out plots > fronts.txt
cat fronts.txt
[ -s plots/accuracy_sphere.png ] && [ -s plots/accuracy_light.png ]
grep -q "^## sphere: reference" plots/accuracy_fronts.md
grep -q "^### punch force error (%), largest" plots/accuracy_fronts.md
grep -q "^| P1 0.7 4 steps |" plots/accuracy_fronts.md
# bad arguments: exit 2 with one line
rc=0
bash "$SOURCE_DIR/benchmarks/accuracy_cost.sh" --grid huge > bad.txt 2>&1 || rc=$?
[ $rc -eq 2 ] && [ "$(wc -l < bad.txt)" -eq 1 ]
rc=0
/usr/bin/python3 "$SOURCE_DIR/benchmarks/accuracy_cost_plot.py" missing.csv > bad.txt 2>&1 || rc=$?
[ $rc -eq 2 ] && [ "$(wc -l < bad.txt)" -eq 1 ]
echo "accuracy_cost ok"
