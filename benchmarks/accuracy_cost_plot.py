#!/usr/bin/python3
"""Error against wall time from benchmarks/accuracy_cost.sh's CSV.

Usage: accuracy_cost_plot.py CSV [--out DIR] [--scenes a,b]

For each scene of the CSV writes DIR/accuracy_SCENE.png: one log-log panel
per error measure (punch force: the largest error at 25/50/75/100 % of the
stroke, and at the end of the stroke; final relative density; particle volume change; mid-height section
area; with several particles, the count of particles with as many straight
section edges as contact neighbours), every run a point, the Pareto front (no cheaper run is as accurate)
joined and labelled. Writes DIR/accuracy_fronts.md with a Markdown table of
each front and prints it. The scene's reference run (error 0 by definition)
is left out of the plots and tables; runs that failed or stopped short have
no error and are left out too. Errors below 1e-4 are drawn at 1e-4.
"""

import argparse
import csv
import math
import os
import sys

MEASURES = [("err_force_percent", "punch force error (%), largest of 25/50/75/100 % stroke"),
            ("err_F100_percent", "punch force error at the end of the stroke (%)"),
            ("err_density_pp", "final relative density error (percentage points)"),
            ("err_volume_pp", "particle volume change error (percentage points)"),
            ("err_section_percent", "mid-height section area error (%)"),
            ("err_edges", "particles with as many section edges as neighbours: difference")]
FLOOR = 1e-4


def fail(message):
    print(f"accuracy_cost_plot.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def pareto(points):
    """The runs no cheaper (or equally cheap) run beats in error, by time; a
    run joins only if it cuts the error by more than 1 % of it (equal
    answers from settings that change only the time are not a new point)."""
    front, best = [], math.inf
    for p in sorted(points, key=lambda p: (p["wall"], p["error"])):
        if p["error"] < 0.99 * best:
            front.append(p)
            best = p["error"]
    return front


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv", help="accuracy_cost.csv of benchmarks/accuracy_cost.sh")
    parser.add_argument("--out", default=".", help="directory for the PNGs and accuracy_fronts.md")
    parser.add_argument("--scenes", help="only these scenes (comma-separated)")
    args = parser.parse_args()
    if not os.path.isfile(args.csv):
        fail(f"no file '{args.csv}'")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("matplotlib is missing (Debian: apt-get install python3-matplotlib)")
    rows = list(csv.DictReader(open(args.csv)))
    if not rows or "err_force_percent" not in rows[0]:
        fail(f"'{args.csv}' has no runs of accuracy_cost.sh")
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    if args.scenes:
        scenes = [s for s in scenes if s in args.scenes.split(",")]
    os.makedirs(args.out, exist_ok=True)
    text = []
    for scene in scenes:
        runs = [r for r in rows if r["scene"] == scene]
        reference = runs[0]
        measures = [(key, title) for key, title in MEASURES
                    if any(not math.isnan(number(r[key])) for r in runs[1:])]
        if not measures:
            continue
        cols = 2 if len(measures) > 1 else 1
        nrows = (len(measures) + cols - 1) // cols
        fig, axes = plt.subplots(nrows, cols, figsize=(6.5 * cols, 4.8 * nrows), squeeze=False)
        for ax in axes.flat[len(measures):]:
            ax.set_visible(False)
        text.append(f"## {scene}: reference {reference['label']} "
                    f"({number(reference['wall_s']):.1f} s)\n")
        for ax, (key, title) in zip(axes.flat, measures):
            points = [{"wall": number(r["wall_s"]), "error": number(r[key]), "label": r["label"],
                       "row": r} for r in runs[1:] if r["status"] == "ok"]
            points = [p for p in points if not math.isnan(p["error"]) and not math.isnan(p["wall"])]
            if key in ("err_section_percent", "err_edges"):
                # the shape's own reference (a run without graphics cannot be)
                points = [p for p in points
                          if p["row"].get("shape_reference", "") != p["label"]]
            if not points:
                continue
            front = pareto(points)
            ax.loglog([p["wall"] for p in points], [max(p["error"], FLOOR) for p in points],
                      "o", color="0.6", label="runs")
            ax.loglog([p["wall"] for p in front], [max(p["error"], FLOOR) for p in front],
                      "o-", color="C3", label="Pareto front")
            for p in front:
                ax.annotate(p["label"], (p["wall"], max(p["error"], FLOOR)), fontsize=7,
                            xytext=(4, 4), textcoords="offset points")
            ax.set_xlabel("wall time (s, 1 rank)")
            ax.set_ylabel(title)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
            text.append(f"### {title}\n")
            text.append("| run | wall (s) | Newton iterations | error |")
            text.append("|---|---|---|---|")
            for p in front:
                text.append(f"| {p['label']} | {p['wall']:.1f} | {p['row']['newton_iterations']} | "
                            f"{p['error']:.3g} |")
            text.append("")
        fig.suptitle(f"{scene}: error against the reference ({reference['label']}) "
                     f"against wall time")
        fig.tight_layout()
        name = os.path.join(args.out, f"accuracy_{scene}.png")
        fig.savefig(name, dpi=90)
        plt.close(fig)
        print(f"wrote {name}", file=sys.stderr)
    markdown = "\n".join(text) + "\n"
    with open(os.path.join(args.out, "accuracy_fronts.md"), "w") as f:
        f.write(markdown)
    print(markdown)


if __name__ == "__main__":
    main()
