"""Pressure against relative density from benchmarks/press_to_95.sh.

Usage: python3 benchmarks/press_to_95_plot.py OUT PICTURE.png [MATERIALS]
reads OUT/MATERIAL_implicit.csv and OUT/MATERIAL_explicit.csv (relative
density in %, pressure in MPa) and draws both methods per material.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out, picture = sys.argv[1], sys.argv[2]
materials = sys.argv[3].split() if len(sys.argv) > 3 else ["Sn", "Fe", "Cu"]
colours = {"Sn": "tab:blue", "Fe": "tab:red", "Cu": "tab:orange"}
figure, axes = plt.subplots(figsize=(6.4, 4.4))
for material in materials:
    for method, style in (("implicit", "-"), ("explicit", "--")):
        rows = list(csv.DictReader(open(f"{out}/{material}_{method}.csv")))
        axes.plot([float(r["relative_density_percent"]) for r in rows],
                  [float(r["pressure_MPa"]) for r in rows], style,
                  color=colours.get(material), label=f"{material} {method}")
axes.set_xlabel("relative density (%)")
axes.set_ylabel("upper punch pressure (MPa)")
axes.set_xlim(left=44)
axes.grid(True, alpha=0.3)
axes.legend()
figure.tight_layout()
figure.savefig(picture, dpi=110)
print("wrote", picture)
