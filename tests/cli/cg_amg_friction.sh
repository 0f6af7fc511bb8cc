# CG with ML AMG on a frictional multi-particle scene: the seven tin spheres
# of prm/seven_spheres_sn.prm (friction 0.2, 0.6 mm mesh), pressed 0.12 mm
# in 4 steps with the symmetric friction tangent (the one CG can take), give
# the direct solver's forces and densities on 1 rank and on 2 ranks, to the
# Newton tolerance. CG must really run: more linear than Newton iterations.
set -eu
cd "$WORK_DIR"
common=(--set "Mesh/Element size=0.6" --set "Time stepping/Number of steps=4"
  --set "Time stepping/End time=0.4"
  --set "Tools/Upper punch/Displacement history=0:0, 0.4:0.12"
  --set "Contact/Friction tangent=symmetric"
  --set "Output/Interval=0" --set "Output/Checkpoint interval=0")
"$DENSIFY" "$SOURCE_DIR/prm/seven_spheres_sn.prm" "${common[@]}" \
  --set "Solver/Linear solver=direct" --set "Output/Directory=direct" \
  > direct.log
"$DENSIFY" "$SOURCE_DIR/prm/seven_spheres_sn.prm" "${common[@]}" \
  --set "Solver/Linear solver=cg-amg" --set "Output/Directory=amg1" > amg1.log
"$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" \
  "$SOURCE_DIR/prm/seven_spheres_sn.prm" "${common[@]}" \
  --set "Solver/Linear solver=cg-amg" --set "Output/Directory=amg2" > amg2.log
grep -q "2 MPI rank" amg2.log
for run in direct amg1 amg2; do
  # columns: step, time, punch, F_upper, F_lower, F_die, relative density
  tail -n +2 "$run/statistics.csv" | cut -d, -f1-7 > "$run.csv"
done
cat direct.csv
# the Newton tolerance is 1e-6 of the residual's scale; the forces agree to
# 1e-5 of themselves (and 1e-6 N where they are zero)
"$NUMDIFF" -r 1e-5 -a 1e-6 -s ', \n' direct.csv amg1.csv
"$NUMDIFF" -r 1e-5 -a 1e-6 -s ', \n' direct.csv amg2.csv
# column 8: newton_iterations, column 9: linear_iterations
for run in amg1 amg2; do
  awk -F, 'NR > 1 {n += $8; l += $9} END {
    printf "%s: %d Newton, %d CG iterations\n", FILENAME, n, l
    exit !(l > n)}' "$run/statistics.csv"
done
