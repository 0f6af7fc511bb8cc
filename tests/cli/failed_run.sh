# A run that cannot converge (cut-backs exhausted) stops with one clear error
# line and exit code 1; statistics.csv and the log written so far stay valid.
set -u
cd "$WORK_DIR"
out=$("$DENSIFY" "$SOURCE_DIR/prm/hertz.prm" --set "Output/Directory=out" \
  --set "Mesh/Polynomial degree=1" --set "Mesh/Element size=0.4" \
  --set "Mesh/Refined element size=0.1" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.1" \
  --set "Time stepping/Number of steps=2" \
  --set "Time stepping/Maximum cut-backs=0" \
  --set "Solver/Maximum Newton iterations=3" 2>&1 >/dev/null)
rc=$?
echo "exit $rc: $out"
[ $rc -eq 1 ] || exit 1
[ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || exit 1
printf '%s' "$out" | grep -q "Newton did not converge" || exit 1
# the header is there, and nothing half-written
head -n 1 out/statistics.csv | grep -q '^step,time,punch_displacement'
[ "$(wc -l < out/statistics.csv)" -le 2 ] || exit 1
grep -q "Densify:" out/log.txt
# the reason is in the log too
grep -q "densify: error: step 1: Newton did not converge" out/log.txt
