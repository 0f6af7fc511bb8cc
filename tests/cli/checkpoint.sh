# Checkpoint and restart. A resumed run reproduces the uninterrupted one:
#  1. two J2 tin spheres (finite strain, friction 0.2) touching each other
#     and the die: the periodic checkpoint after step 4 (plastic history,
#     tool and particle contact multipliers and friction history in use) is
#     resumed in a copy of the output; steps 5-6 equal the uninterrupted run;
#  2. SIGTERM stops a run after the current step with a checkpoint (exit 3),
#     --resume finishes it; statistics.csv, particles.csv and solution.pvd
#     equal the uninterrupted run's;
#  3. on 2 MPI ranks with --stop-after, resumed on 2 ranks: equal to the
#     uninterrupted 1-rank run to the Newton tolerance;
#  4. one-line errors (exit 2): resume on another number of ranks, with other
#     parameters, with a --stop-after step the checkpoint has passed, or
#     without a checkpoint;
#  5. a finished run pressed further: its last step's checkpoint (6 steps,
#     a checkpoint every 3) resumed with a longer End time, Number of steps
#     and punch history (the same load step) equals the run made to the
#     longer schedule at once; a finished run resumed as it was, a history
#     changed before the checkpoint or another load step are one-line
#     errors.
# Each group of runs is a part of its own (tests/cli/lib/parts.bash); the
# check compares the stopped runs with the uninterrupted one.
# ctest parts: free pair signal mpi:2 errors further
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
source "$SOURCE_DIR/tests/cli/lib/two_tin_spheres.bash"

# compare the columns $1 of two statistics.csv files. $all: all but the
# timing columns (wall_seconds, step_seconds) and linear_iterations: the
# resumed run builds the matrix pattern of the particle contacts from the
# current search, the uninterrupted one keeps a pattern made earlier while it
# still covers the contacts, and AMG's aggregation sees the stored zeros, so
# CG may take another number of iterations to the same tolerance
same_statistics() {
  local columns=$1 tolerance=$2 a=$3 b=$4
  cut -d, -f"$columns" "$a" > "$a.cmp"
  cut -d, -f"$columns" "$b" > "$b.cmp"
  "$NUMDIFF" -q -r "$tolerance" -a 1e-9 -s ', \n' "$a.cmp" "$b.cmp"
}
all=1-8,11-15,17-

if part free; then
  rm -rf free
  "$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=free" > free.log
fi

# 1. periodic checkpoint with particle contact, resumed in a copy
if part pair; then
rm -rf pair pair_resumed
"$DENSIFY" "$prm" "${pair[@]}" --set "Output/Directory=pair" \
  --set "Output/Checkpoint interval=4" > pair.log
grep -q "checkpoint written after step 4" pair.log
grep -q "load step 4 of 6" pair/checkpoint/info.txt
/usr/bin/python3 - pair/statistics.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
# the checkpoint holds contact between the particles and with the die
assert float(rows[3]["particle_contact_force"]) > 0, rows[3]
assert int(rows[3]["contact_pairs"]) == 1, rows[3]
assert float(rows[3]["die_wall_force"]) > 0, rows[3]
PY
cp -r pair pair_resumed
"$DENSIFY" "$prm" "${pair[@]}" --set "Output/Directory=pair_resumed" \
  --set "Output/Checkpoint interval=4" --resume > pair_resumed.log
grep -q "Resumed from the checkpoint after step 4" pair_resumed.log
[ "$(grep -c '^step ' pair_resumed.log)" -eq 2 ]
same_statistics $all 1e-9 pair/statistics.csv pair_resumed/statistics.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' pair/particles.csv pair_resumed/particles.csv
fi

# 2. SIGTERM, then --resume
if part signal; then
rm -rf free_signal
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=free_signal" > signal.log &
pid=$!
for _ in $(seq 600); do
  rows=$(cat free_signal/statistics.csv 2>/dev/null | wc -l)
  [ "$rows" -ge 2 ] && break
  sleep 0.1
done
kill -TERM $pid
set +e
wait $pid
rc=$?
set -e
echo "after SIGTERM: exit $rc"
[ $rc -eq 3 ]
grep -q "on a signal; checkpoint in free_signal/checkpoint/" signal.log
stopped=$(($(wc -l < free_signal/statistics.csv) - 1))
[ "$stopped" -ge 1 ] && [ "$stopped" -lt 6 ]
grep -q "load step $stopped of 6" free_signal/checkpoint/info.txt
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=free_signal" --resume > resume.log
[ "$(wc -l < free_signal/statistics.csv)" -eq 7 ]
# the .pvd lists each output step once, the .pvtu files it names exist
[ "$(grep -c 'DataSet' free_signal/solution.pvd)" -eq 3 ]
for f in $(grep -o 'solution_[0-9]*.pvtu' free_signal/solution.pvd); do
  [ -f "free_signal/$f" ]
done
fi

# 3. two ranks, --stop-after, resumed on two ranks
if part mpi; then
rm -rf free_mpi
set +e
"$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$prm" "${free[@]}" \
  --set "Output/Directory=free_mpi" --stop-after 3 > mpi_stop.log 2>&1
rc=$?
set -e
[ $rc -eq 3 ]
grep -q "Stopped after step 3/6 (--stop-after)" mpi_stop.log
grep -q "written by 2 MPI rank(s)" free_mpi/checkpoint/info.txt
# 4a. another number of ranks
set +e
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=free_mpi" --resume \
  > /dev/null 2> ranks.err
rc=$?
set -e
cat ranks.err
[ $rc -eq 2 ] && [ "$(wc -l < ranks.err)" -eq 1 ]
grep -q "written by 2 MPI rank(s), this run has 1; resume with mpirun -np 2" ranks.err
"$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$prm" "${free[@]}" \
  --set "Output/Directory=free_mpi" --resume > mpi_resume.log
grep -q "Resumed from the checkpoint after step 3" mpi_resume.log
fi

# 4b. other parameters
if part errors; then
rm -rf changed none
set +e
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=changed" --stop-after 2 > /dev/null
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=changed" --resume \
  --set "Contact/Friction coefficient=0.3" > /dev/null 2> changed.err
rc=$?
set -e
cat changed.err
[ $rc -eq 2 ] && [ "$(wc -l < changed.err)" -eq 1 ]
grep -q "other parameters (it has 'Contact/Friction coefficient = 0.2', this run 'Contact/Friction coefficient = 0.3')" changed.err
# a load step to stop after that the checkpoint has passed
set +e
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=changed" --resume \
  --stop-after 1 > /dev/null 2> passed.err
rc=$?
set -e
cat passed.err
[ $rc -eq 2 ] && [ "$(wc -l < passed.err)" -eq 1 ]
grep -q -- "--stop-after 1: the checkpoint is after step 2, so the run would never stop there" passed.err

# 4c. no checkpoint
set +e
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=none" --resume > /dev/null 2> none.err
rc=$?
set -e
cat none.err
[ $rc -eq 2 ] && [ "$(wc -l < none.err)" -eq 1 ]
grep -q "no checkpoint" none.err
fi

# 5. pressed further
if part further; then
rm -rf short long further
longer=(--set "Time stepping/End time=1.5" --set "Time stepping/Number of steps=9"
        --set "Tools/Upper punch/Displacement history=0:0, 1.5:0.18")
"$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=short" \
  --set "Output/Checkpoint interval=3" > short.log
grep -q "load step 6 of 6.*press further" short/checkpoint/info.txt
"$DENSIFY" "$prm" "${free[@]}" "${longer[@]}" --set "Output/Directory=long" > long.log
cp -r short further
"$DENSIFY" "$prm" "${free[@]}" "${longer[@]}" --set "Output/Directory=further" \
  --resume > further.log
grep -q "Resumed from the checkpoint after step 6" further.log
[ "$(grep -c '^step ' further.log)" -eq 3 ]
same_statistics $all 1e-9 long/statistics.csv further/statistics.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' long/particles.csv further/particles.csv
# the errors, each one line and exit 2
refused() { # expected text, options
  local expected=$1; shift
  set +e
  "$DENSIFY" "$prm" "${free[@]}" --set "Output/Directory=short" --resume "$@" \
    > /dev/null 2> refused.err
  local rc=$?
  set -e
  cat refused.err
  [ $rc -eq 2 ] && [ "$(wc -l < refused.err)" -eq 1 ]
  grep -q "$expected" refused.err
}
refused "the checkpoint is of the run's last step 6; to press further"
refused "Displacement history = 0:0, 1.5:0.2', which differs from '0:0, 1:0.12' before the checkpoint's time 1 s" \
  --set "Time stepping/End time=1.5" --set "Time stepping/Number of steps=9" \
  --set "Tools/Upper punch/Displacement history=0:0, 1.5:0.2"
refused "a load step End time / Number of steps of 0.15 s instead of 0.16666667 s" \
  --set "Time stepping/End time=1.5" --set "Time stepping/Number of steps=10" \
  --set "Tools/Upper punch/Displacement history=0:0, 1.5:0.18"
fi

# the stopped and resumed runs against the uninterrupted one
part check || exit 0
same_statistics $all 1e-9 free/statistics.csv free_signal/statistics.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' free/particles.csv free_signal/particles.csv
# forces, density and volume (iteration counts differ between 1 and 2 ranks)
same_statistics 1-7,15 1e-3 free/statistics.csv free_mpi/statistics.csv
echo "checkpoint tests passed"
