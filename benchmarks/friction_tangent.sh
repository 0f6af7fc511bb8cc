#!/bin/bash
# The friction tangent (Contact/Friction tangent) side by side on one scene:
# `consistent` (the exact Coulomb tangent) and `secant-start` (auto's choice
# with friction), alternately in ROUNDS rounds on the same machine. Prints per
# run the Newton iterations, continuations, cut-backs and wall time, the wall
# time ratio secant-start / consistent of each round, and the upper punch
# force at the given strokes (interpolated between the stations).
# Usage (from the source root):
#   bash benchmarks/friction_tangent.sh SCENE.prm NP "STROKES" [ROUNDS] [--set ...]...
# e.g.
#   bash benchmarks/friction_tangent.sh prm/single_layer_sn_light.prm 1 "0.32 0.64 0.96 1.28" 2
# Extra --set options apply to both variants.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
scene=$1; np=$2; strokes=$3; shift 3
rounds=1
if [ $# -gt 0 ] && [[ $1 =~ ^[0-9]+$ ]]; then rounds=$1; shift; fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
densify=${DENSIFY:-$root/build/densify}
out=$(mktemp -d)
for round in $(seq 1 "$rounds"); do
  for tangent in consistent secant-start; do
    dir=$out/${tangent}_$round
    start=$(date +%s.%N)
    rc=0
    mpirun --oversubscribe -np "$np" "$densify" "$scene" \
      --set "Output/Directory=$dir" --set "Output/Interval=0" \
      --set "Output/Checkpoint interval=0" \
      --set "Contact/Friction tangent=$tangent" "$@" > "$dir.log" 2>&1 || rc=$?
    echo "$(date +%s.%N) - $start" | bc > "$dir.seconds"
    echo "$rc" > "$dir.rc"
  done
done
echo "== $(basename "$scene") on $np rank(s), $rounds round(s); options: $*"
/usr/bin/python3 - "$out" "$strokes" "$rounds" <<'PY'
import csv, sys
out, strokes, rounds = sys.argv[1], [float(s) for s in sys.argv[2].split()], int(sys.argv[3])
def at(rs, stroke, column):
    for a, b in zip(rs, rs[1:]):
        sa, sb = float(a["punch_displacement"]), float(b["punch_displacement"])
        if sa <= stroke <= sb:
            w = (stroke - sa) / (sb - sa)
            return (1 - w) * float(a[column]) + w * float(b[column])
    return float("nan")
last = {}
for r in range(1, rounds + 1):
    t = {}
    for tangent in ("consistent", "secant-start"):
        name = f"{out}/{tangent}_{r}"
        rows = list(csv.DictReader(open(f"{name}/statistics.csv")))
        rc = open(f"{name}.rc").read().strip()
        t[tangent] = float(open(f"{name}.seconds").read())
        newton = [int(x["newton_iterations"]) for x in rows]
        print(f"round {r} {tangent:12s}: {len(rows)} steps"
              f"{'' if rc == '0' else ' (FAILED, exit ' + rc + ')'}, "
              f"Newton iterations {sum(newton)} (largest {max(newton)}), "
              f"continuations {sum(int(x['continuations']) for x in rows)}, "
              f"cut-backs {sum(int(x['cutbacks']) for x in rows)}, "
              f"wall {t[tangent]:.1f} s")
        last[tangent] = rows
    print(f"round {r}: wall time secant-start / consistent {t['secant-start'] / t['consistent']:.3f}")
print("stroke (mm) | F_upper consistent (N) | secant-start (N) | difference")
for s in strokes:
    a, b = at(last["consistent"], s, "upper_punch_force"), at(last["secant-start"], s, "upper_punch_force")
    print(f"{s:.3f} | {a:.1f} | {b:.1f} | {100 * (b / a - 1):+.3f} %")
PY
