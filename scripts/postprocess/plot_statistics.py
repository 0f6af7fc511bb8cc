#!/usr/bin/python3
"""Density and punch-force curves of a Densify run.

Usage: plot_statistics.py OUTPUT_DIR [--out DIR]

Reads OUTPUT_DIR/statistics.csv (columns by name, so appended columns do
not matter) and writes into OUTPUT_DIR (or --out):

  curves.csv   stroke_mm, relative_density_percent, upper_punch_force_N,
               lower_punch_force_N, die_wall_force_N (one row per load step)
  density.png  relative density (%) against punch stroke (mm)
  forces.png   upper punch, lower punch and die-wall forces (N) against stroke
  compaction.png  relative density against the upper punch's mean stress
               (MPa), and the Heckel plot ln(1/(1 - D)) against it with the
               line Densify's summary fits over the upper half of the
               pressure range (only for runs with a die and both punches)
  ejection.png the ejection curve of a press cycle: the lower punch's force
               (N) against its rise in the die (mm; lower_punch_displacement
               - die_displacement) over the rows in the phase eject
               (only for runs that eject)
  contacts.png the mean coordination number and the contact area fraction
               (%) against relative density (only for runs in which
               particles touch, with a die)

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


def heckel_line(pressure, density):
    """Least-squares K, A of ln(1/(1 - D)) = K P + A over P >= half the largest
    (the fit of Densify's run summary), or None with fewer than 3 points."""
    top = max(pressure)
    points = [(p, math.log(1.0 / (1.0 - d))) for p, d in zip(pressure, density)
              if p > 0 and p >= 0.5 * top and 0 < d < 1]
    n = len(points)
    if n < 3:
        return None
    mx = sum(p for p, _ in points) / n
    my = sum(y for _, y in points) / n
    sxx = sum((p - mx) ** 2 for p, _ in points)
    if sxx <= 0:
        return None
    k = sum((p - mx) * (y - my) for p, y in points) / sxx
    return k, my - k * mx


def plot_compaction(directory, out_dir):
    """Write compaction.png; returns its name, or None if the run has no
    punch stresses (no die, or a statistics.csv without the column)."""
    rows = read_csv(output_file(directory, "statistics.csv"))
    if "upper_punch_stress" not in rows[0]:
        return None
    pressure = [to_float(r["upper_punch_stress"]) for r in rows]
    density = [to_float(r["relative_density"]) for r in rows]
    if any(math.isnan(v) for v in pressure + density):
        return None
    matplotlib = require("matplotlib", "python3-matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.5), dpi=120)
    left.plot(pressure, [100 * d for d in density], "o-", markersize=3)
    left.set_xlabel("upper punch stress (MPa)")
    left.set_ylabel("relative density (%)")
    left.set_title("Pressure and density")
    heckel = [math.log(1.0 / (1.0 - d)) if 0 < d < 1 else math.nan for d in density]
    right.plot(pressure, heckel, "o", markersize=3, label="run")
    line = heckel_line(pressure, density)
    if line:
        k, a = line
        ps = [p for p in pressure if p >= 0.5 * max(pressure)]
        right.plot([min(ps), max(ps)], [k * min(ps) + a, k * max(ps) + a], "-",
                   label=f"K = {k:.4g} 1/MPa, A = {a:.4g}")
        right.legend()
    right.set_xlabel("upper punch stress P (MPa)")
    right.set_ylabel("ln(1/(1 - D))")
    right.set_title("Heckel plot")
    for ax in (left, right):
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "compaction.png"))
    plt.close(fig)
    return "compaction.png"


def plot_ejection(directory, out_dir):
    """Write ejection.png; returns its name, or None if no row ejects (or
    the statistics.csv has no phase or lower punch rise)."""
    rows = read_csv(output_file(directory, "statistics.csv"))
    if "phase" not in rows[0] or "lower_punch_displacement" not in rows[0]:
        return None
    eject = [r for r in rows if to_float(r["phase"]) == 3]
    if not eject:
        return None
    matplotlib = require("matplotlib", "python3-matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # the lower punch's rise in the die (a lowered die ejects as well)
    rise = [to_float(r["lower_punch_displacement"])
            - (to_float(r["die_displacement"]) if "die_displacement" in r else 0.)
            for r in eject]
    force = [to_float(r["lower_punch_force"]) for r in eject]
    fig, ax = plt.subplots(figsize=(6, 4.5), dpi=120)
    ax.plot(rise, force, "o-", markersize=3)
    peak = max(range(len(force)), key=lambda i: force[i])
    ax.annotate(f"peak {force[peak]:.4g} N", (rise[peak], force[peak]),
                textcoords="offset points", xytext=(5, 5))
    ax.set_xlabel("lower punch rise in the die (mm)")
    ax.set_ylabel("lower punch force (N)")
    ax.set_ylim(bottom=0)
    ax.ticklabel_format(useOffset=False)
    ax.set_title("Ejection")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "ejection.png"))
    plt.close(fig)
    return "ejection.png"


def plot_contacts(directory, out_dir):
    """Write contacts.png (mean coordination number and contact area fraction
    against relative density); returns its name, or None if no two particles
    touch or the statistics.csv has no such columns or no density."""
    rows = read_csv(output_file(directory, "statistics.csv"))
    if "coordination_number" not in rows[0]:
        return None
    rows = [r for r in rows
            if not math.isnan(to_float(r["coordination_number"]))
            and not math.isnan(to_float(r["relative_density"]))]
    if not any(to_float(r["coordination_number"]) > 0 for r in rows):
        return None
    matplotlib = require("matplotlib", "python3-matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    density = [100 * to_float(r["relative_density"]) for r in rows]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.5), dpi=120)
    left.plot(density, [to_float(r["coordination_number"]) for r in rows],
              "o-", markersize=3)
    left.set_ylabel("mean coordination number")
    left.set_title("Contacts per particle")
    right.plot(density,
               [100 * to_float(r["contact_area_fraction"]) for r in rows],
               "o-", markersize=3)
    right.set_ylabel("contact area fraction (%)")
    right.set_title("Particle surface in contact")
    for ax in (left, right):
        ax.set_xlabel("relative density (%)")
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "contacts.png"))
    plt.close(fig)
    return "contacts.png"


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
        extras = [name for name in (plot_compaction(args.directory, out_dir),
                                    plot_ejection(args.directory, out_dir),
                                    plot_contacts(args.directory, out_dir)) if name]
    except PostprocessError as exc:
        fail(str(exc))
    n = len(curves["stroke_mm"])
    extra = "".join(f", {name}" for name in extras)
    print(f"wrote curves.csv, density.png, forces.png{extra} ({n} steps) into {out_dir}")


if __name__ == "__main__":
    main()
