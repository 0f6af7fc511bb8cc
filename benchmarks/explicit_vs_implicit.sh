#!/bin/bash
# The explicit and the implicit method on the same scene, one after the
# other on the same machine: wall time of each and their ratio, the upper
# punch force at given strokes (interpolated between the stations) and its
# difference, the final relative density, the explicit run's steps, time per
# step, largest KE/IE and added mass, and the timer tables' largest sections.
# Usage (from the source root):
#   bash benchmarks/explicit_vs_implicit.sh SCENE.prm NP "STROKES" [--set ...]...
# e.g.
#   bash benchmarks/explicit_vs_implicit.sh prm/single_layer_sn_light.prm 1 "0.32 0.64 0.96 1.28"
# Extra --set options apply to the explicit run only (e.g. its
# "Explicit/Number of steps=N"). IMPLICIT_DIR=DIR reuses the statistics of an
# earlier implicit run instead of running it again.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
scene=$1; np=$2; strokes=$3; shift 3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
densify=${DENSIFY:-$root/build/densify}
out=$(mktemp -d)
run() { # name, extra options
  local name=$1; shift
  local start=$(date +%s.%N)
  mpirun --oversubscribe -np "$np" "$densify" "$scene" \
    --set "Output/Directory=$out/$name" --set "Output/Interval=0" \
    --set "Output/Checkpoint interval=0" "$@" > "$out/$name.log" 2>&1
  echo "$(date +%s.%N) - $start" | bc > "$out/$name.seconds"
}
if [ -n "${IMPLICIT_DIR:-}" ]; then
  mkdir -p "$out/implicit" && cp "$IMPLICIT_DIR/statistics.csv" "$out/implicit/"
  cp "$IMPLICIT_DIR/log.txt" "$out/implicit/"
  awk -F, 'END {print $10}' "$IMPLICIT_DIR/statistics.csv" > "$out/implicit.seconds"
else
  run implicit
fi
run explicit --set "Solver/Method=explicit" "$@"
echo "== $(basename "$scene") on $np rank(s); explicit: $*"
/usr/bin/python3 - "$out" "$strokes" <<'PY'
import csv, sys
out, strokes = sys.argv[1], [float(s) for s in sys.argv[2].split()]
def rows(name):
    return list(csv.DictReader(open(f"{out}/{name}/statistics.csv")))
def at(rs, stroke, column):
    for a, b in zip(rs, rs[1:]):
        sa, sb = float(a["punch_displacement"]), float(b["punch_displacement"])
        if sa <= stroke <= sb:
            w = (stroke - sa) / (sb - sa)
            return (1 - w) * float(a[column]) + w * float(b[column])
    return float("nan")
im, ex = rows("implicit"), rows("explicit")
t_im = float(open(f"{out}/implicit.seconds").read())
t_ex = float(open(f"{out}/explicit.seconds").read())
print(f"wall time: implicit {t_im:.1f} s, explicit {t_ex:.1f} s, "
      f"explicit / implicit {t_ex / t_im:.3f}")
steps = int(ex[-1]["explicit_steps"])
print(f"explicit: {steps} steps, {t_ex / steps * 1e3:.2f} ms per step (wall, "
      f"set-up included), added mass {100 * float(ex[-1]['added_mass']):.3g} %, "
      f"largest KE/IE after the first 10 % of the stations "
      f"{100 * max(float(r['kinetic_energy']) / float(r['internal_work']) for r in ex[len(ex) // 10:]):.3g} %, "
      f"energy balance at the end {100 * float(ex[-1]['energy_balance']) / float(ex[-1]['external_work']):.3g} % of the external work")
print("stroke (mm) | F_upper implicit (N) | explicit (N) | difference")
for s in strokes:
    a, b = at(im, s, "upper_punch_force"), at(ex, s, "upper_punch_force")
    print(f"{s:.3f} | {a:.1f} | {b:.1f} | {100 * (b / a - 1):+.2f} %")
print(f"final relative density: implicit {100 * float(im[-1]['relative_density']):.3f} %, "
      f"explicit {100 * float(ex[-1]['relative_density']):.3f} %")
PY
for name in implicit explicit; do
  echo "-- timer table of the $name run (largest sections)"
  grep -E "^\| [A-Z]" "$out/$name/log.txt" | grep -v "Section" | sort -t'|' -k4 -r | head -n 5
done
echo "(runs in $out)"
