# Sourced by the cli tests of CG with AMG against the direct solver.
# solvers_agree PRM OPTION...: runs PRM with the OPTIONs by the direct
# solver on 1 rank (directory direct) and by cg-amg on 1 and 2 ranks (amg1,
# amg2), each within 120 s (no hang), and checks that the 2-rank run had
# 2 ranks and that the steps, times, strokes, forces and densities
# (statistics.csv columns 1-7) of both cg-amg runs agree with the direct
# run's to 1e-5 of themselves (1e-6 N where they are zero; the Newton
# tolerance is 1e-6 of the residual's scale). Stops the test at the first
# failure (set -e).
solvers_agree() {
  local prm=$1
  shift
  timeout 120 "$DENSIFY" "$prm" "$@" --set "Solver/Linear solver=direct" \
    --set "Output/Directory=direct" > direct.log
  timeout 120 "$DENSIFY" "$prm" "$@" --set "Solver/Linear solver=cg-amg" \
    --set "Output/Directory=amg1" > amg1.log
  timeout 120 "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$prm" "$@" \
    --set "Solver/Linear solver=cg-amg" --set "Output/Directory=amg2" > amg2.log
  grep -q "2 MPI rank" amg2.log
  local run
  for run in direct amg1 amg2; do
    tail -n +2 "$run/statistics.csv" | cut -d, -f1-7 > "$run.csv"
  done
  cat direct.csv
  "$NUMDIFF" -r 1e-5 -a 1e-6 -s ', \n' direct.csv amg1.csv
  "$NUMDIFF" -r 1e-5 -a 1e-6 -s ', \n' direct.csv amg2.csv
}
