#!/usr/bin/python3
"""The table of benchmarks/inertia_study.sh: the upper punch force of the
high-speed light layer at four strokes per punch speed, its difference from
the quasi-static (implicit) force, and the kinetic energy against the
internal work (KE/IE) of each explicit run, as a markdown table.

Usage (from the source root):
  /usr/bin/python3 benchmarks/inertia_table.py OUT_DIR [STROKES]

OUT_DIR is the output directory of benchmarks/inertia_study.sh: its
runs.txt (speed, directory, exit code, wall seconds, options; tab-separated)
and each run's statistics.csv. STROKES in mm, ','-separated (default
0.32,0.64,0.96,1.28). Forces are interpolated linearly between the stations
in the punch displacement. KE/IE: the largest ratio of kinetic energy to
internal work (elastic energy + plastic work) from 10 % of the stroke on
(before it the internal work is close to zero) and the ratio at the end.
Wall time: the run's own (wall_seconds of its last station), without the
time a run waited for a lock.
A run that stopped early shows its forces up to where it got and its error
line below the table.
"""

import csv
import os
import sys

import numpy as np


def read_runs(out):
    runs = []
    with open(os.path.join(out, "runs.txt")) as f:
        for line in f:
            if not line.strip():
                continue
            speed, name, rc, seconds, options = (line.rstrip("\n").split("\t") + [""] * 5)[:5]
            runs.append({"speed": speed, "dir": os.path.join(out, name), "rc": int(rc),
                         "seconds": float(seconds) if seconds else float("nan"),
                         "options": options})
    return runs


def read_statistics(directory):
    path = os.path.join(directory, "statistics.csv")
    if not os.path.exists(path):
        return {}
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return {}
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def force_at(stats, stroke):
    """Upper punch force at a stroke (mm), NaN beyond the last station."""
    s, f = stats["punch_displacement"], stats["upper_punch_force"]
    if stroke < s[0] or stroke > s[-1] + 1e-9:
        return float("nan")
    return float(np.interp(stroke, s, f))


def error_line(directory):
    path = os.path.join(directory, "run.log")
    if not os.path.exists(path):
        return ""
    with open(path) as f:
        lines = [l.strip() for l in f if "error" in l]
    return lines[0] if lines else ""


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: inertia_table.py OUT_DIR [STROKES]")
    out = sys.argv[1]
    strokes = [float(s) for s in (sys.argv[2] if len(sys.argv) == 3
                                  else "0.32,0.64,0.96,1.28").split(",")]
    try:
        runs = read_runs(out)
    except OSError as e:
        sys.exit(f"inertia_table.py: cannot read {out}/runs.txt: {e.strerror}")
    reference = [r for r in runs if r["speed"] == "quasi-static"]
    if not reference:
        sys.exit(f"inertia_table.py: {out}/runs.txt has no quasi-static run")
    qs = read_statistics(reference[0]["dir"])
    if not qs:
        sys.exit(f"inertia_table.py: the quasi-static run has no statistics.csv")
    f_qs = [force_at(qs, s) for s in strokes]
    speeds = sorted((r for r in runs if r["speed"] != "quasi-static"),
                    key=lambda r: float(r["speed"]))

    print("| punch speed (m/s) | " +
          " | ".join(f"F_upper at {s:g} mm (N)" for s in strokes) +
          " | largest KE/IE from 10 % of the stroke | KE/IE at the end | explicit steps | wall time |")
    print("|---" * (len(strokes) + 5) + "|")
    print("| quasi-static (implicit) | " +
          " | ".join(f"{f:,.1f}" for f in f_qs) +
          f" | – | – | – | {qs['wall_seconds'][-1]:.0f} s |")
    notes = []
    for r in speeds:
        st = read_statistics(r["dir"])
        label = r["speed"]
        extra = [o for o in r["options"].split(";") if o and not o.startswith("Explicit/Loading time")]
        if extra:
            label += " (" + ", ".join(extra) + ")"
        if r["rc"] != 0:
            label += " *"
            notes.append(f"{label}: exit {r['rc']} after "
                         f"{st['punch_displacement'][-1] if st else 0:.3g} mm: {error_line(r['dir'])}")
        cells = []
        for s, f0 in zip(strokes, f_qs):
            f = force_at(st, s) if st else float("nan")
            cells.append("–" if np.isnan(f) else f"{f:,.1f} ({100 * (f / f0 - 1):+.1f} %)".replace("-", "−"))
        if st:
            ratio = st["kinetic_energy"] / np.maximum(st["internal_work"], 1e-300)
            late = st["punch_displacement"] >= 0.1 * max(strokes)
            ke_max = f"{100 * ratio[late].max():.2g} %" if late.any() else "–"
            ke_end = f"{100 * ratio[-1]:.2g} %"
            steps = f"{int(st['explicit_steps'][-1]):,}"
            wall = f"{st['wall_seconds'][-1]:.0f} s"
        else:
            ke_max = ke_end = steps = wall = "–"
        print(f"| {label} | " + " | ".join(cells) +
              f" | {ke_max} | {ke_end} | {steps} | {wall} |")
    for n in notes:
        print(f"\n\\* {n}")


if __name__ == "__main__":
    main()
