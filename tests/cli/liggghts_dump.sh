# A LIGGGHTS dump as Particles/Particle file: tests/data/die_fill.liggghts,
# 12 spheres of 2-3 mm (atom types 1 and 2) poured into an 8 mm die by
# scripts/packing/liggghts_fill.sh. --validate reads its last snapshot
# (metres to mm, type t the t-th name of Particles/Materials), moves the DEM
# contact overlaps apart and finds the bed the script wrote from it
# (tests/data/die_fill.csv: the same count, density, coordination number);
# one load step presses the bed with each atom's material; a malformed dump,
# a die or lower punch that does not fit the fill, or too few material
# names is one error line naming the parameter, exit 2.
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
data="$SOURCE_DIR/tests/data"
scene=("$SOURCE_DIR/prm/default.prm" --set "Tools/Die wall/Diameter=8"
  --set "Particles/Materials=Sn, Cu")
"$DENSIFY" --validate "${scene[@]}" \
  --set "Particles/Particle file=$data/die_fill.liggghts" 2> /dev/null | tee dump.txt
grep -q "valid (12 particle(s), relative density 37.12 % " dump.txt
"$DENSIFY" --validate "${scene[@]}" \
  --set "Particles/Particle file=$data/die_fill.csv" 2> /dev/null | tee csv.txt
[ "$(sed 's/^[^(]*//' dump.txt)" = "$(sed 's/^[^(]*//' csv.txt)" ]
echo "ok   the dump and the script's CSV give the same bed"

# one load step: atom 1 (type 2) is particle 0, Cu; atom 2 (type 1) Sn
"$DENSIFY" "${scene[@]}" --set "Particles/Particle file=$data/die_fill.liggghts" \
  --set "Output/Directory=out" --set "Output/Interval=0" \
  --set "Output/Checkpoint interval=0" --set "Mesh/Element size=0.8" \
  --set "Time stepping/Number of steps=1" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.02" > run.txt 2> run.err
grep -q "12 particle(s)" run.txt
[ "$(wc -l < out/statistics.csv)" -eq 2 ]
sed -n 2p out/particles.csv | grep -q '^1,0,Cu,'
sed -n 3p out/particles.csv | grep -q '^1,1,Sn,'
[ "$(grep -c '^1,[0-9]*,Cu,' out/particles.csv)" -eq 6 ]
[ "$(grep -c '^1,[0-9]*,Sn,' out/particles.csv)" -eq 6 ]
echo "ok   one load step with the dump's materials"

# bad input (expect_error counts failures in $fails)
set +e
snapshot() { # the stored dump's last snapshot with its ATOMS line and rows changed
  awk '/^ITEM: TIMESTEP/ {n = NR} {line[NR] = $0} END {for (i = n; i <= NR; ++i) print line[i]}' \
    "$data/die_fill.liggghts"
}
snapshot | sed 's/ radius *$//; /^[0-9]/ s/ [^ ]* *$//' > no_radius.liggghts
snapshot | sed '$ s/ [^ ]* *$/ 0/' > zero_radius.liggghts
printf 'ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n0\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id type x y z radius\n' > empty.liggghts
snapshot | head -n 15 > cut.liggghts
snapshot | awk '/^[0-9]/ && NF == 6 {$2 = 3} {print}' > type3.liggghts
snapshot | awk '/^[0-9]/ && NF == 6 {for (k = 3; k <= 6; ++k) $k *= 1000} {print}' > millimetres.liggghts
expect_error no_radius 2 "no_radius.liggghts:9: the ATOMS line has no column radius" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=no_radius.liggghts"
expect_error zero_radius 2 "zero_radius.liggghts:21: atom 9 has the radius 0 m: radii must be > 0" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=zero_radius.liggghts"
expect_error empty 2 "Particles/Particle file: empty.liggghts:9: the last snapshot (timestep 0, line 1) has no atoms" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=empty.liggghts"
expect_error cut_short 2 "ends after 6 of 12 atoms: the dump is cut short" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=cut.liggghts"
expect_error type3 2 "Particles/Materials: type3.liggghts:10: atom 2 has the type 3" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=type3.liggghts"
expect_error millimetres 2 "crosses the die wall by 3996.2 mm" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=millimetres.liggghts"
expect_error small_die 2 "set Tools/Die wall/Diameter to the die of the fill" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=$data/die_fill.liggghts" \
  --set "Tools/Die wall/Diameter=7.5"
expect_error high_punch 2 "set Tools/Lower punch/Position to the floor of the fill" \
  "$DENSIFY" --validate "${scene[@]}" --set "Particles/Particle file=$data/die_fill.liggghts" \
  --set "Tools/Lower punch/Position=0.5"
[ "$fails" -eq 0 ] || exit 1
echo "ok   bad dumps"
