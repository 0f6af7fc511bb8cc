# Solver/Line search = energy (the step where R(u + s du).du has fallen to
# half its size at s = 0, doc/theory.md; the default) reaches the converged
# states of the residual search, on 1 and 2 ranks: both stop at the same Newton
# tolerance, so the load path must agree to far below that path's own
# accuracy. The light paper scene (seven J2 tin spheres, friction 0.2)
# shrunk to 0.24 mm of stroke in 8 steps; what the energy search saves is
# measured in doc/performance.md, not asserted.
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/shrunk_light_scene.bash"
# the 1-rank runs side by side (the test holds two processors for its
# 2-rank run)
"$DENSIFY" "$scene" --set "Output/Directory=residual" "${common[@]}" \
  --set "Solver/Line search=residual" \
  > residual.log &
first=$!
"$DENSIFY" "$scene" --set "Output/Directory=energy" "${common[@]}" \
  --set "Solver/Line search=energy" --set "Output/Verbose=true" > energy.log
wait $first
"$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$scene" \
  --set "Output/Directory=energy2" "${common[@]}" \
  --set "Solver/Line search=energy" > energy2.log
grep -q "2 MPI rank" energy2.log
# the energy search ran: its trials print R.du relative to R.du at s = 0
grep -q "R.du/|R0.du|" energy.log
newton() { awk -F, 'NR > 1 {s += $8} END {print s}' "$1/statistics.csv"; }
echo "Newton iterations: residual $(newton residual), energy $(newton energy)," \
  "energy on 2 ranks $(newton energy2)"
# step .. relative density: forces and density to 1e-6 relative
for run in energy energy2; do
  cut -d, -f1-7 residual/statistics.csv > a.csv
  cut -d, -f1-7 "$run/statistics.csv" > b.csv
  "$NUMDIFF" -r 1e-6 -a 1e-8 -s ', \n' a.csv b.csv
done
tail -n 1 a.csv
