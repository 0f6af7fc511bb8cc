#!/usr/bin/python3
"""Per-particle table of a Densify run at each graphical output step.

Usage: particle_table.py OUTPUT_DIR [--step N] [--out DIR] [edge options]

Reads OUTPUT_DIR/solution.pvd (and its solution_NNNNN.pvtu) and
OUTPUT_DIR/particles.csv, and writes particle_table_NNNNN.csv with one row
per particle:

  particle            particle index (particle_id)
  contact_partners    particles in contact (particles.csv; empty until the solver writes it)
  die_contact         touches the die wall (particles.csv; empty until the solver writes it)
  volume              current volume, mm^3 (particles.csv, else the deformed mesh)
  mean_plastic_strain volume-weighted mean equivalent plastic strain (0 without plasticity)
  max_plastic_strain  largest nodal equivalent plastic strain (0 without plasticity)
  cross_section_edges straight edges of the mid-height section (edges.py), empty if no section
  section_z           height of the cut, mm: the middle of the particle's deformed z extent
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import (PostprocessError, fail, load_grid, missing_module,  # noqa: E402
                     output_file, point_array, read_csv, require, select_steps, to_float, warped)

try:
    import edges  # noqa: E402
except ImportError as error:
    fail(missing_module(error, "python3-numpy"))

COLUMNS = ["particle", "contact_partners", "die_contact", "volume", "mean_plastic_strain",
           "max_plastic_strain", "cross_section_edges", "section_z"]


def particle_rows(directory):
    """particles.csv as {(step, particle): row}, or {} when the file is absent."""
    path = os.path.join(directory, "particles.csv")
    if not os.path.isfile(path):
        return {}
    return {(int(r["step"]), int(r["particle"])): r for r in read_csv(path)}


def fmt(value):
    """Format a number for the table (empty for None/nan)."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def table_for_step(directory, step, path, csv_rows, edge_options):
    """The rows (lists of strings) of one output step."""
    require("numpy", "python3-numpy")
    import numpy as np
    from sections import extract_particle, integrate, mid_height_section, particle_ids

    grid = load_grid(path)
    strain = point_array(grid, "plastic_strain")
    deformed = warped(grid)
    rows = []
    for particle in particle_ids(deformed):
        mesh = extract_particle(deformed, particle)
        volume, integral = integrate(mesh, "plastic_strain" if strain is not None else None)
        if strain is not None and volume > 0:
            values = point_array(mesh, "plastic_strain")
            mean_strain, max_strain = integral / volume, float(np.max(values))
        else:
            mean_strain, max_strain = 0.0, 0.0
        z, polygon = mid_height_section(mesh)
        n_edges = None if polygon is None else edges.count_straight_edges(polygon, **edge_options)
        info = csv_rows.get((step, particle), {})
        csv_volume = to_float(info.get("volume"))
        if not math.isnan(csv_volume):
            volume = csv_volume
        rows.append([particle, info.get("contact_partners", ""), info.get("die_contact", ""),
                     volume, mean_strain, max_strain, n_edges, z])
    return [[fmt(v) for v in row] for row in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", help="Densify output directory (Output/Directory)")
    parser.add_argument("--step", type=int, help="only this output step (-1: the last one)")
    parser.add_argument("--out", help="directory for the tables (default: OUTPUT_DIR)")
    parser.add_argument("--angle-tolerance", type=float, default=edges.DEFAULT_ANGLE_TOLERANCE,
                        help="largest direction spread along one edge, degrees (default %(default)s)")
    parser.add_argument("--min-edge-fraction", type=float, default=edges.DEFAULT_MIN_EDGE_FRACTION,
                        help="shortest edge as a fraction of the perimeter (default %(default)s)")
    parser.add_argument("--noise", type=float, default=edges.DEFAULT_NOISE,
                        help="ignored deviation as a fraction of the equivalent radius "
                             "(default %(default)s)")
    args = parser.parse_args()
    options = {"angle_tolerance": args.angle_tolerance,
               "min_edge_fraction": args.min_edge_fraction, "noise": args.noise}
    try:
        output_file(args.directory, "solution.pvd")
        steps = select_steps(args.directory, args.step)
        csv_rows = particle_rows(args.directory)
        out_dir = args.out or args.directory
        os.makedirs(out_dir, exist_ok=True)
        for step, path in steps:
            rows = table_for_step(args.directory, step, path, csv_rows, options)
            name = os.path.join(out_dir, f"particle_table_{step:05d}.csv")
            with open(name, "w") as f:
                f.write(",".join(COLUMNS) + "\n")
                for row in rows:
                    f.write(",".join(row) + "\n")
            print(f"wrote {name} ({len(rows)} particles)")
    except PostprocessError as exc:
        fail(str(exc))


if __name__ == "__main__":
    main()
