#!/bin/bash
# What the geometric particle-contact tangent (Contact/Geometric tangent) buys:
# Newton iterations, cut-backs and wall time of the seven-sphere layer of
# tests/seven_spheres.cc (elastic Sn, P1, 8 steps to 0.4 mm), frictionless
# (Hold poles on axis = vertical) and with friction 0.2, each with the
# geometric terms on and off (direct solver, 1 rank).
# Usage (from the source root): bash benchmarks/contact_tangent.sh
# Needs build/densify.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp -d)
common=(--set "Output/Interval=0" --set "Material/Model=elastic"
  --set "Material/Finite strain=false" --set "Mesh/Element size=0.5"
  --set "Mesh/Refinement directions=0,0,1; 0,0,-1; 1,0,0; 0.5,0.8660254,0; -0.5,0.8660254,0; -1,0,0; -0.5,-0.8660254,0; 0.5,-0.8660254,0"
  --set "Mesh/Refined element size=0.2" --set "Mesh/Refinement growth=0.5"
  --set "Particles/Centres=0,0,1.25; 2.5,0,1.25; 1.25,2.1650635094610964,1.25; -1.25,2.1650635094610964,1.25; -2.5,0,1.25; -1.25,-2.1650635094610964,1.25; 1.25,-2.1650635094610964,1.25; 2.98779,1.725,0.3"
  --set "Particles/Diameters=2.5,2.5,2.5,2.5,2.5,2.5,2.5,0.5"
  --set "Tools/Die wall/Diameter=7.5"
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.4"
  --set "Time stepping/Number of steps=8" --set "Solver/Linear solver=direct"
  --set "Solver/Maximum Newton iterations=100")
for case in frictionless friction; do
  if [ $case = frictionless ]; then
    extra=(--set "Contact/Friction coefficient=0" --set "Contact/Hold poles on axis=vertical")
  else
    extra=(--set "Contact/Friction coefficient=0.2")
  fi
  for geometric in true false; do
    dir=$out/${case}_$geometric
    rc=0
    "$root/build/densify" "$root/prm/seven_spheres_sn.prm" "${common[@]}" "${extra[@]}" \
      --set "Contact/Geometric tangent=$geometric" --set "Output/Directory=$dir" \
      > "$dir.log" 2>&1 || rc=$?
    /usr/bin/python3 - "$dir/statistics.csv" "$case" "$geometric" "$rc" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
newton = [int(r["newton_iterations"]) for r in rows]
print(f"{sys.argv[2]:12s} geometric tangent {sys.argv[3]:5s}: "
      f"{len(rows)} steps{'' if sys.argv[4] == '0' else ' (FAILED, exit ' + sys.argv[4] + ')'}, "
      f"Newton iterations {sum(newton)} ({' '.join(map(str, newton))}), "
      f"cut-backs {sum(int(r['cutbacks']) for r in rows)}, "
      f"wall {float(rows[-1]['wall_seconds']):.1f} s, "
      f"final punch force {float(rows[-1]['upper_punch_force']):.1f} N")
PY
  done
done
