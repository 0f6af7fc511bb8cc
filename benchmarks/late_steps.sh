#!/bin/bash
# Solver levers on later steps of the paper's scene at full fidelity: resumes
# a checkpoint of prm/single_layer_sn.prm and runs a few steps once per
# variant (SET tolerances: fixed or adaptive linear tolerance, Newton
# tolerance; SET line-search: Solver/Line search residual or energy; SET
# geometric-tangent: Contact/Geometric tangent false or true), printing
# wall time, factorizations, GMRES solves with old factors, Newton iterations
# per step and the final forces, so that time and accuracy can be compared.
# Usage (from the source root):
#   bash benchmarks/late_steps.sh RUN_DIR [N_STEPS [SET [RANKS]]]
# RUN_DIR: the Output/Directory of a run of prm/single_layer_sn.prm with a
# checkpoint (Output/Checkpoint interval); N_STEPS after it (default 4); SET
# tolerances (default), line-search or geometric-tangent; RANKS: MPI ranks
# (default 1; the checkpoint's number of ranks).
# Needs build/densify; run it alone on the machine.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
run=${1:?usage: bash benchmarks/late_steps.sh RUN_DIR [N_STEPS [SET]]}
n=${2:-4}
set_name=${3:-tolerances}
ranks=${4:-1}
launch=()
if [ "$ranks" -gt 1 ]; then
  launch=(mpirun -np "$ranks")
fi
info="$run/checkpoint/info.txt"
[ -f "$info" ] || { echo "no checkpoint in $run (expected $info)"; exit 2; }
first=$(awk '{print $3}' "$info")
last=$((first + n))
out=$(mktemp -d)
variant() {
  local name=$1
  shift
  local dir="$out/$name"
  mkdir -p "$dir"
  cp -r "$run/checkpoint" "$run/statistics.csv" "$dir/"
  local rc=0
  /usr/bin/time -f "%e %M" -o "$dir.time" "${launch[@]}" "$root/build/densify" \
    "$root/prm/single_layer_sn.prm" --set Solver/Method=implicit --set "Output/Directory=$dir" \
    --set "Output/Checkpoint interval=0" --set "Output/Interval=0" \
    --resume --stop-after "$last" "$@" > "$dir.log" 2>&1 || rc=$?
  if [ $rc -ne 0 ] && [ $rc -ne 3 ]; then
    echo "$name: densify failed (exit $rc):"; tail -n 3 "$dir.log"; return
  fi
  read -r wall kb < <(tail -n 1 "$dir.time")
  local direct reused
  direct=$(grep "Solve: direct" "$dir.log" | awk -F'|' '{print $3+0}')
  reused=$(grep "Solve: GMRES with old factors" "$dir.log" | awk -F'|' '{print $3+0}')
  local newton forces
  newton=$(awk -F, -v f="$first" 'NR > 1 && $1 > f {printf "%s ", $8}' "$dir/statistics.csv")
  forces=$(awk -F, 'END {printf "F_upper %.2f N, F_lower %.2f N, die wall (axial) %.3f N", $4, $5, $6}' "$dir/statistics.csv")
  echo "$name: ${wall} s, $((kb / 1024)) MB, ${direct:-0} factorizations," \
    "${reused:-0} solves with old factors, Newton per step: ${newton}; ${forces}"
}
echo "steps $((first + 1))..$last of prm/single_layer_sn.prm, resumed from $run"
case $set_name in
  tolerances)
    variant "adaptive-linear-tolerance" --set "Solver/Adaptive linear tolerance=true"
    variant "fixed-linear-tolerance" --set "Solver/Adaptive linear tolerance=false"
    variant "newton-tolerance-1e-8" --set "Solver/Adaptive linear tolerance=true" \
      --set "Solver/Newton tolerance=1e-8"
    variant "newton-tolerance-1e-7" --set "Solver/Adaptive linear tolerance=true" \
      --set "Solver/Newton tolerance=1e-7"
    ;;
  line-search)
    variant "line-search-residual" --set "Solver/Line search=residual"
    variant "line-search-energy" --set "Solver/Line search=energy"
    ;;
  geometric-tangent)
    variant "geometric-tangent-false" --set "Contact/Geometric tangent=false"
    variant "geometric-tangent-true" --set "Contact/Geometric tangent=true"
    ;;
  *)
    echo "unknown SET $set_name (tolerances, line-search or geometric-tangent)"
    exit 2
    ;;
esac
rm -rf "$out"
