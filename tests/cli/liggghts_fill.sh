# The DEM die fill end to end: scripts/packing/liggghts_fill.sh runs LIGGGHTS
# (the Debian package liggghts, which scripts/setup.sh installs; without it
# the test is skipped, exit 77; LIGGGHTS=PATH names another executable).
# 12 spheres of 2-3 mm, half Sn, half Cu, poured into an 8 mm die, settle in
# seconds; the CSV's particles stand on the lower punch (z = 0) inside the
# die, 6 of each material; densify --validate accepts the CSV and the dump
# alike, with the same bed; the same seed gives the same bed; a fill to a
# height strikes off what stands above it; a fill without a count or height
# is one error line, exit 2.
set -eu
cd "$WORK_DIR"
liggghts=${LIGGGHTS:-liggghts}
if ! command -v "$liggghts" > /dev/null; then
  echo "SKIPPED: $liggghts is not installed (scripts/setup.sh installs the Debian package liggghts)"
  exit 77
fi
fill="$SOURCE_DIR/scripts/packing/liggghts_fill.sh"
rm -rf a b h
small=(--liggghts "$liggghts" --die-diameter 8 --particles 12 --diameters 2,3 --materials Sn:0.5,Cu:0.5 --seed 3)
bash "$fill" "${small[@]}" --out a | tee a.txt
grep -q "^LIGGGHTS fill: 12 particles settled" a.txt
# on the lower punch, inside the die, no two overlapping: check_particles by
# --validate; here the bed's bottom and the materials
awk -F, '!/^#/ && $1 != "x" {
    n++; bottom = $3 - $4 / 2; if (n == 1 || bottom < low) low = bottom
    r = sqrt($1 * $1 + $2 * $2) + $4 / 2; if (r > wide) wide = r
    count[$5]++ }
  END { printf "%d particles, lowest bottom %.9f mm, widest %.9f mm, Sn %d, Cu %d\n",
          n, low, wide, count["Sn"], count["Cu"]
        exit !(n == 12 && low > -1e-9 && low < 1e-9 && wide <= 4 + 1e-9 &&
               count["Sn"] == 6 && count["Cu"] == 6) }' a/particles.csv
scene=("$SOURCE_DIR/prm/default.prm" --set "Tools/Die wall/Diameter=8"
  --set "Particles/Materials=Sn, Cu")
"$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=a/particles.csv" \
  2> /dev/null | tee csv.txt
"$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=a/bed.liggghts" \
  2> /dev/null | tee dump.txt
grep -q "valid (12 particle(s)" csv.txt
[ "$(sed 's/^[^(]*//' dump.txt)" = "$(sed 's/^[^(]*//' csv.txt)" ]
echo "ok   the CSV and the dump: the same valid bed"

bash "$fill" "${small[@]}" --out b > /dev/null
cmp <(grep -v '^#' a/particles.csv) <(grep -v '^#' b/particles.csv)
echo "ok   the same seed, the same bed"

# equal spheres of 2 mm up to 5 mm: the tops below 5 mm, up to the shift
# that moves the DEM overlaps apart (below 1 % of a diameter)
bash "$fill" --liggghts "$liggghts" --die-diameter 8 --fill-height 5 --diameters 2 --seed 2 --out h | tee h.txt
awk -F, '!/^#/ && $1 != "x" { n++; top = $3 + $4 / 2; if (top > high) high = top }
  END { printf "%d particles, highest top %.4f mm\n", n, high
        exit !(n > 0 && high <= 5.02 && high > 4) }' h/particles.csv
"$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=h/particles.csv" 2> /dev/null
echo "ok   a fill height"

set +e
out=$(bash "$fill" --die-diameter 8 --out x 2>&1)
rc=$?
set -e
echo "$out"
[ "$rc" -eq 2 ] && [ "$(echo "$out" | wc -l)" -eq 1 ] &&
  echo "$out" | grep -q -- "give --particles N or --fill-height H"
echo "ok   no count, no height: one error line"
