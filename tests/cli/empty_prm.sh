# An empty parameter file, one of blanks only, or a directory given as the
# parameter file is refused (exit code 2, one line), and nothing is written:
# not the built-in default scene into ./output. The 2-rank run stops at the
# input check, so the test holds one processor.
# ctest processors: 1
set -u
cd "$WORK_DIR"
rm -rf output
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
: > empty.prm
printf '\n  \n\t\n' > blank.prm
mkdir -p adir
expect_error "empty file" 2 "'empty.prm' is empty" "$DENSIFY" empty.prm
expect_error "blank file" 2 "'blank.prm' is empty" "$DENSIFY" blank.prm
expect_error "empty file, --validate" 2 "'empty.prm' is empty" "$DENSIFY" --validate empty.prm
expect_error "directory" 2 "'adir' is a directory" "$DENSIFY" adir
expect_error "directory under mpirun -np 2" 2 "'adir' is a directory" \
  "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" adir
[ ! -e output ] || { echo "FAIL: ./output was written"; fails=$((fails + 1)); }
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
