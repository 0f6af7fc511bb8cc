# CG with ML AMG on a frictional multi-particle scene: the seven tin spheres
# of prm/seven_spheres_sn.prm (friction 0.2, 0.6 mm mesh), pressed 0.12 mm
# in 4 steps with the symmetric friction tangent (one of the two CG can take), give
# the direct solver's forces and densities on 1 rank and on 2 ranks, to the
# Newton tolerance (tests/cli/lib/solver_agree.bash). CG must really run:
# more linear than Newton iterations.
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/solver_agree.bash"
solvers_agree "$SOURCE_DIR/prm/seven_spheres_sn.prm" \
  --set "Mesh/Element size=0.6" --set "Time stepping/Number of steps=4" \
  --set "Time stepping/End time=0.4" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.4:0.12" \
  --set "Contact/Friction tangent=symmetric" \
  --set "Output/Interval=0" --set "Output/Checkpoint interval=0"
# column 8: newton_iterations, column 9: linear_iterations
for run in amg1 amg2; do
  awk -F, 'NR > 1 {n += $8; l += $9} END {
    printf "%s: %d Newton, %d CG iterations\n", FILENAME, n, l
    exit !(l > n)}' "$run/statistics.csv"
done
