#!/usr/bin/env python3
"""The table of benchmarks/press_to_95.sh from its OUT directory:
   python3 benchmarks/press_to_95_table.py OUT "MATERIALS"
the upper punch pressure at 80 / 85 / 90 / 92.5 / 95 % relative density by
each method (upper_punch_stress of statistics.csv: F_upper over the die's
bore), the explicit run against the implicit one, the smallest V/V0
and the wall time; writes OUT/MATERIAL_METHOD.csv (density %, MPa).
A method without OUT/MATERIAL_METHOD/statistics.csv is "not run"; one
without OUT/MATERIAL_METHOD.seconds takes its run's own wall_seconds."""
import csv, sys
out, materials = sys.argv[1], sys.argv[2].split()
stations = [80.0, 85.0, 90.0, 92.5, 95.0]
def rows(name):
    try:
        return list(csv.DictReader(open(f"{out}/{name}/statistics.csv")))
    except FileNotFoundError:
        return []
def curve(rs):
    return [(100 * float(r["relative_density"]), float(r["upper_punch_stress"]))
            for r in rs]
def at(c, density):
    for (da, pa), (db, pb) in zip(c, c[1:]):
        if da <= density <= db and db > da:
            return pa + (density - da) / (db - da) * (pb - pa)
    return float("nan")
print("pressure = upper_punch_stress (F_upper / die bore area, MPa)")
print("material | method | end density % | smallest V/V0 | wall s | "
      + " | ".join("p at %g %%" % s for s in stations))
for material in materials:
    curves = {}
    for method in ("implicit", "explicit"):
        name = f"{material}_{method}"
        rs = rows(name)
        if not rs:
            print(f"{material} | {method} | not run")
            continue
        try:
            seconds = float(open(f"{out}/{name}.seconds").read())
        except FileNotFoundError:
            seconds = float(rs[-1]["wall_seconds"])
        try:
            failed = [l.strip() for l in open(f"{out}/{name}.log")
                      if "error" in l or ("exit" in l and "exit 0" not in l)]
        except FileNotFoundError:
            failed = []
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
    if len(curves) < 2:
        continue
    diff = [100 * (at(curves["explicit"], s) / at(curves["implicit"], s) - 1)
            for s in stations]
    print(f"{material} | explicit - implicit | | | | "
          + " | ".join("%+.2f %%" % d for d in diff))
