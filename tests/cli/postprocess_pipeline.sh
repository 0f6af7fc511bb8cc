# The post-processing scripts on a real two-step run of prm/default.prm
# (its own mesh, about 2 s): plot_statistics.py, particle_table.py,
# cell_volume.py and render.py (off-screen, under xvfb-run when there is no
# display) write their files, the pictures are PNGs of some size and the
# table has one row per particle. Then the run's sphere meshes are flattened onto k vertical planes
# by a made-up displacement, and the mid-height sections must have k edges.
# Needs Debian's python3-numpy, python3-matplotlib, python3-vtk9, xvfb and
# xauth (scripts/setup.sh installs them).
set -eu
python=${PYTHON:-/usr/bin/python3}
scripts="$SOURCE_DIR/scripts/postprocess"
cd "$WORK_DIR"
for module in numpy matplotlib vtk; do
  if ! "$python" -c "import $module" 2>/dev/null; then
    echo "FAIL: $python cannot import $module: install python3-numpy, python3-matplotlib and python3-vtk9 (bash scripts/setup.sh)" >&2
    exit 1
  fi
done
if [ -z "${DISPLAY:-}" ] && ! command -v xvfb-run > /dev/null; then
  echo "FAIL: no DISPLAY and no xvfb-run: install xvfb and xauth (bash scripts/setup.sh)" >&2
  exit 1
fi

rm -rf out plots
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" \
  --set "Output/Directory=$WORK_DIR/out" \
  --set "Time stepping/Number of steps=2" > run.txt
grep "^Finished" run.txt

check_png() {  # file, minimum size in bytes
  [ -f "$1" ] || { echo "FAIL: $1 missing" >&2; exit 1; }
  size=$(stat -c %s "$1")
  [ "$size" -ge "$2" ] || { echo "FAIL: $1 has $size bytes (< $2)" >&2; exit 1; }
  [ "$(head -c 4 "$1" | tail -c 3)" = "PNG" ] || { echo "FAIL: $1 is not a PNG" >&2; exit 1; }
  echo "$1: $size bytes"
}

echo "== plot_statistics.py"
"$python" "$scripts/plot_statistics.py" out --out plots
check_png plots/density.png 10000
check_png plots/compaction.png 10000
check_png plots/forces.png 10000
head -n 1 plots/curves.csv | grep -q "^stroke_mm,relative_density_percent,upper_punch_force_N,lower_punch_force_N,die_wall_force_N$"
[ "$(wc -l < plots/curves.csv)" -eq 3 ] || { echo "FAIL: curves.csv should have 2 steps" >&2; exit 1; }

echo "== particle_table.py"
"$python" "$scripts/particle_table.py" out --step 2
table=out/particle_table_00002.csv
head -n 1 "$table" | grep -q "^particle,contact_partners,die_contact,volume,mean_plastic_strain,max_plastic_strain,cross_section_edges"
particles=$(awk -F, 'NR > 1 && $1 == 2 {n++} END {print n}' out/particles.csv)
rows=$(($(wc -l < "$table") - 1))
echo "$rows rows, $particles particles in particles.csv at step 2"
[ "$particles" -ge 1 ] && [ "$rows" -eq "$particles" ] || { echo "FAIL: one row per particle expected" >&2; exit 1; }
# every particle has a section with an edge count and a positive volume
awk -F, 'NR > 1 && ($7 == "" || $4 <= 0) {bad = 1} END {exit bad}' "$table" \
  || { echo "FAIL: a row lacks its edge count or volume" >&2; cat "$table"; exit 1; }
# the spheres are pressed by 8 um only: their sections are still round
awk -F, 'NR > 1 && $7 != 0 {bad = 1} END {exit bad}' "$table" \
  || { echo "FAIL: a barely pressed sphere has a section with straight edges" >&2; cat "$table"; exit 1; }
"$python" "$scripts/particle_table.py" out > /dev/null
[ -f out/particle_table_00001.csv ] && [ -f out/particle_table_00002.csv ]

echo "== edges of the run's spheres flattened onto k planes"
"$python" "$scripts/flatten_check.py" out --step 2

echo "== cell_volume.py"
# pressed by 8 um, every cell keeps its volume within a tenth: the
# smallest ratio of each step is below 1 (the contacts) and above 0.9
"$python" "$scripts/cell_volume.py" out > cells.txt
cat cells.txt
awk '$1 ~ /^[0-9]+$/ {n++; if (!($3 > 0.9 && $3 < 1.)) bad = 1}
     END {exit bad || n != 2}' cells.txt \
  || { echo "FAIL: cell_volume.py: two steps with 0.9 < min V/V0 < 1 expected" >&2; exit 1; }

echo "== render.py"
"$python" "$scripts/render.py" out --out plots --size 600 450
check_png plots/view_top.png 10000
check_png plots/view_oblique.png 10000

echo "== errors"
if "$python" "$scripts/plot_statistics.py" does_not_exist 2> err.txt; then
  echo "FAIL: plot_statistics.py accepted a missing directory" >&2; exit 1
fi
cat err.txt
[ "$(wc -l < err.txt)" -eq 1 ] && grep -q "does not exist" err.txt
if "$python" "$scripts/render.py" out --step 7 2> err.txt; then
  echo "FAIL: render.py accepted a step without output" >&2; exit 1
fi
cat err.txt
echo "postprocess_pipeline: all checks passed"
