#!/bin/bash
# The explicit method's force kernels of two builds side by side: the light
# layer (prm/single_layer_sn_light.prm, 2,492 tetrahedra) by explicit
# dynamics to station STATIONS, each build RUNS times, alternated (old, new,
# old, new, ...), on RANKS ranks. Prints per build the median of the timer
# rows "Explicit: internal forces", "Explicit: contact and loads",
# "Contact: search" and "Explicit: mass" + "Explicit: largest frequency" in
# microseconds per tetrahedron per core per explicit step, the median wall
# time, and their ratios new / old; and the two builds' last station lines.
# The same build twice with RANKS 1 and 2 in two calls gives the strong
# scaling (the ratio of the per-core figures is 1 for perfect scaling).
# Usage (from the source root):
#   bash benchmarks/explicit_kernel.sh OLD_EXECUTABLE NEW_EXECUTABLE [RUNS] [STATIONS] [RANKS]
# defaults: 3 runs, 40 stations, 1 rank; SCENE=prm/... another scene (its
# own Explicit/Number of steps); SET="ENTRY=VALUE;ENTRY=VALUE" more
# parameter overrides for both builds, e.g. SET="Explicit/Number of
# steps=10000;Explicit/Ramp fraction=0.2". doc/performance.md, "The explicit
# force kernels".
set -eu
[ $# -ge 2 ] || {
  echo "usage: explicit_kernel.sh OLD NEW [RUNS] [STATIONS] [RANKS]"
  exit 2
}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
old=$1 new=$2 runs=${3:-3} stations=${4:-40} ranks=${5:-1}
scene=${SCENE:-prm/single_layer_sn_light.prm}
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "explicit_kernel.sh: $b is not an executable"; exit 2; }
done
out=$(mktemp -d)
overrides=()
if [ -n "${SET:-}" ]; then
  IFS=';' read -r -a entries <<< "$SET"
  for e in "${entries[@]}"; do overrides+=(--set "$e"); done
fi
launch=()
[ "$ranks" -gt 1 ] && launch=(mpirun -np "$ranks")
for r in $(seq 1 "$runs"); do
  for v in old new; do
    b=$old; [ $v = new ] && b=$new
    start=$(date +%s%N)
    "${launch[@]}" "$b" "$scene" --set Solver/Method=explicit \
      --set Output/Interval=0 --set "Output/Checkpoint interval=0" \
      --set "Output/Directory=$out/$v" "${overrides[@]}" \
      --stop-after "$stations" > "$out/$v.$r.log" 2>&1 ||
      [ $? -eq 3 ] || { echo "explicit_kernel.sh: $b failed ($out/$v.$r.log)"; exit 1; }
    awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN {printf "%.2f\n", (b - a) / 1e9}' > "$out/$v.$r.wall"
  done
done
# per run: cells, explicit steps, timer seconds -> microseconds per
# tetrahedron per core per explicit step (the per-station parts, search and
# mass/time-step updates, spread over the steps)
for v in old new; do
  for r in $(seq 1 "$runs"); do
    awk -v ranks="$ranks" -v wall="$(cat "$out/$v.$r.wall")" '
      /tetrahedra,/ { for (i = 1; i <= NF; ++i) if ($(i) ~ /^tetrahedra/) cells = $(i - 1) }
      /^step / { for (i = 1; i <= NF; ++i) if ($(i) == "explicit") steps += $(i + 1) }
      # timer rows: | name | calls | 10.6s | 67% |
      function seconds() { split($0, f, "|"); sub(/s *$/, "", f[4]); return f[4] + 0 }
      /Explicit: internal forces/ { internal = seconds() }
      /Explicit: contact and loads/ { contact = seconds() }
      /Contact: search/ { search = seconds() }
      /Explicit: mass|Explicit: largest frequency/ { mass += seconds() }
      END { c = 1e6 * ranks / (cells * steps)
            printf "%.4f %.4f %.4f %.4f %.2f\n", internal * c, contact * c, search * c, mass * c, wall }' "$out/$v.$r.log"
  done > "$out/$v.table"
done
median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
names=("internal forces" "contact+loads" "search" "mass+frequency" "wall s")
printf "%-5s" build; for n in "${names[@]}"; do printf " %16s" "$n"; done; echo
for v in old new; do
  printf "%-5s" $v
  for k in 1 2 3 4 5; do
    m=$(cut -d' ' -f$k "$out/$v.table" | median)
    eval "${v}_$k=$m"
    printf " %16s" "$m"
  done
  echo
done
printf "%-5s" ratio
for k in 1 2 3 4 5; do
  eval "a=\$old_$k b=\$new_$k"
  awk -v a="$a" -v b="$b" 'BEGIN {if (a > 0) printf " %16.3f", b / a; else printf " %16s", "-"}'
done
echo
echo "(us per tetrahedron per core per explicit step, wall time in s; medians of $runs runs)"
echo "last station, old: $(grep -E '^step' "$out/old.1.log" | tail -n 1 | cut -d" " -f1-16)"
echo "last station, new: $(grep -E '^step' "$out/new.1.log" | tail -n 1 | cut -d" " -f1-16)"
echo "logs in $out"
