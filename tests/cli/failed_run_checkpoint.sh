# A run that fails (Newton, cut-backs exhausted) after converged steps
# writes a checkpoint of its last converged state and names it in its one
# error line (exit 1); --resume continues from it with other Solver and
# Time stepping/Maximum cut-backs settings and finishes, each step's row once.
set -u
cd "$WORK_DIR"
rm -rf out
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
scene=("$SOURCE_DIR/prm/hertz.prm" --set "Output/Directory=out"
  --set "Mesh/Polynomial degree=1" --set "Mesh/Element size=0.4"
  --set "Mesh/Refined element size=0.1"
  --set "Tools/Upper punch/Displacement history=0:0, 0.5:0.002, 1:0.1"
  --set "Time stepping/Number of steps=2")
expect_error "failed step 2" 1 "the last converged state (time 0.5 s) is in out/checkpoint/" \
  "$DENSIFY" "${scene[@]}" --set "Time stepping/Maximum cut-backs=0" \
  --set "Solver/Maximum Newton iterations=3"
grep -q "load step 1 of 2" out/checkpoint/info.txt ||
  { echo "FAIL: no checkpoint of step 1"; fails=$((fails + 1)); }
if "$DENSIFY" "${scene[@]}" --resume > resume.log 2>&1; then
  grep "Resumed from the checkpoint after step 1" resume.log ||
    { echo "FAIL: not resumed"; fails=$((fails + 1)); }
  steps=$(cut -d, -f1 out/statistics.csv | tr '\n' ' ')
  echo "statistics.csv steps: $steps"
  [ "$steps" = "step 1 2 " ] || { echo "FAIL: rows"; fails=$((fails + 1)); }
else
  echo "FAIL: --resume with the default solver settings:"
  tail -3 resume.log
  fails=$((fails + 1))
fi
# a run that fails in its first step has nothing to keep
rm -rf out
expect_error "failed step 1" 1 "Newton did not converge" \
  "$DENSIFY" "${scene[@]}" --set "Tools/Upper punch/Displacement history=0:0, 1:0.1" \
  --set "Time stepping/Maximum cut-backs=0" --set "Solver/Maximum Newton iterations=3"
[ ! -e out/checkpoint ] || { echo "FAIL: checkpoint of nothing"; fails=$((fails + 1)); }
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
