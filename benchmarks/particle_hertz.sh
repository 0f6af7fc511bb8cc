#!/usr/bin/env bash
# Two equal elastic tin spheres stacked between frictionless punches on the
# mesh of prm/hertz.prm (P2, poles refined to 0.03 mm), pressed by 0.048 mm
# in 3 steps, against Hertz for the stack: F = 4/3 E/(1 - nu^2) sqrt(R)
# (delta/4)^(3/2). Prints delta/R, the FEM and Hertz forces and the error at
# each step; about 3 minutes on one core. The ctest tests/particle_hertz.cc
# runs the same scene with the poles refined to 0.04 mm, checked from the
# second step. doc/verification.md, "Two spheres pressed together".
# Usage: bash benchmarks/particle_hertz.sh [build dir] [refined element size]
set -eu
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
densify=${1:-$root/build}/densify
h=${2:-0.03}
out=$(mktemp -d)
"$densify" "$root/prm/hertz.prm" --set "Output/Directory=$out" \
  --set "Output/Interval=0" --set "Particles/Centres=0,0,1.25; 0,0,3.75" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.048" \
  --set "Solver/Linear solver=direct" --set "Contact/Hold poles on axis=true" \
  --set "Mesh/Refined element size=$h" | grep "^Finished"
/usr/bin/python3 - "$out/statistics.csv" <<'PY'
import csv, math, sys
E, nu, R = 43120., 0.3, 1.25
print("delta/R  F_fem (N)  F_hertz (N)  error (%)")
for r in csv.DictReader(open(sys.argv[1])):
    d, F = float(r["punch_displacement"]), float(r["upper_punch_force"])
    Fh = 4. / 3. * E / (1 - nu * nu) * math.sqrt(R) * (d / 4) ** 1.5
    print("%.4f  %.3f  %.3f  %+.2f" % (d / R, F, Fh, 100 * (F - Fh) / Fh))
PY
rm -rf "$out"
