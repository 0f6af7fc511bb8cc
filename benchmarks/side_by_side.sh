#!/bin/bash
# Two commands timed in turn on the same machine (A B A B ...): the whole
# process from start to exit, start-up included. Prints per command the
# median, smallest and largest wall time and the largest peak memory
# (/usr/bin/time), and the median, smallest and largest of the pairwise
# ratios A/B: pairing keeps the ratio meaningful when the machine's speed
# drifts during the call. Each command is one shell string (bash -c); its
# output goes to OUT/a.N.log and OUT/b.N.log, OUT printed at the end.
# Usage (from the source root):
#   bash benchmarks/side_by_side.sh RUNS 'COMMAND_A' 'COMMAND_B'
# e.g.
#   bash benchmarks/side_by_side.sh 3 \
#     'build/densify prm/single_layer_sn_light.prm --set Output/Interval=0' \
#     'OLD/densify prm/single_layer_sn_light.prm --set Output/Interval=0'
# Give each command its own Output/Directory when both write results.
set -eu
[ $# -eq 3 ] || {
  echo "usage: side_by_side.sh RUNS 'COMMAND_A' 'COMMAND_B'"
  exit 2
}
runs=$1 a=$2 b=$3
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || {
  echo "side_by_side.sh: RUNS must be a positive integer (got '$runs')"
  exit 2
}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mktemp -d)
for r in $(seq 1 "$runs"); do
  for v in a b; do
    cmd=$a
    [ $v = b ] && cmd=$b
    start=$(date +%s.%N)
    /usr/bin/time -f "%M" -o "$out/$v.$r.kb" bash -c "$cmd" > "$out/$v.$r.log" 2>&1 ||
      echo "side_by_side.sh: command $v exited with $? in run $r ($out/$v.$r.log)"
    echo "$start $(date +%s.%N)" > "$out/$v.$r.wall"
  done
done
/usr/bin/python3 - "$out" "$runs" <<'PY'
import statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
def read(v, kind):
    return [[float(x) for x in open(f"{out}/{v}.{r}.{kind}").read().split()]
            for r in range(1, runs + 1)]
# wall: start and end stamps; kb: the peak resident set (last number)
wall = {v: [end - start for start, end in read(v, "wall")] for v in "ab"}
for v in "ab":
    w = wall[v]
    print(f"{v.upper()}: wall median {statistics.median(w):.2f} s "
          f"(min {min(w):.2f}, max {max(w):.2f}), "
          f"peak memory {max(k[-1] for k in read(v, 'kb')) / 1024:.0f} MiB")
ratios = [x / y for x, y in zip(wall["a"], wall["b"])]
print(f"A/B: median {statistics.median(ratios):.3f} "
      f"(min {min(ratios):.3f}, max {max(ratios):.3f}) over {runs} pairs")
PY
echo "logs in $out"
