# CG with ML AMG on a scene with a free particle: three tin spheres in a row
# pressed by the punches and a fourth, small sphere that touches nothing
# (friction 0.2, symmetric friction tangent, 0.6 mm mesh, 3 steps). The AMG
# set-up and CG handle the particle that no contact holds (the
# stabilisation holds it): on 1 and 2 ranks the run finishes, within a time
# limit (no hang), with the direct solver's forces, and the free sphere does
# not move.
set -eu
cd "$WORK_DIR"
common=(--set "Particles/Centres=-2.5,0,1.25; 0,0,1.25; 2.5,0,1.25; 5,0,1.25"
  --set "Particles/Diameters=2.5,2.5,2.5,1.0" --set "Tools/Die wall/Diameter=12"
  --set "Mesh/Element size=0.6" --set "Time stepping/Number of steps=3"
  --set "Time stepping/End time=0.3"
  --set "Tools/Upper punch/Displacement history=0:0, 0.3:0.09"
  --set "Contact/Friction tangent=symmetric"
  --set "Output/Interval=0" --set "Output/Checkpoint interval=0")
timeout 120 "$DENSIFY" "$SOURCE_DIR/prm/seven_spheres_sn.prm" "${common[@]}" \
  --set "Solver/Linear solver=direct" --set "Output/Directory=direct" \
  > direct.log
timeout 120 "$DENSIFY" "$SOURCE_DIR/prm/seven_spheres_sn.prm" "${common[@]}" \
  --set "Solver/Linear solver=cg-amg" --set "Output/Directory=amg1" > amg1.log
timeout 120 "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" \
  "$SOURCE_DIR/prm/seven_spheres_sn.prm" "${common[@]}" \
  --set "Solver/Linear solver=cg-amg" --set "Output/Directory=amg2" > amg2.log
grep -q "4 particle(s).*2 MPI rank" amg2.log
for run in direct amg1 amg2; do
  # columns: step, time, punch, F_upper, F_lower, F_die, relative density
  tail -n +2 "$run/statistics.csv" | cut -d, -f1-7 > "$run.csv"
done
cat direct.csv
"$NUMDIFF" -r 1e-5 -a 1e-6 -s ', \n' direct.csv amg1.csv
"$NUMDIFF" -r 1e-5 -a 1e-6 -s ', \n' direct.csv amg2.csv
# particles.csv: particle 3's mean displacement (columns 6-8) stays below
# 1e-9 mm at every step
for run in amg1 amg2; do
  awk -F, '$2 == 3 {n++; for (c = 6; c <= 8; ++c) if ($c > 1e-9 || $c < -1e-9) bad++}
    END {printf "%s: free particle at %d steps, moved at %d\n", FILENAME, n, bad
      exit !(n == 3 && bad == 0)}' "$run/particles.csv"
done
