#!/usr/bin/python3
"""Several runs of the same scene side by side: density and punch force at equal strokes.

Usage: compare_runs.py DIR DIR [DIR ...] [--labels A,B,C] [--strokes 0.32,0.64,0.96]
                       [--reference LABEL] [--out DIR]

Reads DIR/statistics.csv of every run (columns by name) and prints a
Markdown table to stdout: for each stroke (mm) the relative density (%) and
the upper punch force (N) of every run, and the ratio of each run's upper
punch force to the reference run's (the first run, or --reference). Each
run's values are interpolated linearly in punch_displacement between the
first two consecutive rows that bracket the stroke; "-" marks a run that has
not reached the stroke (or a stroke below its first row). Below the table
one line per run: its last step, stroke, density, forces, the equilibrium
residual F_upper - F_lower - die_wall_force, the particle volume change
from the first row, total Newton iterations and total step_seconds.

Labels default to the directories' base names. Strokes default to about six
evenly spaced rows of the run with the shortest stroke plus its last row,
so every run has reached them. A run that is still being written is read up
to its last complete line.

With --out DIR it writes into DIR:

  comparison.csv       stroke_mm, density_percent_<label>..., upper_force_N_<label>...,
                       ratio_<label>... (non-reference runs), one row per stroke;
                       empty cell = not reached
  compare_density.png  relative density (%) of every run against stroke (mm)
  compare_forces.png   upper punch force (N) of every run against stroke (mm)
"""

import argparse
import csv
import io
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import PostprocessError, fail, output_file, require, to_float  # noqa: E402

NEEDED = ["step", "punch_displacement", "relative_density", "upper_punch_force",
          "lower_punch_force", "die_wall_force", "particle_volume", "newton_iterations",
          "step_seconds"]
DEFAULT_ROWS = 7  # default strokes: rows (n - 1) k / 7, k = 1..7, of the shortest run


class Run:
    """One run: its label, directory and statistics.csv columns as lists of floats."""

    def __init__(self, label, directory, columns):
        self.label = label
        self.directory = directory
        self.columns = columns
        self.stroke = columns["punch_displacement"]

    def max_stroke(self):
        """The furthest stroke the run has reached (mm)."""
        return max(self.stroke)

    def at(self, name, stroke):
        """Column `name` interpolated linearly at `stroke`; None when not covered.

        Uses the first pair of consecutive rows with s_i <= stroke <= s_i+1
        (the loading branch, should the stroke ever go back).
        """
        values = self.columns[name]
        if len(self.stroke) == 1:
            return values[0] if self.stroke[0] == stroke else None
        for i in range(len(self.stroke) - 1):
            a, b = self.stroke[i], self.stroke[i + 1]
            if a <= stroke <= b:
                if b == a:
                    return values[i + 1]
                t = (stroke - a) / (b - a)
                return values[i] + t * (values[i + 1] - values[i])
        return None


def read_statistics(directory):
    """The complete rows of DIR/statistics.csv as a dict of float lists (NEEDED columns).

    A last line without its newline (a run writing it right now) is left out.
    """
    if not os.path.isdir(directory):
        raise PostprocessError(f"run directory '{directory}' does not exist; give the "
                               "output directories (Output/Directory) of Densify runs")
    try:
        path = output_file(directory, "statistics.csv")
    except PostprocessError as exc:
        raise PostprocessError(f"{exc}; is '{directory}' the output directory "
                               "(Output/Directory) of a Densify run that has done a step?") from exc
    with open(path, newline="") as f:
        text = f.read()
    if text and not text.endswith("\n"):
        text = text[:text.rfind("\n") + 1]
    reader = csv.DictReader(io.StringIO(text))
    rows = list(reader)
    header = reader.fieldnames or []
    missing = [c for c in NEEDED if c not in header]
    if missing:
        raise PostprocessError(f"'{path}' lacks the column(s) {', '.join(missing)}; compare "
                               "runs whose statistics.csv has them (written by a current "
                               "Densify)")
    if not rows:
        raise PostprocessError(f"'{path}' has no complete data row; give runs that have "
                               "finished at least one step")
    columns = {c: [to_float(r[c]) for r in rows] for c in NEEDED}
    for number, stroke in enumerate(columns["punch_displacement"], start=2):
        if not math.isfinite(stroke):
            raise PostprocessError(f"'{path}' line {number}: punch_displacement is not a "
                                   "number; repair or truncate the file")
    return columns


def parse_labels(text, directories):
    """One label per directory: from --labels, else the directories' base names."""
    if text is None:
        labels = [os.path.basename(os.path.normpath(d)) for d in directories]
        source = "the directory base names"
    else:
        labels = [label.strip() for label in text.split(",")]
        source = "--labels"
        if len(labels) != len(directories):
            raise PostprocessError(
                f"--labels gives {len(labels)} label(s) for {len(directories)} run "
                f"directories; give one label per DIR, comma-separated, e.g. "
                f"--labels {','.join(chr(65 + i) for i in range(len(directories)))}")
        if any(not label for label in labels):
            raise PostprocessError(f"--labels '{text}' has an empty label; give one "
                                   "non-empty label per DIR, comma-separated")
    if len(set(labels)) != len(labels):
        raise PostprocessError(f"the labels ({', '.join(labels)}, from {source}) are not "
                               "unique; give distinct ones with --labels A,B,...")
    return labels


def parse_strokes(text):
    """The strokes (mm) of --strokes: comma-separated numbers >= 0."""
    strokes = []
    for item in text.split(","):
        value = to_float(item.strip())
        if not math.isfinite(value):
            raise PostprocessError(f"--strokes: '{item.strip()}' is not a number; give "
                                   "comma-separated strokes in mm, e.g. --strokes 0.32,0.64")
        if value < 0:
            raise PostprocessError(f"--strokes: {item.strip()} is negative; strokes are the "
                                   "upper punch's travel in mm, give values >= 0")
        strokes.append(value)
    return strokes


def default_strokes(runs):
    """About six evenly spaced rows of the run with the shortest stroke, plus its last row."""
    shortest = min(runs, key=Run.max_stroke)
    n = len(shortest.stroke)
    indices = sorted({round(k * (n - 1) / DEFAULT_ROWS) for k in range(1, DEFAULT_ROWS + 1)})
    return [shortest.stroke[i] for i in indices]


def check_strokes(strokes, runs):
    """PostprocessError for a stroke that no run has reached."""
    furthest = max(runs, key=Run.max_stroke)
    for stroke in strokes:
        if stroke > furthest.max_stroke():
            raise PostprocessError(
                f"--strokes: {stroke:g} mm is beyond every run (the furthest, "
                f"{furthest.label}, reached {furthest.max_stroke():g} mm); give strokes "
                f"up to {furthest.max_stroke():g}")


def compare(runs, strokes, reference):
    """Rows of the comparison: dicts with stroke, density, force and ratio per label."""
    table = []
    for stroke in strokes:
        row = {"stroke": stroke, "density": {}, "force": {}, "ratio": {}}
        for run in runs:
            density = run.at("relative_density", stroke)
            row["density"][run.label] = None if density is None else 100.0 * density
            row["force"][run.label] = run.at("upper_punch_force", stroke)
        base = row["force"][reference.label]
        for run in runs:
            if run is reference:
                continue
            force = row["force"][run.label]
            if force is None or base is None:
                row["ratio"][run.label] = None
            else:
                row["ratio"][run.label] = force / base if base != 0 else math.nan
        table.append(row)
    return table


def cell(value, digits):
    """A table cell: '-' for not reached, else the value with `digits` decimals."""
    if value is None:
        return "-"
    return "nan" if math.isnan(value) else f"{value:.{digits}f}"


def print_table(table, runs, reference):
    """Print the comparison as a Markdown table."""
    others = [r for r in runs if r is not reference]
    header = (["stroke (mm)"] + [f"density {r.label} (%)" for r in runs]
              + [f"F_upper {r.label} (N)" for r in runs]
              + [f"{r.label}/{reference.label}" for r in others])
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    not_reached = False
    for row in table:
        cells = ([f"{row['stroke']:.5g}"] + [cell(row["density"][r.label], 3) for r in runs]
                 + [cell(row["force"][r.label], 1) for r in runs]
                 + [cell(row["ratio"][r.label], 4) for r in others])
        not_reached |= "-" in cells
        print("| " + " | ".join(cells) + " |")
    print()
    print(f"F_upper: upper punch force; X/{reference.label}: F_upper of run X over F_upper of "
          f"the reference run {reference.label}.")
    if not_reached:
        print("-: the run has not reached this stroke (or it is below the run's first row).")


def summary(run):
    """One line about the run's last row and totals."""
    c = run.columns
    last = len(run.stroke) - 1
    upper, lower, wall = (c["upper_punch_force"][last], c["lower_punch_force"][last],
                          c["die_wall_force"][last])
    volume0, volume = c["particle_volume"][0], c["particle_volume"][last]
    change = 100.0 * (volume - volume0) / volume0 if volume0 else math.nan
    step = c["step"][last]
    step_text = f"{step:.0f}" if math.isfinite(step) else "nan"
    newton = sum(c["newton_iterations"])
    newton_text = f"{newton:.0f}" if math.isfinite(newton) else "nan"
    return (f"- {run.label} ({run.directory}): last step {step_text}, stroke "
            f"{run.stroke[last]:.5g} mm, density {100.0 * c['relative_density'][last]:.3f} %, "
            f"F_upper {upper:.1f} N, F_lower {lower:.1f} N, die wall {wall:.1f} N, "
            f"F_upper - F_lower - die wall = {upper - lower - wall:.3g} N, particle volume "
            f"{change:+.4f} % from the first row, {newton_text} Newton iterations, "
            f"{sum(c['step_seconds']):.1f} s of step_seconds")


def write_csv(table, runs, reference, path):
    """Write the table's numbers, one row per stroke; an empty cell means not reached."""
    others = [r for r in runs if r is not reference]
    names = (["stroke_mm"] + [f"density_percent_{r.label}" for r in runs]
             + [f"upper_force_N_{r.label}" for r in runs] + [f"ratio_{r.label}" for r in others])

    def text(value):
        """A CSV cell: empty for not reached."""
        if value is None:
            return ""
        return "nan" if math.isnan(value) else f"{value:.10g}"

    with open(path, "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(names)
        for row in table:
            writer.writerow([text(row["stroke"])] + [text(row["density"][r.label]) for r in runs]
                            + [text(row["force"][r.label]) for r in runs]
                            + [text(row["ratio"][r.label]) for r in others])


def plot(runs, strokes, out_dir):
    """Write compare_density.png and compare_forces.png (all runs against stroke)."""
    matplotlib = require("matplotlib", "python3-matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    for name, column, scale, ylabel, title in [
            ("compare_density.png", "relative_density", 100.0, "relative density (%)",
             "Relative density"),
            ("compare_forces.png", "upper_punch_force", 1.0, "upper punch force (N)",
             "Upper punch force")]:
        fig, ax = plt.subplots(figsize=(6, 4.5), dpi=120)
        for run in runs:
            values = [scale * v for v in run.columns[column]]
            ax.plot(run.stroke, values, "-", label=run.label, linewidth=1.5)
        for stroke in strokes:
            ax.axvline(stroke, color="0.8", linewidth=0.8, zorder=0)
        ax.set_xlabel("punch stroke (mm)")
        ax.set_ylabel(ylabel)
        ax.set_title(title)
        ax.grid(True, alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, name))
        plt.close(fig)


def attach_values(argv, options):
    """Join '--option VALUE' into '--option=VALUE' for the given options.

    argparse takes a value such as '-0.1,0.2' for an option name; joined, a
    negative stroke reaches parse_strokes and gets its own error message.
    """
    joined = []
    i = 0
    while i < len(argv):
        if argv[i] in options and i + 1 < len(argv):
            joined.append(f"{argv[i]}={argv[i + 1]}")
            i += 2
        else:
            joined.append(argv[i])
            i += 1
    return joined


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directories", nargs="+", metavar="DIR",
                        help="Densify output directories (Output/Directory), at least two")
    parser.add_argument("--labels", help="comma-separated run names (default: base names)")
    parser.add_argument("--strokes", help="comma-separated strokes in mm (default: about 6 "
                        "rows of the shortest run plus its last)")
    parser.add_argument("--reference", help="label of the run the force ratios refer to "
                        "(default: the first)")
    parser.add_argument("--out", help="directory for comparison.csv and the two PNGs")
    parser.error = lambda message: fail(f"{message} (see --help)")
    args = parser.parse_args(attach_values(sys.argv[1:], ("--labels", "--strokes",
                                                          "--reference", "--out")))
    try:
        if len(args.directories) < 2:
            raise PostprocessError(f"got {len(args.directories)} run directory; give at "
                                   "least two DIRs to compare")
        labels = parse_labels(args.labels, args.directories)
        strokes = parse_strokes(args.strokes) if args.strokes is not None else None
        runs = [Run(label, d, read_statistics(d)) for label, d in zip(labels, args.directories)]
        reference = runs[0]
        if args.reference is not None:
            matches = [r for r in runs if r.label == args.reference]
            if not matches:
                raise PostprocessError(f"--reference '{args.reference}' is none of the labels "
                                       f"({', '.join(labels)}); give one of them")
            reference = matches[0]
        if strokes is None:
            strokes = default_strokes(runs)
        else:
            check_strokes(strokes, runs)
        table = compare(runs, strokes, reference)
        if args.out:
            try:
                os.makedirs(args.out, exist_ok=True)
                write_csv(table, runs, reference, os.path.join(args.out, "comparison.csv"))
            except OSError as exc:
                raise PostprocessError(f"--out '{args.out}': cannot write there ({exc}); "
                                       "give a writable directory") from exc
            plot(runs, strokes, args.out)
    except PostprocessError as exc:
        fail(str(exc))
    print_table(table, runs, reference)
    print()
    for run in runs:
        print(summary(run))
    if args.out:
        print()
        print(f"wrote comparison.csv, compare_density.png, compare_forces.png "
              f"({len(strokes)} strokes) into {args.out}")


if __name__ == "__main__":
    main()
