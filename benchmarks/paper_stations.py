#!/usr/bin/env python3
"""The paper scene's stations from a run's statistics.csv: upper punch force,
relative density and smallest cell volume ratio at the strokes 0.32 / 0.64 /
0.96 / 1.024 / 1.152 / 1.216 / 1.28 mm (linear interpolation between the
rows), the force curve's largest jump from 60 % density on, and the force
against an implicit reference of
doc/paper_comparison.md: 'plain' (the default; Sn, Fe or Cu by the plain
F-bar element: alpha = 0, no barrier) or 'defaults' (Sn, Fe or Cu with the
defaults: "The reference with the defaults"; Cu's ends at 1.2749 mm, so its
1.28 mm row compares with nan).

Usage (from the source root):
  python3 benchmarks/paper_stations.py OUTPUT_DIR/statistics.csv [Sn|Fe|Cu] \
    [plain|defaults]

The tables of doc/verification.md ("The barrier against crushed cells")
come from it, after for instance
  mpirun -np 2 build/densify prm/single_layer_sn.prm --set Output/Directory=DIR
"""
import csv
import math
import sys

STROKES = [0.32, 0.64, 0.96, 1.024, 1.152, 1.216, 1.28]
# doc/paper_comparison.md: F_upper (N) of the implicit runs at STROKES
REFERENCE = {
    "Sn": [3482.7, 5343.0, 9908.2, 12079.7, 20350.0, 24478.6, 29848.7],
    "Fe": [5672.7, 8653.7, 16058.5, 19609.6, 32908.6, 39633.6, 49185.1],
    "Cu": [3745.4, 5709.9, 10599.8, 12935.7, 21736.8, 26187.0, 32543.8],
}
# doc/paper_comparison.md, "The reference with the defaults"
REFERENCE_DEFAULTS = {
    "Sn": [3493.4, 5368.8, 9963.1, 12147.7, 20448.7, 24601.3, 30111.6],
    "Fe": [5710.1, 8755.7, 16268.3, 19892.6, 33301.6, 40092.6, 50528.8],
    "Cu": [3771.7, 5785.6, 10750.0, 13167.4, 21994.9, 26514.9, math.nan],
}


def interpolate(xs, ys, x):
    """ys at x, linear between the neighbouring rows; nan outside."""
    for i in range(1, len(xs)):
        if xs[i - 1] <= x + 1e-12 and x <= xs[i] + 1e-12:
            if xs[i] == xs[i - 1]:
                return ys[i]
            w = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return (1 - w) * ys[i - 1] + w * ys[i]
    return math.nan


def main():
    if len(sys.argv) not in (2, 3, 4):
        sys.exit("usage: paper_stations.py STATISTICS.csv [Sn|Fe|Cu] "
                 "[plain|defaults]")
    material = sys.argv[2] if len(sys.argv) >= 3 else "Sn"
    which = sys.argv[3] if len(sys.argv) == 4 else "plain"
    if material not in REFERENCE:
        sys.exit("paper_stations.py: the material must be Sn, Fe or Cu")
    if which not in ("plain", "defaults"):
        sys.exit("paper_stations.py: the reference must be plain or defaults")
    references = REFERENCE if which == "plain" else REFERENCE_DEFAULTS
    if material not in references:
        sys.exit(f"paper_stations.py: no reference with the defaults for "
                 f"{material} yet (doc/paper_comparison.md); use plain")
    try:
        with open(sys.argv[1], newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"paper_stations.py: cannot read {sys.argv[1]}: {e.strerror}")
    if not rows:
        sys.exit(f"paper_stations.py: {sys.argv[1]} has no rows")
    stroke = [0.0] + [float(r["punch_displacement"]) for r in rows]
    force = [0.0] + [float(r["upper_punch_force"]) for r in rows]
    density = [math.nan] + [float(r["relative_density"]) for r in rows]
    ratio = [1.0] + [float(r.get("min_cell_volume_ratio", "nan")) for r in rows]
    print("stroke_mm  F_upper_N  vs_reference  density_%  min_V/V0_to_here")
    for x, reference in zip(STROKES, references[material]):
        f = interpolate(stroke, force, x)
        d = interpolate(stroke, density, x)
        reached = [r for s, r in zip(stroke, ratio) if s <= x + 1e-9]
        smallest = min(reached) if reached else math.nan
        print(f"{x:8.3f}  {f:10.1f}  {100 * (f / reference - 1):+7.2f} %"
              f"  {100 * d:8.3f}  {smallest:.3f}")
    print(f"smallest V/V0 of the run: {min(ratio):.3f} "
          f"(last row: {ratio[-1]:.3f}, stroke {stroke[-1]:.4f} mm)")
    # the force curve's smoothness from 60 % relative density on: the
    # largest second difference of ln F_upper between consecutive rows
    # (a kick of the compact shows as a jump up and back)
    jumps = [(abs(math.log(force[i + 1]) - 2 * math.log(force[i])
                  + math.log(force[i - 1])), rows[i - 1]["step"])
             for i in range(2, len(force) - 1)
             if density[i] >= 0.6 and min(force[i - 1:i + 2]) > 0]
    if jumps:
        jump, step = max(jumps)
        print(f"largest jump of the force curve from 60 % density on: "
              f"{100 * jump:.1f} % (second difference of ln F_upper, "
              f"row {step}); rows above 2 %: "
              f"{sum(1 for j, _ in jumps if j > 0.02)}")


if __name__ == "__main__":
    main()
