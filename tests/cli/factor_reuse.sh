# Solver/Linear solver = gmres-lu (GMRES preconditioned by the factorization
# of an earlier tangent) gives the direct solver's results, on 1 and 2 ranks,
# with fewer factorizations than linear solves; so does the inexact Newton of
# Solver/Adaptive linear tolerance (what it costs or saves is printed and
# measured in doc/performance.md, not asserted): the light
# paper scene (seven J2 tin spheres with friction 0.2) shrunk to 0.24 mm of
# stroke in 8 steps, where the particles press on the punches and the die
# wall. Each run is a part of its own (tests/cli/lib/parts.bash).
# ctest parts: direct reuse adaptive fronts_1 reuse2:2 fronts_2:2
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
source "$SOURCE_DIR/tests/cli/lib/shrunk_light_scene.bash"
# (the scene itself asks for gmres-lu)
part direct && "$DENSIFY" "$scene" --set "Output/Directory=direct" "${common[@]}" \
  --set "Solver/Linear solver=direct" > direct.log
part reuse && "$DENSIFY" "$scene" --set "Output/Directory=reuse" "${common[@]}" \
  --set "Solver/Linear solver=gmres-lu" > reuse.log
part adaptive && "$DENSIFY" "$scene" --set "Output/Directory=adaptive" "${common[@]}" \
  --set "Solver/Linear solver=gmres-lu" \
  --set "Solver/Adaptive linear tolerance=true" > adaptive.log
part reuse2 && "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$scene" --set "Output/Directory=reuse2" \
  "${common[@]}" --set "Solver/Linear solver=gmres-lu" > reuse2.log
# the first step of MUMPS's factorizations on 1 rank and both ways on 2
# (checked below)
fronts() { # ranks, Solver/Reproducible
  local rc=0
  "$MPIEXEC" --oversubscribe -np "$1" "$DENSIFY" "$scene" "${common[@]}" \
    --set "Output/Directory=fronts$1$2" --set "Output/Verbose=true" \
    --set "Solver/Reproducible=$2" --stop-after 1 > "fronts$1$2.log" || rc=$?
  [ "$rc" -eq 3 ] # stopped by --stop-after
}
part fronts_1 && fronts 1 true
if part fronts_2; then
  fronts 2 true
  fronts 2 false
fi
part check || exit 0
grep -q "linear solver direct" direct.log
grep -q "2 MPI rank" reuse2.log
# the timing table: factorizations ("Solve: direct") and reusing solves
factorizations=$(grep "Solve: direct" reuse.log | awk -F'|' '{print $3+0}')
reused=$(grep "Solve: GMRES with old factors" reuse.log | awk -F'|' '{print $3+0}')
echo "gmres-lu: $factorizations factorizations, $reused solves with old factors"
[ "$reused" -gt "$factorizations" ]
# linear iterations (column 9) summed over the steps
iterations() { awk -F, 'NR > 1 {s += $9} END {print s}' "$1/statistics.csv"; }
newton() { awk -F, 'NR > 1 {s += $8} END {print s}' "$1/statistics.csv"; }
echo "Newton / linear iterations: fixed tolerance $(newton reuse) /" \
  "$(iterations reuse), adaptive $(newton adaptive) / $(iterations adaptive)"
# step .. relative density: forces and density to 1e-6 relative
for run in reuse reuse2 adaptive; do
  cut -d, -f1-7 direct/statistics.csv > a.csv
  cut -d, -f1-7 "$run/statistics.csv" > b.csv
  "$NUMDIFF" -r 1e-6 -a 1e-8 -s ', \n' a.csv b.csv
done
tail -n 1 a.csv

# MUMPS is given the tangent without the zero entries that the contact
# pattern reserves for candidate facets: in the first step, where the
# spheres touch at points, no front of the factorization spans more than
# one particle's DoFs (with the zeros, fronts of 483 against 276 DoFs per
# particle; doc/performance.md). Both ways of running MUMPS on 2 ranks, and
# 1 rank.
for run in "1 true" "2 true" "2 false"; do
  set -- $run
  read -r particles dofs < <(sed -n 's/^Densify: \([0-9]*\) particle(s), [0-9]* tetrahedra, \([0-9]*\) DoFs.*/\1 \2/p' "fronts$1$2.log")
  front=$(sed -n 's/.*largest front \([0-9]*\).*/\1/p' "fronts$1$2.log" | sort -n | tail -n 1)
  echo "$1 rank(s), Reproducible=$2: largest front $front, $((dofs / particles)) DoFs per particle"
  [ -n "$front" ] && [ "$front" -le $((dofs / particles)) ]
  # the verbose count of yielding material points (one per cell corner with
  # the nodal-averaged F-bar), summed over the ranks: the converged step's
  # count is the same on 1 and 2 ranks and at most the number of corners
  read -r tets < <(sed -n 's/^Densify: [0-9]* particle(s), \([0-9]*\) tetrahedra.*/\1/p' "fronts$1$2.log")
  yielding=$(sed -n 's/.*yielding points \([0-9]*\) (changed.*/\1/p' "fronts$1$2.log" | tail -n 1)
  echo "$1 rank(s), Reproducible=$2: $yielding of $((4 * tets)) corner points yield in step 1"
  [ -n "$yielding" ] && [ "$yielding" -le $((4 * tets)) ]
  [ -z "${first_yielding:-}" ] && first_yielding=$yielding
  [ "$yielding" -eq "$first_yielding" ]
done
