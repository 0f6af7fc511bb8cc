# The first run of the README, `bash scripts/run.sh`, on a shrunk version of
# its scene (prm/single_layer_sn_light.prm on a 0.6 mm mesh, 0.08 mm of stroke
# in 2 steps; DENSIFY set, so no set-up): the run, then the density and force
# curves, the per-particle table, the two pictures coloured by plastic
# strain and the summary (scripts/postprocess/report.sh). Needs Debian's
# python3-numpy, python3-matplotlib, python3-vtk9, xvfb and xauth.
set -eu
cd "$WORK_DIR"
rm -rf out
export DENSIFY
bash "$SOURCE_DIR/scripts/run.sh" \
  --set "Output/Directory=out" \
  --set "Mesh/Element size=0.6" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.08" \
  --set "Time stepping/Number of steps=2" > run.txt 2>&1 \
  || { cat run.txt; echo "FAIL: scripts/run.sh failed" >&2; exit 1; }
cat run.txt | tail -n 20

check_png() {  # file, minimum size in bytes
  [ -f "$1" ] || { echo "FAIL: $1 missing" >&2; exit 1; }
  size=$(stat -c %s "$1")
  [ "$size" -ge "$2" ] || { echo "FAIL: $1 has $size bytes (< $2)" >&2; exit 1; }
  [ "$(head -c 4 "$1" | tail -c 3)" = "PNG" ] || { echo "FAIL: $1 is not a PNG" >&2; exit 1; }
}
check_png out/density.png 10000
check_png out/forces.png 10000
check_png out/view_top.png 10000
check_png out/view_oblique.png 10000
# the pictures are coloured by plastic strain
grep -q "plastic_strain) into out" run.txt \
  || { echo "FAIL: render.py did not colour by plastic_strain" >&2; exit 1; }
# the table of the last step: one row per particle (seven spheres)
table=out/particle_table_00002.csv
[ -f "$table" ] || { echo "FAIL: $table missing" >&2; exit 1; }
[ "$(($(wc -l < "$table") - 1))" -eq 7 ] || { echo "FAIL: $table should have 7 rows" >&2; exit 1; }
# the summary: every line, with the numbers of the last row of statistics.csv
for pattern in "^Densify run in out$" "load steps: *2, punch stroke 0.08 mm" \
    "relative density: .* after step 1, .* at the end" \
    "forces at the end: upper punch [0-9.]* N, lower punch [0-9.]* N, die wall [0-9.]* N" \
    "particle volume: *[0-9.]* % of the initial mesh volume kept" \
    "run time: *[0-9.]*[hms]" "out/view_top.png" "out/particle_table_00002.csv"; do
  grep -q "$pattern" run.txt || { echo "FAIL: no '$pattern' in the summary" >&2; exit 1; }
done
last=$(tail -n 1 out/statistics.csv)
density=$(awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) c[$i] = i}
                   END {printf "%.2f %%", 100 * $c["relative_density"]}' out/statistics.csv)
grep -q "$density at the end" run.txt \
  || { echo "FAIL: the summary's final density is not $density ($last)" >&2; exit 1; }
# report.sh alone, and its errors
if bash "$SOURCE_DIR/scripts/postprocess/report.sh" does_not_exist 2> err.txt; then
  echo "FAIL: report.sh accepted a missing directory" >&2; exit 1
fi
grep -q "does not exist" err.txt
echo "first_run: all checks passed"
