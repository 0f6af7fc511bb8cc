#!/usr/bin/python3
"""The CSV of benchmarks/accuracy_cost.sh: one row per run, errors against the
scene's reference run (its first run).

Usage: accuracy_cost_table.py LIST SOURCE_ROOT > accuracy_cost.csv

LIST has one run per line: scene, label, run directory, exit code, scene
file, the run's own --set entries (';'-separated), tab-separated. Each run
directory holds statistics.csv and log.txt, DIR.time holds "wall user sys".
The shape's reference is the first run of the scene whose graphical output
is there (column shape_reference). Settings are the scene file's values with the run's entries applied, and
doc/parameters.prm's defaults for the rest.
"""

import csv
import math
import os
import re
import sys

STROKE_FRACTIONS = (0.25, 0.5, 0.75, 1.0)
SETTINGS = [("degree", "Mesh/Polynomial degree"),
            ("element_size", "Mesh/Element size"),
            ("refined_size", "Mesh/Refined element size"),
            ("locking_remedy", "Mesh/Volumetric locking remedy"),
            ("load_steps", "Time stepping/Number of steps"),
            ("newton_tolerance", "Solver/Newton tolerance"),
            ("linear_solver", "Solver/Linear solver"),
            ("penalty_factor", "Contact/Penalty factor"),
            ("friction_model", "Contact/Friction model"),
            ("method", "Solver/Method"),
            ("explicit_steps_set", "Explicit/Number of steps")]
COLUMNS = (["scene", "label", "status"] + [c for c, _ in SETTINGS] +
           ["dofs", "wall_s", "core_s", "newton_iterations", "load_steps_done", "cutbacks",
            "explicit_steps", "stroke_mm"] +
           [f"F{int(100 * f)}_N" for f in STROKE_FRACTIONS] +
           ["density_percent", "volume_change_percent", "section_area_mm2", "edges_match"] +
           [f"err_F{int(100 * f)}_percent" for f in STROKE_FRACTIONS] +
           ["err_force_percent", "err_density_pp", "err_volume_pp", "err_section_percent",
            "err_edges", "shape_reference"])


def read_prm(path):
    """{"Sub/Name": value} of the set lines of a parameter file."""
    values, section = {}, []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line.startswith("subsection "):
                section.append(line[len("subsection "):].strip())
            elif line == "end" and section:
                section.pop()
            elif line.startswith("set ") and "=" in line:
                name, value = line[4:].split("=", 1)
                values["/".join(section + [name.strip()])] = value.strip()
    return values


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def at_stroke(rows, stroke, column="upper_punch_force"):
    """column interpolated at punch_displacement = stroke (nan beyond the run)."""
    points = [(0.0, 0.0)] + [(number(r["punch_displacement"]), number(r[column])) for r in rows]
    for (sa, fa), (sb, fb) in zip(points, points[1:]):
        if sa <= stroke + 1e-12 and stroke <= sb + 1e-12 and sb > sa:
            w = min(max((stroke - sa) / (sb - sa), 0.0), 1.0)
            return (1 - w) * fa + w * fb
    return math.nan


def shape(directory):
    """(mean mid-height section area, particles whose straight section edges
    equal their contact neighbours, or nan for one particle) at the last
    output step; (nan, nan) without VTK or output."""
    try:
        sys.path.insert(0, os.path.join(ROOT, "scripts", "postprocess"))
        import edges
        from results import load_grid, read_csv, select_steps, warped
        from sections import extract_particle, mid_height_section, particle_ids, polygon_area
        step, path = select_steps(directory, -1)[0]
        grid = warped(load_grid(path))
        partners = {}
        particles_csv = os.path.join(directory, "particles.csv")
        if os.path.isfile(particles_csv):
            for r in read_csv(particles_csv):
                if int(r["step"]) == step:
                    partners[int(r["particle"])] = r.get("contact_partners", "")
        areas, match, ids = [], 0, particle_ids(grid)
        for p in ids:
            _, polygon = mid_height_section(extract_particle(grid, p))
            if polygon is None:
                continue
            import numpy as np
            areas.append(polygon_area(np.column_stack([polygon, np.zeros(len(polygon))])))
            n = edges.count_straight_edges(polygon)
            k = number(partners.get(p))
            if not math.isnan(k) and n == int(k):
                match += 1
        mean_area = sum(areas) / len(areas) if areas else math.nan
        return mean_area, (match if len(ids) > 1 else math.nan)
    except Exception as exc:  # noqa: BLE001 - a missing module or output leaves it empty
        print(f"accuracy_cost_table.py: no shape for {directory}: {exc}", file=sys.stderr)
        return math.nan, math.nan


def run_row(scene, label, directory, status, scene_file, sets, defaults):
    settings = dict(defaults)
    settings.update(read_prm(scene_file))
    # the entries a Scene/Fidelity level set (those the file and --set left
    # unset), as the run's banner lists them
    log = open(directory + ".log", errors="replace").read()
    m = re.search(r"^Fidelity: \S+ \((.*)\)$", log, re.M)
    if m:
        for entry in m.group(1).split(", "):
            if " = " in entry:
                name, value = entry.split(" = ", 1)
                settings[name.strip()] = value.strip()
    for entry in filter(None, sets.split(";")):
        name, value = entry.split("=", 1)
        settings[name.strip()] = value.strip()
    row = {"scene": scene, "label": label, "status": "ok" if status == "0" else f"exit {status}"}
    for column, entry in SETTINGS:
        row[column] = settings.get(entry, "")
    stats = os.path.join(directory, "statistics.csv")
    rows = list(csv.DictReader(open(stats))) if os.path.isfile(stats) else []
    wall, user, system = (number(t) for t in open(directory + ".time").read().split()[-3:])
    row["wall_s"], row["core_s"] = wall, user + system
    m = re.search(r"(\d+) DoFs", log)
    row["dofs"] = int(m.group(1)) if m else ""
    row["newton_iterations"] = sum(int(r["newton_iterations"]) for r in rows)
    row["load_steps_done"] = len(rows)
    row["cutbacks"] = sum(int(r["cutbacks"]) for r in rows)
    row["explicit_steps"] = int(number(rows[-1]["explicit_steps"])) if rows and not math.isnan(
        number(rows[-1].get("explicit_steps"))) else 0
    row["stroke_mm"] = number(rows[-1]["punch_displacement"]) if rows else math.nan
    row["_rows"] = rows
    if rows:
        row["density_percent"] = 100 * number(rows[-1]["relative_density"])
        # the volume before the first step is not in the file: the change is
        # measured from step 1 (elastic, tiny)
        row["volume_change_percent"] = 100 * (number(rows[-1]["particle_volume"]) /
                                              number(rows[0]["particle_volume"]) - 1)
    else:
        row["density_percent"] = row["volume_change_percent"] = math.nan
    row["section_area_mm2"], row["edges_match"] = shape(directory) if rows else (math.nan, math.nan)
    return row


def relative(a, b):
    return 100 * abs(a - b) / abs(b) if b not in (0, None) and not math.isnan(b) else math.nan


def fmt(value):
    if isinstance(value, float):
        return "" if math.isnan(value) else f"{value:.6g}"
    return str(value)


def main():
    global ROOT
    listing, ROOT = sys.argv[1], sys.argv[2]
    defaults = read_prm(os.path.join(ROOT, "doc", "parameters.prm"))
    table = []
    for line in open(listing):
        fields = line.rstrip("\n").split("\t")
        if len(fields) == 6:
            table.append(run_row(*fields, defaults))
    references = {}
    for row in table:
        references.setdefault(row["scene"], row)
    for row in table:
        ref = references[row["scene"]]
        # the reference's own stroke (that of a run stopped early, too)
        stroke = ref["stroke_mm"]
        errors = []
        for f in STROKE_FRACTIONS:
            key = f"F{int(100 * f)}_N"
            row[key] = at_stroke(row["_rows"], f * stroke) if row["_rows"] else math.nan
            ref_value = at_stroke(ref["_rows"], f * stroke) if ref["_rows"] else math.nan
            row[f"err_F{int(100 * f)}_percent"] = relative(row[key], ref_value)
            errors.append(row[f"err_F{int(100 * f)}_percent"])
        row["err_force_percent"] = max(errors) if not any(math.isnan(e) for e in errors) else math.nan
        row["err_density_pp"] = abs(row["density_percent"] - ref["density_percent"])
        row["err_volume_pp"] = abs(row["volume_change_percent"] - ref["volume_change_percent"])
        # the shape needs the graphical output, which a run may lack: its
        # reference is the first run of the scene that has it
        shaped = [r for r in table if r["scene"] == row["scene"] and
                  not math.isnan(r["section_area_mm2"])]
        shape_ref = shaped[0] if shaped else ref
        row["shape_reference"] = shape_ref["label"]
        row["err_section_percent"] = relative(row["section_area_mm2"],
                                              shape_ref["section_area_mm2"])
        row["err_edges"] = abs(row["edges_match"] - shape_ref["edges_match"])
        if row["status"] != "ok" or row["stroke_mm"] < stroke - 1e-9:
            # a run that stopped short has no error at the stroke it missed
            row["err_force_percent"] = math.nan
    writer = csv.writer(sys.stdout, lineterminator="\n")
    writer.writerow(COLUMNS)
    for row in table:
        writer.writerow([fmt(row.get(c, "")) for c in COLUMNS])


ROOT = "."
if __name__ == "__main__":
    main()
