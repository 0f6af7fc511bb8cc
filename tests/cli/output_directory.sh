# Output/Directory: empty is refused (it would write into /), by a run and
# by --validate; one that cannot be written is refused with exit code 2 on
# one and on two ranks, promptly (no rank waits for another).
# (its 2-rank runs stop at the output directory check: one processor's
# work)
# ctest processors: 1
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
prm="$SOURCE_DIR/prm/default.prm"
expect_error "empty" 2 "Output/Directory is empty" "$DENSIFY" "$prm" --set "Output/Directory="
expect_error "blanks" 2 "Output/Directory is empty" "$DENSIFY" "$prm" --set "Output/Directory=  "
expect_error "empty, --validate" 2 "Output/Directory is empty" \
  "$DENSIFY" --validate "$prm" --set "Output/Directory="
expect_error "empty, 2 ranks" 2 "Output/Directory is empty" \
  "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$prm" --set "Output/Directory="
expect_error "not writable" 2 "cannot write '/proc/xyz/log.txt'" \
  "$DENSIFY" "$prm" --set "Output/Directory=/proc/xyz"
start=$(date +%s)
expect_error "not writable, 2 ranks" 2 "cannot write '/proc/xyz/log.txt'" \
  "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$prm" --set "Output/Directory=/proc/xyz"
took=$(($(date +%s) - start))
echo "2 ranks stopped after ${took}s"
[ "$took" -lt 30 ] || { echo "FAIL: took ${took}s"; fails=$((fails + 1)); }
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
