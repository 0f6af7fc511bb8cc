# Checkpoints belong to their run, and --resume neither loses nor duplicates
# rows:
#  1. run A stops after step 3 with a checkpoint; run B starts afresh in the
#     same directory and is killed (SIGKILL) before it writes a checkpoint;
#     --resume must not continue from A's checkpoint (exit 2, no checkpoint);
#  2. a run killed after its checkpoint of step 3 and a few more steps is
#     resumed: statistics.csv and particles.csv hold every step once, and
#     solution.pvd every graphics step once, also when the resumed run
#     writes no graphics;
#  3. --resume on 2 ranks from a 1-rank checkpoint names the rank counts.
# (its one 2-rank run stops at the checkpoint check: one processor's work)
# ctest processors: 1
set -u
cd "$WORK_DIR"
rm -rf out a.log b.log c.log d.log
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
prm="$SOURCE_DIR/prm/default.prm"
scene=(--set "Output/Directory=out" --set "Mesh/Element size=0.6"
  --set "Mesh/Refinement directions=" --set "Time stepping/Number of steps=10")

# wait until the run writing the log $2 has printed step $1 (or ended)
wait_step() {
  for _ in $(seq 1200); do
    grep -q "^step $1/" "$2" && return
    grep -q "^Finished" "$2" && return
    sleep 0.05
  done
}

# 1. the stale checkpoint
"$DENSIFY" "$prm" "${scene[@]}" --stop-after 3 > a.log
rc=$?
[ $rc -eq 3 ] || { echo "FAIL: run A exit $rc"; fails=$((fails + 1)); }
grep -q "load step 3 of 10" out/checkpoint/info.txt ||
  { echo "FAIL: no checkpoint of run A"; fails=$((fails + 1)); }
"$DENSIFY" "$prm" "${scene[@]}" --set "Output/Checkpoint interval=0" > b.log &
pid=$!
wait_step 2 b.log
kill -KILL $pid 2>/dev/null
wait $pid 2>/dev/null
echo "run B killed after $(($(wc -l < out/statistics.csv) - 1)) step(s)"
expect_error "--resume after a fresh run" 2 "no checkpoint" \
  "$DENSIFY" "$prm" "${scene[@]}" --resume

# 2. killed after a checkpoint, resumed without graphics
rm -rf out a.log b.log c.log d.log
"$DENSIFY" "$prm" "${scene[@]}" --set "Output/Checkpoint interval=3" > c.log &
pid=$!
wait_step 5 c.log
kill -KILL $pid 2>/dev/null
wait $pid 2>/dev/null
echo "run C killed after $(($(wc -l < out/statistics.csv) - 1)) step(s)"
"$DENSIFY" "$prm" "${scene[@]}" --set "Output/Interval=0" --resume > d.log ||
  { echo "FAIL: --resume"; cat d.log; fails=$((fails + 1)); }
grep "Resumed" d.log
/usr/bin/python3 - out <<'PY' || fails=$((fails + 1))
import csv, os, re, sys
d = sys.argv[1]
steps = [int(r["step"]) for r in csv.DictReader(open(d + "/statistics.csv"))]
assert steps == list(range(1, 11)), ("statistics.csv", steps)
rows = [(int(r["step"]), int(r["particle"]))
        for r in csv.DictReader(open(d + "/particles.csv"))]
assert rows == [(s, p) for s in range(1, 11) for p in range(3)], \
    ("particles.csv", rows)
# the graphics the resumed run kept: those up to its checkpoint, once each
pvd = open(d + "/solution.pvd").read()
files = re.findall(r'file="([^"]+)"', pvd)
resumed = int(re.search(r"after step (\d+)", open("d.log").read()).group(1))
assert files == ["solution_%05d.pvtu" % s for s in range(1, resumed + 1)], files
for f in files:
    assert os.path.exists(os.path.join(d, f)), f
print("rows and graphics records: each step once")
PY

# 3. a checkpoint of one rank, resumed on two: the rank count is named
rm -rf out
"$DENSIFY" "$prm" "${scene[@]}" --stop-after 1 > e.log
expect_error "--resume on 2 ranks from 1" 2 "written by 1 MPI rank(s), this run has 2; resume with mpirun -np 1" \
  "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$prm" "${scene[@]}" --resume
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
