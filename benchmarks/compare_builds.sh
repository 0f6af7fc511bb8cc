#!/bin/bash
# Two builds of densify on the same machine, one after the other: the paper
# scene's steps 1-3 on 1 and 2 ranks (scene_speed.sh), three late steps on 2
# ranks from a copy of a checkpoint, and the light scene on 1 rank. Prints
# the step lines, wall times, peak memory and timer tables of each.
# Usage (from the source root):
#   bash benchmarks/compare_builds.sh OLD_EXECUTABLE NEW_EXECUTABLE [RUN_DIR]
# RUN_DIR: an output directory of prm/single_layer_sn.prm on 2 ranks whose
# checkpoint/ is the one after step 200 (the late window is skipped without
# it). doc/performance.md, "Comparing two builds".
set -eu
[ $# -ge 2 ] || { echo "usage: compare_builds.sh OLD NEW [RUN_DIR]"; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
old=$1 new=$2 run=${3:-}
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "compare_builds.sh: $b is not an executable"; exit 2; }
done
out=$(mktemp -d)
for v in old new; do
  b=$old; [ $v = new ] && b=$new
  echo "=== $v ($b): paper scene, steps 1-3"
  DENSIFY=$b bash benchmarks/scene_speed.sh prm/single_layer_sn.prm --set Solver/Method=implicit --stop-after 3
done
if [ -n "$run" ]; then
  for v in old new; do
    b=$old; [ $v = new ] && b=$new
    d=$out/late_$v; mkdir -p "$d"; cp -r "$run/checkpoint" "$run/statistics.csv" "$run/particles.csv" "$d/"
    last=$(awk '/load step/{print $3}' "$d/checkpoint/info.txt")
    echo "=== $v: paper scene, steps $((last + 1))-$((last + 3)), 2 ranks"
    /usr/bin/time -f "%e s wall, %M kB peak (largest process)" mpirun -np 2 "$b" prm/single_layer_sn.prm --set Solver/Method=implicit \
      --set "Output/Directory=$d" --set Output/Interval=0 --resume --stop-after $((last + 3)) \
      > "$d.log" 2> "$d.time" || [ $? -eq 3 ]
    grep -E '^step' "$d.log" | tail -n 3; tail -n 1 "$d.time"
    grep -E '^\| [A-Z][a-z]+:' "$d.log"
  done
fi
for v in old new; do
  b=$old; [ $v = new ] && b=$new
  d=$out/light_$v
  echo "=== $v: light scene, 1 rank"
  /usr/bin/time -f "%e s wall, %M kB peak" "$b" prm/single_layer_sn_light.prm \
    --set "Output/Directory=$d" --set Output/Interval=0 > "$d.log" 2> "$d.time"
  grep -E '^Finished' "$d.log"; tail -n 1 "$d.time"
  grep -E '^\| [A-Z][a-z]+:' "$d.log"
done
