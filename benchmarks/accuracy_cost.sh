#!/bin/bash
# What accuracy costs in time (doc/accuracy.md): runs a grid of settings
# (mesh, element, load steps, Newton tolerance, contact penalty, friction
# law, method) on the scenes
# named, one after the other on 1 rank, and writes one CSV row per run: the
# settings, wall time and core-seconds, Newton iterations, steps and
# cut-backs, and the errors against the finest run of each scene (the first
# of its grid): upper punch force at 25, 50, 75 and 100 % of the stroke,
# final relative density, particle volume change, and the shape (mid-height
# section area of every particle; with several particles also how many have
# as many straight section edges as contact neighbours).
# Usage (from the source root):
#   bash benchmarks/accuracy_cost.sh [--scenes sphere,light,layer43]
#        [--grid tiny|standard|full] [--out DIR] [--keep] [--only REGEX]
# Defaults: --scenes sphere,light --grid standard --out accuracy_cost.
# Writes DIR/accuracy_cost.csv (and DIR/runs/ with each run's statistics.csv
# and log; --keep also keeps the graphical output; --only runs just the runs
# whose "scene: label" matches the extended regular expression, e.g. to
# add runs to a study: their lines of DIR/runs/list.txt go into the other
# study's list, the reference first, and benchmarks/accuracy_cost_table.py
# LIST . rewrites the CSV). Then
#   python3 benchmarks/accuracy_cost_plot.py DIR/accuracy_cost.csv --out doc
# plots error against wall time with the Pareto front and prints its table.
# Scenes: sphere = prm/single_sphere_sn.prm pressed to 30 % height
# reduction (0.75 mm); light = prm/single_layer_sn_light.prm to the full
# stroke; layer43 = prm/single_layer_sn.prm (hours per run: the standard
# grid stops it after the first 50 of 250 steps, so its errors are those of
# the first fifth of the stroke). Needs build/densify (or DENSIFY=...) and
# python3 with numpy (and python3-vtk9 for the shape). Run alone on the
# machine: wall times are what is measured (ACCURACY_LOCK=FILE runs each run
# under flock FILE, so that runs of others wait).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
densify=${DENSIFY:-$root/build/densify}
usage='usage: bash benchmarks/accuracy_cost.sh [--scenes sphere,light,layer43] [--grid tiny|standard|full] [--out DIR] [--keep] [--only REGEX]'
scenes=sphere,light
grid=standard
out=accuracy_cost
keep=false
only=
while [ $# -gt 0 ]; do
  case "$1" in
    --scenes) scenes=${2:?$usage}; shift 2 ;;
    --grid) grid=${2:?$usage}; shift 2 ;;
    --out) out=${2:?$usage}; shift 2 ;;
    --keep) keep=true; shift ;;
    --only) only=${2:?$usage}; shift 2 ;;
    -h|--help) echo "$usage"; exit 0 ;;
    *) echo "accuracy_cost.sh: error: unknown argument '$1'; $usage" >&2; exit 2 ;;
  esac
done
case "$grid" in tiny|standard|full) ;; *) echo "accuracy_cost.sh: error: --grid '$grid': expected tiny, standard or full" >&2; exit 2 ;; esac
[ -x "$densify" ] || { echo "accuracy_cost.sh: error: no executable $densify (build first)" >&2; exit 2; }

# ---- the grid --------------------------------------------------------------
# Each run: "scene|label|Sub/Entry=value;Sub/Entry=value;...". The first run
# of a scene is its reference (the finest); the second is the next-finest
# level of the same settings, whose distance to the first shows how far the
# reference itself is converged.
runs=()
add() { runs+=("$1|$2|$3"); }
# sphere levels: P1 with the nodal-averaged F-bar (remedy auto), P1 plain,
# P2; element size / size at the poles (mm)
p1() { echo "Mesh/Polynomial degree=1;Mesh/Element size=$1;Mesh/Refined element size=$2"; }
p2() { echo "Mesh/Polynomial degree=2;Mesh/Element size=$1;Mesh/Refined element size=$2"; }
steps() { echo "Time stepping/Number of steps=$1"; }
case "$grid" in
  tiny)
    # seconds: a shrunk sphere (0.1 mm) and a shrunk light layer (0.04 mm)
    add sphere "ref P1 0.5 4 steps" "$(p1 0.5 0.25);$(steps 4);Tools/Upper punch/Displacement history=0:0, 1:0.1"
    add sphere "P1 0.7 4 steps" "$(p1 0.7 0.35);$(steps 4);Tools/Upper punch/Displacement history=0:0, 1:0.1"
    add sphere "P1 0.7 2 steps" "$(p1 0.7 0.35);$(steps 2);Tools/Upper punch/Displacement history=0:0, 1:0.1"
    add light "ref 0.6 4 steps" "Mesh/Element size=0.6;$(steps 4);Tools/Die wall/Diameter=7.52;Tools/Upper punch/Displacement history=0:0, 0.8:0.04"
    add light "0.6 2 steps" "Mesh/Element size=0.6;$(steps 2);Tools/Die wall/Diameter=7.52;Tools/Upper punch/Displacement history=0:0, 0.8:0.04"
    ;;
  standard|full)
    # the sphere: every lever
    add sphere "ref P2 0.4/0.1 32 steps" "$(p2 0.4 0.1);$(steps 32)"
    add sphere "P2 0.6/0.2 32 steps" "$(p2 0.6 0.2);$(steps 32)"
    add sphere "P2 0.4/0.1 16 steps" "$(p2 0.4 0.1);$(steps 16)"
    add sphere "P2 0.6/0.2 16 steps" "$(p2 0.6 0.2);$(steps 16)"
    add sphere "P2 0.6/0.2 8 steps" "$(p2 0.6 0.2);$(steps 8)"
    add sphere "P2 0.6/0.2 16 steps cg-amg" "$(p2 0.6 0.2);$(steps 16);Solver/Linear solver=auto"
    add sphere "P1 0.25/0.08 16 steps" "$(p1 0.25 0.08);$(steps 16)"
    add sphere "P1 0.3/0.1 16 steps" "$(p1 0.3 0.1);$(steps 16)"
    add sphere "P1 0.4/0.15 16 steps" "$(p1 0.4 0.15);$(steps 16)"
    add sphere "P1 0.6/0.25 16 steps" "$(p1 0.6 0.25);$(steps 16)"
    add sphere "P1 0.4/0.15 8 steps" "$(p1 0.4 0.15);$(steps 8)"
    add sphere "P1 0.4/0.15 32 steps" "$(p1 0.4 0.15);$(steps 32)"
    add sphere "P1 plain 0.4/0.15 16 steps" "$(p1 0.4 0.15);$(steps 16);Mesh/Volumetric locking remedy=none"
    add sphere "P1 0.4/0.15 16 steps tol 1e-4" "$(p1 0.4 0.15);$(steps 16);Solver/Newton tolerance=1e-4"
    add sphere "P1 0.4/0.15 16 steps tol 1e-6" "$(p1 0.4 0.15);$(steps 16);Solver/Newton tolerance=1e-6"
    add sphere "P1 0.4/0.15 16 steps penalty 100" "$(p1 0.4 0.15);$(steps 16);Contact/Penalty factor=100"
    # the light layer: a reduced grid (a run at 0.5 mm is about a minute,
    # the reference at 0.3 mm about ten)
    add light "ref 0.3 128 steps" "Mesh/Element size=0.3"
    add light "0.35 128 steps" "Mesh/Element size=0.35"
    add light "0.4 128 steps" "Mesh/Element size=0.4"
    add light "0.45 128 steps" "Mesh/Element size=0.45"
    add light "0.5 128 steps (scene)" ""
    add light "0.6 128 steps" "Mesh/Element size=0.6"
    add light "0.5 64 steps" "$(steps 64)"
    add light "0.5 32 steps" "$(steps 32)"
    add light "0.6 32 steps" "Mesh/Element size=0.6;$(steps 32)"
    add light "0.5 tol 1e-4" "Solver/Newton tolerance=1e-4"
    add light "0.5 penalty 30" "Contact/Penalty factor=30"
    add light "0.5 arctangent" "Contact/Friction model=arctangent"
    add light "0.5 P1 plain" "Mesh/Volumetric locking remedy=none"
    add light "0.5 explicit 4000" "Solver/Method=explicit;Explicit/Number of steps=4000"
    if [ "$grid" = full ]; then
      add light "0.5 explicit 8000" "Solver/Method=explicit;Explicit/Number of steps=8000"
      add light "0.45 64 steps" "Mesh/Element size=0.45;$(steps 64)"
      add light "0.5 penalty 10" "Contact/Penalty factor=10"
      add sphere "P2 0.6/0.2 16 steps tol 1e-4" "$(p2 0.6 0.2);$(steps 16);Solver/Newton tolerance=1e-4"
    fi
    # the 43-sphere layer: the first 50 of 250 steps (hours otherwise)
    add layer43 "ref 0.3 250 steps" ""
    add layer43 "0.4 250 steps" "Mesh/Element size=0.4"
    add layer43 "0.5 250 steps" "Mesh/Element size=0.5"
    add layer43 "0.5 125 steps" "Mesh/Element size=0.5;$(steps 125)"
    ;;
esac

scene_file() {
  case "$1" in
    sphere) echo "$root/prm/single_sphere_sn.prm" ;;
    light) echo "$root/prm/single_layer_sn_light.prm" ;;
    layer43) echo "$root/prm/single_layer_sn.prm" ;;
    *) echo "accuracy_cost.sh: error: unknown scene '$1' (sphere, light, layer43)" >&2; exit 2 ;;
  esac
}
# options every run of a scene gets
scene_options() {
  case "$1" in
    # the study's sphere solves with gmres-lu (the scene: auto, CG + AMG,
    # which one run of the grid keeps)
    sphere) echo "Tools/Upper punch/Displacement history=0:0, 1:0.75;Solver/Linear solver=gmres-lu" ;;
    layer43) echo "@stop-after" ;;
    *) echo "" ;;
  esac
}
for s in ${scenes//,/ }; do scene_file "$s" > /dev/null; done

mkdir -p "$out/runs"
list=$out/runs/list.txt
: > "$list"
i=0
for run in "${runs[@]}"; do
  IFS='|' read -r scene label sets <<< "$run"
  case ",$scenes," in *",$scene,"*) ;; *) continue ;; esac
  i=$((i + 1))
  if [ -n "$only" ] && ! printf '%s: %s\n' "$scene" "$label" | grep -qE -- "$only"; then
    continue
  fi
  dir=$out/runs/$(printf "%03d" $i)_$scene
  args=()
  stop=()
  base=$(scene_options "$scene")
  if [ "$base" = "@stop-after" ]; then
    [ "$grid" = full ] || stop=(--stop-after 50)
    # the paper's layer runs explicit by default; the study is implicit
    base="Solver/Method=implicit"
  fi
  sets=${base:+$base;}$sets
  IFS=';' read -r -a entries <<< "$sets"
  for e in "${entries[@]}"; do
    [ -n "$e" ] && args+=(--set "$e")
  done
  # graphics only at the last step (for the shape), no checkpoints
  args+=(--set "Output/Directory=$dir" --set "Output/Interval=100000"
         --set "Output/Checkpoint interval=0")
  echo "== $scene: $label"
  rc=0
  # ACCURACY_LOCK=FILE: each run waits for flock FILE (a shared machine)
  ${ACCURACY_LOCK:+flock "$ACCURACY_LOCK"} /usr/bin/time -f "%e %U %S" -o "$dir.time" "$densify" "$(scene_file "$scene")" \
    "${args[@]}" "${stop[@]}" > "$dir.log" 2>&1 || rc=$?
  # 3: stopped by --stop-after, as asked
  [ $rc -eq 3 ] && [ ${#stop[@]} -gt 0 ] && rc=0
  [ $rc -eq 0 ] || echo "   densify failed (exit $rc): $(tail -n 1 "$dir.log")"
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$scene" "$label" "$dir" "$rc" "$(scene_file "$scene")" "$sets" >> "$list"
  tail -n 1 "$dir.time" | sed 's/^/   time (wall user sys): /'
done

/usr/bin/python3 "$root/benchmarks/accuracy_cost_table.py" "$list" "$root" \
  > "$out/accuracy_cost.csv"
echo "wrote $out/accuracy_cost.csv ($(($(wc -l < "$out/accuracy_cost.csv") - 1)) runs)"
if [ "$keep" = false ]; then
  find "$out/runs" \( -name '*.vtu' -o -name '*.pvtu' \) -delete
fi
