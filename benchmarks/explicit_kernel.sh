#!/bin/bash
# The explicit method's force kernels of two builds side by side: the light
# layer (prm/single_layer_sn_light.prm, 2,492 tetrahedra) by explicit
# dynamics to station STATIONS, each build RUNS times, alternated (old, new,
# old, new, ...), on RANKS ranks. Prints per build the median of the timer
# rows "Explicit: internal forces" and "Explicit: contact and loads" in
# microseconds per tetrahedron per core per explicit step, the median wall
# time, and their ratios new / old; and whether the two builds' last
# station lines agree.
# Usage (from the source root):
#   bash benchmarks/explicit_kernel.sh OLD_EXECUTABLE NEW_EXECUTABLE [RUNS] [STATIONS] [RANKS]
# defaults: 3 runs, 40 stations, 1 rank. doc/performance.md, "The explicit
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
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "explicit_kernel.sh: $b is not an executable"; exit 2; }
done
out=$(mktemp -d)
launch=()
[ "$ranks" -gt 1 ] && launch=(mpirun -np "$ranks")
for r in $(seq 1 "$runs"); do
  for v in old new; do
    b=$old; [ $v = new ] && b=$new
    start=$(date +%s%N)
    "${launch[@]}" "$b" prm/single_layer_sn_light.prm --set Solver/Method=explicit \
      --set Output/Interval=0 --set "Output/Checkpoint interval=0" \
      --set "Output/Directory=$out/$v" --stop-after "$stations" > "$out/$v.$r.log" 2>&1 ||
      [ $? -eq 3 ] || { echo "explicit_kernel.sh: $b failed ($out/$v.$r.log)"; exit 1; }
    awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN {printf "%.2f\n", (b - a) / 1e9}' > "$out/$v.$r.wall"
  done
done
# per run: cells, explicit steps, timer seconds -> microseconds per
# tetrahedron per core per step
for v in old new; do
  for r in $(seq 1 "$runs"); do
    awk -v ranks="$ranks" -v wall="$(cat "$out/$v.$r.wall")" '
      /tetrahedra,/ { for (i = 1; i <= NF; ++i) if ($(i) ~ /^tetrahedra/) cells = $(i - 1) }
      /^step / { for (i = 1; i <= NF; ++i) if ($(i) == "explicit") steps += $(i + 1) }
      # timer rows: | name | calls | 10.6s | 67% |
      /Explicit: internal forces/ { split($0, f, "|"); sub(/s *$/, "", f[4]); internal = f[4] + 0 }
      /Explicit: contact and loads/ { split($0, f, "|"); sub(/s *$/, "", f[4]); contact = f[4] + 0 }
      END { c = 1e6 * ranks / (cells * steps)
            printf "%.4f %.4f %.2f\n", internal * c, contact * c, wall }' "$out/$v.$r.log"
  done | sort -n > "$out/$v.table"
done
median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
printf "%-5s %22s %22s %12s\n" build "internal forces us/tet" "contact+loads us/tet" "wall s"
for v in old new; do
  i=$(cut -d' ' -f1 "$out/$v.table" | median)
  c=$(cut -d' ' -f2 "$out/$v.table" | median)
  w=$(cut -d' ' -f3 "$out/$v.table" | median)
  printf "%-5s %22s %22s %12s\n" $v "$i" "$c" "$w"
  eval "${v}_i=$i ${v}_c=$c ${v}_w=$w"
done
awk -v i0="$old_i" -v i1="$new_i" -v c0="$old_c" -v c1="$new_c" -v w0="$old_w" -v w1="$new_w" \
  'BEGIN {printf "%-5s %22.3f %22.3f %12.3f\n", "ratio", i1 / i0, c1 / c0, w1 / w0}'
echo "last station, old: $(grep -E '^step' "$out/old.1.log" | tail -n 1 | cut -d" " -f1-16)"
echo "last station, new: $(grep -E '^step' "$out/new.1.log" | tail -n 1 | cut -d" " -f1-16)"
echo "logs in $out"
