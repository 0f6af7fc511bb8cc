#!/usr/bin/env bash
# Hertz refinement study: the elastic tin sphere of prm/hertz.prm squeezed by
# delta = 0.004 ... 0.016 mm on a sequence of meshes refined at the poles.
# Prints, per mesh, DoFs, wall time, and the force error against
# F = 4/3 E* sqrt(R) (delta/2)^(3/2) at each delta. Used in doc/verification.md.
# Usage: bash benchmarks/hertz_refinement.sh [build dir]   (from the source root)
set -eu
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
densify=${1:-$root/build}/densify
out=$(mktemp -d)
# degree  refined-size  growth  element-size
meshes=("1 0.03 0.3 0.5" "1 0.015 0.25 0.5" "2 0.05 0.3 0.5" "2 0.03 0.3 0.5" "2 0.02 0.25 0.5" "2 0.012 0.25 0.5")
printf "%-4s %-8s %-7s %-8s %-8s %s\n" degree h_pole growth DoFs seconds "error % at delta = 0.004 0.008 0.012 0.016"
for m in "${meshes[@]}"; do
  set -- $m
  dir=$out/p$1_$2_$3
  "$densify" "$root/prm/hertz.prm" --set "Output/Directory=$dir" --set "Output/Interval=0" \
    --set "Mesh/Polynomial degree=$1" --set "Mesh/Refined element size=$2" \
    --set "Mesh/Refinement growth=$3" --set "Mesh/Element size=$4" \
    --set "Tools/Upper punch/Displacement history=0:0, 1:0.016" \
    --set "Time stepping/Number of steps=4" > "$dir.log"
  dofs=$(grep -o '[0-9]* DoFs' "$dir.log" | cut -d' ' -f1)
  awk -F, -v deg=$1 -v hp=$2 -v g=$3 -v dofs=$dofs '
    NR > 1 { E = 43120; nu = 0.3; R = 1.25; Es = E / (1 - nu * nu);
             d = $3 / 2; F = 4 / 3 * Es * sqrt(R) * d ^ 1.5;
             err = err sprintf(" %+6.2f", 100 * ($4 - F) / F); t = $10 }
    END { printf "P%-3s %-8s %-7s %-8s %-8.1f%s\n", deg, hp, g, dofs, t, err }' "$dir/statistics.csv"
done
