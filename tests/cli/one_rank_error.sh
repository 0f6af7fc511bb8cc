# An error found on one MPI rank only, while the others go on into
# collective operations, ends every rank promptly with the message printed
# once (and the exit code of the error). mpirun's MPMD form gives the two
# ranks different parameter files: the bad one fails to read on its rank
# alone, the other rank starts the run.
# The rank that found the error sleeps while it waits for the others (up to
# 3 s) and the other rank waits in a collective: one processor's work.
# ctest processors: 1
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
rm -rf good_out
cat > good.prm <<'PRM'
subsection Particles
  set Centres = 0,0,1.25
end
subsection Mesh
  set Element size = 0.6
end
subsection Output
  set Directory = good_out
end
PRM
sed 's/set Centres/set Centers/' good.prm > bad.prm
for order in "bad good" "good bad"; do
  set -- $order
  start=$(date +%s)
  expect_error "error on rank of the $1 file first, $2 second" 2 "Centers" \
    "$MPIEXEC" --oversubscribe -np 1 "$DENSIFY" $1.prm : -np 1 "$DENSIFY" $2.prm
  took=$(($(date +%s) - start))
  echo "  stopped after ${took}s"
  [ "$took" -lt 40 ] || { echo "FAIL: took ${took}s"; fails=$((fails + 1)); }
done
# an error on every rank is printed once, without waiting
start=$(date +%s)
expect_error "error on both ranks" 2 "Centers" \
  "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" bad.prm
took=$(($(date +%s) - start))
[ "$took" -lt 8 ] || { echo "FAIL: took ${took}s"; fails=$((fails + 1)); }
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
