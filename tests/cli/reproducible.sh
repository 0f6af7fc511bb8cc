# A run on 2 MPI ranks with the direct solver repeats exactly (Solver/
# Reproducible = true, the default): the frictionless seven-sphere layer,
# whose point contacts open or close on round-off, run twice for 2 steps
# gives the same Newton residuals to all printed digits and the same
# statistics.csv. MUMPS on both ranks (Reproducible = false) changes its
# round-off from run to run (asynchronous scheduling): the same two runs
# then differed in 8 to 12 residual lines (3 tries), and the outer spheres'
# drift of tests/seven_spheres.cc varied between 0.0065 and 0.071 mm.
# EXTRA="--set Solver/Reproducible=false" ctest -R cli.reproducible shows it.
set -eu
cd "$WORK_DIR"
scene=(--set "Output/Interval=0" --set "Output/Verbose=true"
  --set "Material/Model=elastic" --set "Material/Finite strain=false"
  --set "Mesh/Element size=0.5" --set "Mesh/Refined element size=0.2"
  --set "Mesh/Refinement directions=0,0,1; 0,0,-1; 1,0,0; 0.5,0.8660254,0; -0.5,0.8660254,0; -1,0,0; -0.5,-0.8660254,0; 0.5,-0.8660254,0"
  --set "Mesh/Refinement growth=0.5" --set "Tools/Die wall/Diameter=7.5"
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.4"
  --set "Time stepping/End time=0.25" --set "Time stepping/Number of steps=2"
  --set "Contact/Friction coefficient=0" --set "Contact/Hold poles on axis=vertical"
  --set "Solver/Linear solver=direct" ${EXTRA:-})
for run in a b; do
  "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$SOURCE_DIR/prm/seven_spheres_sn.prm" \
    --set "Output/Directory=$run" "${scene[@]}" > $run.log
  grep -q "2 MPI rank" $run.log
  # the Newton lines (residuals, contact points, line search) and the steps'
  # results, without the wall times
  grep -E "^ +(newton|trial step|line search)" $run.log > $run.newton
  grep -q "newton 3" $run.newton
  cut -d, -f1-9 $run/statistics.csv > $run.csv
done
echo "$(wc -l < a.newton) Newton lines"
cmp a.newton b.newton || { diff a.newton b.newton | head -20; exit 1; }
cmp a.csv b.csv
echo "two runs on 2 ranks: identical"
