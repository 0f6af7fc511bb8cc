# Particles from a CSV file (x,y,z,diameter[,material]) run end to end, with
# per-particle materials, and relative paths taken from the working directory.
set -eu
cd "$WORK_DIR"
mkdir -p input
cat > input/particles.csv <<'CSV'
# x, y, z, diameter, material
x,y,z,diameter,material
-1.5,0,1,2,Sn
1.5,0,0.75,1.5,Cu
CSV
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" \
  --set "Particles/Particle file=input/particles.csv" \
  --set "Output/Directory=out" --set "Output/Interval=0" \
  --set "Mesh/Element size=0.5" --set "Time stepping/Number of steps=1" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.01" > log.txt
grep -q "2 particle(s)" log.txt
[ "$(wc -l < out/statistics.csv)" -eq 2 ]
# both particles with their own material, in input order
sed -n 2p out/particles.csv | grep -q '^1,0,Sn,'
sed -n 3p out/particles.csv | grep -q '^1,1,Cu,'
# the upper punch starts on the highest particle (z = 2) and touches only it
tail -n 1 out/statistics.csv | cut -d, -f4 | grep -qv '^0$'
echo ok
# a mixture drawn by fraction overrides the file's materials: one of each
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" \
  --set "Particles/Particle file=input/particles.csv" \
  --set "Particles/Material fractions=Fe:0.5, Cu:0.5" \
  --set "Output/Directory=out_mix" --set "Output/Interval=0" \
  --set "Mesh/Element size=0.5" --set "Time stepping/Number of steps=1" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.01" > mix.txt
[ "$(cut -d, -f3 out_mix/particles.csv | sort | tr '\n' ' ')" = "Cu Fe material " ]
echo ok
# touching particles: particle-particle contact is on, and the run reports
# contact partners per particle (columns are only appended after them)
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" \
  --set "Particles/Centres=0,0,1.25; 2.5,0,1.25" \
  --set "Output/Directory=out_touch" --set "Output/Interval=0" \
  --set "Mesh/Element size=0.6" --set "Time stepping/Number of steps=1" > touch.txt
grep -q "particle-particle contact (friction 0.2 Coulomb)" touch.txt
head -n 1 out_touch/particles.csv | grep -q ',contact_partners,die_contact\(,\|$\)'
[ "$(wc -l < out_touch/particles.csv)" -eq 3 ]
echo ok
