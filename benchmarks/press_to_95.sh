#!/bin/bash
# A scene pressed past the paper's 90 % to 95 % relative density by both
# methods, one material at a time: the implicit and the explicit run side by
# side (one rank each, the two cores), then for each the upper punch
# pressure (F_upper / die area) at given relative densities (interpolated
# between the stations), the difference between the methods, the smallest
# cell volume ratio V/V0 and the wall time. The pressure-density curves go to
# OUT/MATERIAL_METHOD.csv (density in %, pressure in MPa).
# Usage (from the source root):
#   bash benchmarks/press_to_95.sh OUT STROKE "MATERIALS" [--set ...]...
# e.g. the light paper layer on a 0.4 mm mesh to 95 % (doc/verification.md,
# "Pressed to 95 %"):
#   bash benchmarks/press_to_95.sh /tmp/p95 1.366 "Sn Fe Cu" \
#     --set "Mesh/Element size=0.4"
# STROKE is the upper punch's travel (mm) over the scene's end time: for a
# density rho of the meshed particles, 2.5 mm - V / (rho die area) with the
# particle volume V that a run prints as "Initial relative density"; the
# --set options apply to both methods; EXPLICIT_STEPS (default 20000) sets
# the explicit run's Explicit/Number of steps and IMPLICIT_STEPS (default
# 128 per 1.28 mm) the implicit load steps.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=$1; stroke=$2; materials=$3; shift 3
scene=${SCENE:-$root/prm/single_layer_sn_light.prm}
densify=${DENSIFY:-$root/build/densify}
explicit_steps=${EXPLICIT_STEPS:-20000}
implicit_steps=${IMPLICIT_STEPS:-$(echo "($stroke * 100 + 0.5) / 1" | bc)}
mkdir -p "$out"
run() { # name, extra options
  local name=$1; shift
  local start=$(date +%s.%N)
  "$densify" "$scene" --set "Output/Directory=$out/$name" \
    --set "Output/Interval=0" --set "Output/Checkpoint interval=0" \
    --set "Tools/Upper punch/Displacement history=0:0, 0.8:$stroke" \
    "$@" > "$out/$name.log" 2>&1 || echo "$name: exit $?" >> "$out/$name.log"
  echo "$(date +%s.%N) - $start" | bc > "$out/$name.seconds"
}
for material in $materials; do
  run "${material}_implicit" --set "Particles/Materials=$material" \
    --set "Time stepping/Number of steps=$implicit_steps" "$@" &
  first=$!
  run "${material}_explicit" --set "Particles/Materials=$material" \
    --set "Solver/Method=explicit" \
    --set "Explicit/Number of steps=$explicit_steps" "$@"
  wait $first
done
/usr/bin/python3 - "$out" "$materials" "$scene" <<'PY'
import csv, math, re, sys
out, materials, scene = sys.argv[1], sys.argv[2].split(), sys.argv[3]
stations = [80.0, 85.0, 90.0, 92.5, 95.0]
diameter = 8.07
for line in open(scene):
    m = re.match(r"\s*set Diameter\s*=\s*([0-9.]+)", line)
    if m:
        diameter = float(m.group(1))
area = math.pi * diameter ** 2 / 4
def rows(name):
    try:
        return list(csv.DictReader(open(f"{out}/{name}/statistics.csv")))
    except FileNotFoundError:
        return []
def curve(rs):
    return [(100 * float(r["relative_density"]), float(r["upper_punch_force"]) / area)
            for r in rs]
def at(c, density):
    for (da, pa), (db, pb) in zip(c, c[1:]):
        if da <= density <= db and db > da:
            return pa + (density - da) / (db - da) * (pb - pa)
    return float("nan")
print("die area %.3f mm^2; pressure = F_upper / area (MPa)" % area)
print("material | method | end density % | smallest V/V0 | wall s | "
      + " | ".join("p at %g %%" % s for s in stations))
for material in materials:
    curves = {}
    for method in ("implicit", "explicit"):
        name = f"{material}_{method}"
        rs = rows(name)
        seconds = float(open(f"{out}/{name}.seconds").read())
        failed = [l.strip() for l in open(f"{out}/{name}.log") if "error" in l or "exit" in l]
        c = curve(rs)
        curves[method] = c
        with open(f"{out}/{name}.csv", "w") as f:
            f.write("relative_density_percent,pressure_MPa\n")
            for d, p in c:
                f.write(f"{d:.4f},{p:.4f}\n")
        vmin = min((float(r["min_cell_volume_ratio"]) for r in rs), default=float("nan"))
        end = c[-1][0] if c else float("nan")
        print(f"{material} | {method} | {end:.2f} | {vmin:.3f} | {seconds:.0f} | "
              + " | ".join("%.2f" % at(c, s) for s in stations)
              + ("  (" + failed[-1] + ")" if failed else ""))
    diff = [100 * (at(curves["explicit"], s) / at(curves["implicit"], s) - 1)
            for s in stations]
    print(f"{material} | explicit - implicit | | | | "
          + " | ".join("%+.2f %%" % d for d in diff))
PY
