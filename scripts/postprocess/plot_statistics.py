#!/usr/bin/python3
"""Density and punch-force curves of a Densify run.

Usage: plot_statistics.py OUTPUT_DIR [--out DIR]

Reads OUTPUT_DIR/statistics.csv (columns by name, so appended columns do
not matter) and writes into OUTPUT_DIR (or --out):

  curves.csv   stroke_mm, relative_density_percent, upper_punch_force_N,
               lower_punch_force_N, die_wall_force_N (one row per load step)
  density.png  relative density (%) against punch stroke (mm)
  forces.png   upper punch, lower punch and die-wall forces (N) against stroke

Stroke is the column punch_displacement (downward travel of the upper
punch). relative_density is nan when the scene has no die; the density plot
then says so instead of drawing a curve.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import PostprocessError, fail, output_file, read_csv, require, to_float  # noqa: E402

NEEDED = ["punch_displacement", "upper_punch_force", "lower_punch_force", "die_wall_force",
          "relative_density"]


def read_curves(directory):
    """The curves as a dict of lists: stroke (mm), density (%), forces (N)."""
    path = output_file(directory, "statistics.csv")
    rows = read_csv(path)
    missing = [c for c in NEEDED if c not in rows[0]]
    if missing:
        raise PostprocessError(f"'{path}' lacks the column(s) {', '.join(missing)}")
    curves = {
        "stroke_mm": [to_float(r["punch_displacement"]) for r in rows],
        "relative_density_percent": [100.0 * to_float(r["relative_density"]) for r in rows],
        "upper_punch_force_N": [to_float(r["upper_punch_force"]) for r in rows],
        "lower_punch_force_N": [to_float(r["lower_punch_force"]) for r in rows],
        "die_wall_force_N": [to_float(r["die_wall_force"]) for r in rows],
    }
    return curves


def write_csv(curves, path):
    """Write the curves as CSV, one row per load step."""
    names = list(curves)
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for values in zip(*(curves[n] for n in names)):
            f.write(",".join("nan" if math.isnan(v) else f"{v:.10g}" for v in values) + "\n")


def plot(curves, out_dir):
    """Write density.png and forces.png."""
    matplotlib = require("matplotlib", "python3-matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    stroke = curves["stroke_mm"]
    density = curves["relative_density_percent"]
    fig, ax = plt.subplots(figsize=(6, 4.5), dpi=120)
    if all(math.isnan(d) for d in density):
        ax.text(0.5, 0.5, "no relative density\n(the scene has no die or punches)",
                ha="center", va="center", transform=ax.transAxes)
    else:
        ax.plot(stroke, density, "o-", color="tab:blue", markersize=3)
    ax.set_xlabel("punch stroke (mm)")
    ax.set_ylabel("relative density (%)")
    ax.set_title("Relative density")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "density.png"))
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4.5), dpi=120)
    for key, label, style in [("upper_punch_force_N", "upper punch", "o-"),
                              ("lower_punch_force_N", "lower punch", "s--"),
                              ("die_wall_force_N", "die wall (axial)", "^:")]:
        ax.plot(stroke, curves[key], style, label=label, markersize=3)
    ax.set_xlabel("punch stroke (mm)")
    ax.set_ylabel("force (N)")
    ax.set_title("Punch and die-wall forces")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "forces.png"))
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", help="Densify output directory (Output/Directory)")
    parser.add_argument("--out", help="directory for the CSV and PNGs (default: OUTPUT_DIR)")
    args = parser.parse_args()
    try:
        curves = read_curves(args.directory)
        out_dir = args.out or args.directory
        os.makedirs(out_dir, exist_ok=True)
        write_csv(curves, os.path.join(out_dir, "curves.csv"))
        plot(curves, out_dir)
    except PostprocessError as exc:
        fail(str(exc))
    n = len(curves["stroke_mm"])
    print(f"wrote curves.csv, density.png, forces.png ({n} steps) into {out_dir}")


if __name__ == "__main__":
    main()
