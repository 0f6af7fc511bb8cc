#!/bin/bash
# Inertia in high-speed compaction (doc/performance.md, "Inertia: high-speed
# compaction"): runs prm/high_speed_sn_light.prm (the light paper layer of
# seven J2 tin spheres, explicit dynamics with tin's physical density, no
# mass scaling) at several punch speeds, one after the other, and the
# quasi-static reference, prm/single_layer_sn_light.prm (implicit, the same
# mesh, friction and stroke of 1.28 mm), then prints the table of
# benchmarks/inertia_table.py: the upper punch force at four strokes per
# speed, its difference from the quasi-static force, and the kinetic energy
# against the internal work (KE/IE).
# Usage (from the source root):
#   bash benchmarks/inertia_study.sh [OUT_DIR [SPEEDS [--set ...]...]]
# e.g.
#   bash benchmarks/inertia_study.sh inertia_study 1,2,5,10,20,50
# Defaults: OUT_DIR inertia_study, SPEEDS 1,2,5,10,20,50 (m/s, ','-separated). A speed v
# is the mean punch speed, stroke / Explicit/Loading time (1.28e-3 m / v);
# after the smooth start over Explicit/Ramp fraction (5 %) of the loading
# time the punch moves 2.6 % faster than that. A speed may carry its own
# options after a colon, ';'-separated, e.g. "50:Explicit/Time step
# safety=0.7". Extra --set options apply to every explicit run.
# Writes OUT_DIR/quasi_static/ and OUT_DIR/v<SPEED>/ (statistics.csv,
# log.txt, the console output in run.log) and OUT_DIR/runs.txt (one line per
# run: speed, directory, exit code, wall seconds, options; tab-separated),
# the table in OUT_DIR/table.md. A run that stops (e.g. as unstable) keeps
# its stations so far; the table shows its error line.
# Environment: DENSIFY (default build/densify); NP MPI ranks (default 1);
# INERTIA_LOCK=FILE runs each run under flock FILE, so that the heavy jobs
# of others wait; QUASI_STATIC_DIR=DIR reuses the statistics.csv of an
# earlier quasi-static run instead of running it again. Needs python3 with
# numpy.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
densify=${DENSIFY:-$root/build/densify}
out=${1:-inertia_study}
speeds=${2:-1,2,5,10,20,50}
shift $(( $# < 2 ? $# : 2 ))
np=${NP:-1}
stroke_m=1.28e-3
[ -x "$densify" ] || { echo "inertia_study.sh: error: no executable $densify (build first)" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"
: > "$out/runs.txt"
launch=()
[ "$np" -gt 1 ] && launch=(mpirun --oversubscribe -np "$np")
lock=()
[ -n "${INERTIA_LOCK:-}" ] && lock=(flock "$INERTIA_LOCK")

run() { # speed label, directory, scene, options...
  local speed=$1 dir=$2 scene=$3; shift 3
  rm -rf "${out:?}/$dir"
  local start rc=0
  start=$(date +%s.%N)
  "${lock[@]}" "${launch[@]}" "$densify" "$scene" \
    --set "Output/Directory=$out/$dir" --set "Output/Interval=0" \
    --set "Output/Checkpoint interval=0" "$@" > "$out/$dir.log" 2>&1 || rc=$?
  local seconds
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  mkdir -p "$out/$dir" && mv "$out/$dir.log" "$out/$dir/run.log"
  local options=() o
  for o in "$@"; do [ "$o" = --set ] || options+=("$o"); done
  printf '%s\t%s\t%s\t%s\t%s\n' "$speed" "$dir" "$rc" "$seconds" \
    "$(IFS=';'; echo "${options[*]}")" >> "$out/runs.txt"
  echo "$dir: exit $rc, $(printf '%.1f' "$seconds") s $(grep -o 'Finished [0-9]* steps in [^ ]*' "$out/$dir/run.log" || grep 'error' "$out/$dir/run.log" | head -n 1)"
}

if [ -n "${QUASI_STATIC_DIR:-}" ]; then
  mkdir -p "$out/quasi_static"
  cp "$QUASI_STATIC_DIR/statistics.csv" "$out/quasi_static/"
  printf 'quasi-static\tquasi_static\t0\t%s\t(reused %s)\n' \
    "$(awk -F, 'END {print $10}' "$QUASI_STATIC_DIR/statistics.csv")" \
    "$QUASI_STATIC_DIR" >> "$out/runs.txt"
else
  run quasi-static quasi_static "$root/prm/single_layer_sn_light.prm"
fi
IFS=',' read -r -a entries <<< "$speeds"
for entry in "${entries[@]}"; do
  speed=${entry%%:*}
  options=()
  if [ "$entry" != "$speed" ]; then
    IFS=';' read -r -a parts <<< "${entry#*:}"
    for p in "${parts[@]}"; do options+=(--set "$p"); done
  fi
  loading_time=$(/usr/bin/python3 -c "print('%.6g' % ($stroke_m / $speed))")
  run "$speed" "v$speed" "$root/prm/high_speed_sn_light.prm" \
    --set "Explicit/Loading time=$loading_time" "$@" "${options[@]}"
done
/usr/bin/python3 "$root/benchmarks/inertia_table.py" "$out" | tee "$out/table.md"
