#!/usr/bin/python3
"""A short summary of a Densify run, printed to the terminal.

Usage: summary.py OUTPUT_DIR

Reads OUTPUT_DIR/statistics.csv (columns by name), particles.csv (for the
initial particle volume, when present) and log.txt (the run time of its
last "Finished N steps in T" line) and prints: steps and punch stroke, the
relative density after the first and the last step, the punch and die-wall
forces of the last step, the particle volume kept (last step against the
initial mesh volume), the run time, and the files of the directory that
the other scripts of scripts/postprocess/ write.
"""

import argparse
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import PostprocessError, fail, output_file, read_csv, to_float  # noqa: E402

NEEDED = ["step", "punch_displacement", "upper_punch_force", "lower_punch_force",
          "die_wall_force", "relative_density", "particle_volume"]


def initial_volume(directory, last_step):
    """Sum of initial_volume over the particles of the last step, or nan."""
    path = os.path.join(directory, "particles.csv")
    if not os.path.isfile(path):
        return math.nan
    rows = [r for r in read_csv(path) if r.get("step") == last_step]
    if not rows or "initial_volume" not in rows[0]:
        return math.nan
    return sum(to_float(r["initial_volume"]) for r in rows)


def run_time(directory):
    """The T of the last 'Finished N steps in T' line of log.txt, or None."""
    path = os.path.join(directory, "log.txt")
    if not os.path.isfile(path):
        return None
    found = None
    with open(path, errors="replace") as f:
        for line in f:
            match = re.match(r"Finished (\d+) steps in (\S+?);", line)
            if match:
                found = match.group(2)
    return found


def percent(value):
    return "nan" if math.isnan(value) else f"{100.0 * value:.2f} %"


def summary(directory):
    """The summary as a list of lines."""
    path = output_file(directory, "statistics.csv")
    rows = read_csv(path)
    missing = [c for c in NEEDED if c not in rows[0]]
    if missing:
        raise PostprocessError(f"'{path}' lacks the column(s) {', '.join(missing)}")
    first, last = rows[0], rows[-1]
    v0 = initial_volume(directory, last["step"])
    v_first = to_float(first["particle_volume"])
    v_last = to_float(last["particle_volume"])
    reference = v0 if not math.isnan(v0) else v_first
    kept = v_last / reference if reference > 0 else math.nan
    lines = [
        f"Densify run in {directory}",
        f"  load steps:        {last['step']}, punch stroke {to_float(last['punch_displacement']):.4g} mm",
        f"  relative density:  {percent(to_float(first['relative_density']))} after step "
        f"{first['step']}, {percent(to_float(last['relative_density']))} at the end",
        f"  forces at the end: upper punch {to_float(last['upper_punch_force']):.1f} N, "
        f"lower punch {to_float(last['lower_punch_force']):.1f} N, "
        f"die wall {to_float(last['die_wall_force']):.1f} N",
        f"  particle volume:   {percent(kept)} of the initial "
        f"{'mesh volume' if not math.isnan(v0) else 'volume after step ' + first['step']} kept "
        f"({v_last:.4g} mm^3)",
    ]
    time = run_time(directory)
    lines.append(f"  run time:          {time if time else 'unknown (no Finished line in log.txt)'}")
    files = [("statistics.csv", "one row per load step"),
             ("particles.csv", "one row per particle and step"),
             ("solution.pvd", "open in ParaView"),
             ("density.png", "relative density against stroke"),
             ("forces.png", "punch and die-wall forces against stroke"),
             ("view_top.png", "the compact from above"),
             ("view_oblique.png", "the compact from the side")]
    tables = sorted(f for f in os.listdir(directory) if re.match(r"particle_table_\d+\.csv$", f))
    if tables:
        files.append((tables[-1], "per-particle table of the last output step"))
    lines.append("  files:")
    for name, what in files:
        if os.path.exists(os.path.join(directory, name)):
            lines.append(f"    {os.path.join(directory, name)}  ({what})")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", help="Densify output directory (Output/Directory)")
    args = parser.parse_args()
    try:
        lines = summary(args.directory)
    except PostprocessError as exc:
        fail(str(exc))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
