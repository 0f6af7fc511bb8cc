# Explicit dynamics (Solver/Method = explicit) at its stability limit: an
# elastic sphere pressed between punches with physical densities (Explicit/
# Mass scaling = none), so that the stable step the code computes sets the
# time step (the cells' bound, calibrated by a power iteration on the mesh).
# At 0.9 of it the run is stable and its energy balances; at 1.5 of it the
# integration must go unstable, and the run must stop cleanly: exit code 1,
# one error line naming Explicit/Time step safety, and no NaN in
# statistics.csv. On 2 ranks the error line names the cause (the failing
# rank's own text, such as an inverted element), not "another rank". The
# 1-rank and 2-rank runs are parts of their own (tests/cli/lib/parts.bash).
# ctest parts: one_rank two_ranks:2
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
run() {
  ${LAUNCH:-} "$DENSIFY" "$SOURCE_DIR/prm/hertz.prm" --set "Output/Directory=$1" \
    --set "Output/Interval=0" --set "Mesh/Polynomial degree=1" \
    --set "Mesh/Element size=0.5" --set "Mesh/Refinement directions=" \
    --set "Material/Finite strain=true" \
    --set "Tools/Upper punch/Displacement history=0:0, 1:0.01" \
    --set "Time stepping/Number of steps=4" \
    --set "Solver/Method=explicit" --set "Explicit/Mass scaling=none" \
    --set "Explicit/Loading time=2e-4" --set "Explicit/Damping ratio=0.05" \
    --set "Explicit/Time step safety=$2"
}
if part one_rank; then
out=$(run stable 0.9 2>&1)
rc=$?
echo "safety 0.9: exit $rc"
[ $rc -eq 0 ] || { echo "$out"; exit 1; }
/usr/bin/python3 - stable/statistics.csv <<'PY' || exit 1
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
# no NaN but the density and the die's stresses (NaN without a die)
die = ("relative_density", "upper_punch_stress", "lower_punch_stress",
       "die_wall_pressure", "radial_axial_ratio")
assert all(math.isfinite(float(v)) for r in rows for k, v in r.items()
           if k not in die)
last = rows[-1]
work = float(last["external_work"])
balance = float(last["energy_balance"])
print("safety 0.9: external work %.4g mJ, balance %.2g mJ (%.2g %%), %s steps"
      % (work, balance, 100 * balance / work, last["explicit_steps"]))
assert work > 0 and abs(balance) < 0.01 * work
PY
# the error line (the scene's unused entries give warning lines before it)
err=$(run unstable 1.5 2>&1 >/dev/null)
rc=$?
err=$(printf '%s\n' "$err" | grep -v "^densify: warning:")
echo "safety 1.5: exit $rc: $err"
[ $rc -eq 1 ] || exit 1
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || exit 1
printf '%s' "$err" | grep -q "unstable" || exit 1
printf '%s' "$err" | grep -q "Explicit/Time step safety" || exit 1
/usr/bin/python3 - unstable/statistics.csv <<'PY' || exit 1
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
die = ("relative_density", "upper_punch_stress", "lower_punch_stress",
       "die_wall_pressure", "radial_axial_ratio")
assert all(math.isfinite(float(v)) for r in rows for k, v in r.items()
           if k not in die)
PY
fi
# the same on 2 ranks: densify's one error line names the cause
if part two_ranks; then
err=$(LAUNCH="$MPIEXEC --oversubscribe -np 2" run unstable2 1.5 2>&1 >/dev/null)
line=$(printf '%s\n' "$err" | grep "^densify: error:")
echo "2 ranks, safety 1.5: $line"
[ "$(printf '%s\n' "$line" | grep -c .)" -eq 1 ] || { echo "$err"; exit 1; }
printf '%s' "$line" | grep -q "Explicit/Time step safety" || exit 1
printf '%s' "$line" | grep -q "another rank" && exit 1
printf '%s' "$line" | grep -Eq "det F|unstable at|not positive definite" || exit 1
fi
part check || exit 0
echo "stable at 0.9, stopped cleanly at 1.5 (1 and 2 ranks): yes"
