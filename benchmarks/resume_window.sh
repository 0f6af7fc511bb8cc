#!/bin/bash
# Two builds side by side on a window of a long run: each resumes the
# checkpoint in RUN_DIR (written by SCENE on RANKS ranks) for STATIONS
# stations, RUNS times, alternated (old, new, old, new, ...). Prints per run
# the wall time and the timer rows "Explicit: internal forces", "Explicit:
# contact and loads" and "Contact: search"; then the medians per build, their
# ratios new / old, and the last station line of each build (the same line
# when the builds compute the same thing).
# Usage (from the source root):
#   bash benchmarks/resume_window.sh OLD NEW RUN_DIR SCENE [STATIONS] [RANKS] [RUNS] [OPTIONS...]
# defaults: 8 stations, 2 ranks, 1 run; OPTIONS (e.g. --set ...) are those
# the run was started with. Run it alone on the machine.
# doc/performance.md, "Comparing two builds".
set -eu
[ $# -ge 4 ] || {
  echo "usage: resume_window.sh OLD NEW RUN_DIR SCENE [STATIONS] [RANKS] [RUNS]"
  exit 2
}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
old=$1 new=$2 run=$3 scene=$4 stations=${5:-8} ranks=${6:-2} runs=${7:-1}
shift $(($# < 7 ? $# : 7))
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "resume_window.sh: $b is not an executable"; exit 2; }
done
info="$run/checkpoint/info.txt"
[ -f "$info" ] || { echo "resume_window.sh: no checkpoint in $run ($info)"; exit 2; }
first=$(awk '/load step/{print $3}' "$info")
last=$((first + stations))
launch=()
[ "$ranks" -gt 1 ] && launch=(mpirun -np "$ranks")
out=$(mktemp -d)
for r in $(seq 1 "$runs"); do
  for v in old new; do
    b=$old; [ $v = new ] && b=$new
    d=$out/$v.$r; mkdir -p "$d"
    cp -r "$run/checkpoint" "$run/statistics.csv" "$run/particles.csv" "$d/"
    start=$(date +%s%N)
    "${launch[@]}" "$b" "$scene" --set "Output/Directory=$d" --set Output/Interval=0 \
      --set "Output/Checkpoint interval=0" "$@" --resume --stop-after "$last" > "$d.log" 2>&1 ||
      [ $? -eq 3 ] || { echo "resume_window.sh: $b failed ($d.log)"; exit 1; }
    awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN {printf "%.2f\n", (b - a) / 1e9}' > "$d.wall"
    printf '%s run %s: %s s wall;' "$v" "$r" "$(cat "$d.wall")"
    awk -F'|' '/Explicit: internal forces|Explicit: contact and loads|Contact: search/ {
      gsub(/^ +| +$/, "", $2); gsub(/^ +| +$/, "", $4); printf " %s %s;", $2, $4 }' "$d.log"
    echo
  done
done
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
row() { awk -F'|' -v k="$1" '$0 ~ k { gsub(/s/, "", $4); print $4 + 0 }' "$2"; }
for key in wall "Explicit: internal forces" "Explicit: contact and loads"; do
  for v in old new; do
    for r in $(seq 1 "$runs"); do
      if [ "$key" = wall ]; then cat "$out/$v.$r.wall"; else row "$key" "$out/$v.$r.log"; fi
    done | median > "$out/$v.median"
  done
  awk -v k="$key" -v o="$(cat "$out/old.median")" -v n="$(cat "$out/new.median")" \
    'BEGIN { printf "%-28s old %8.1f s  new %8.1f s  ratio %.3f\n", k, o, n, n / o }'
done
for v in old new; do
  echo "last station, $v: $(grep -E '^step' "$out/$v.1.log" | tail -n 1 | cut -c1-160)"
done
echo "logs in $out"
