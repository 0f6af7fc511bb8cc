"""Newton iterations per load step of one or more implicit runs.

Usage: /usr/bin/python3 benchmarks/newton_iterations_plot.py PICTURE.png LABEL=statistics.csv...
draws each run's `newton_iterations` against its step, marks the steps
retried with the pseudo-transient continuation (`continuations`) and those
cut back (`cutbacks`), and prints per run the steps, the Newton iterations
in all, the largest step and the continuations and cut-backs.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

picture = sys.argv[1]
figure, axes = plt.subplots(figsize=(7.0, 4.2))
for argument in sys.argv[2:]:
    label, path = argument.split("=", 1)
    rows = list(csv.DictReader(open(path)))
    steps = [int(r["step"]) for r in rows]
    newton = [int(r["newton_iterations"]) for r in rows]
    retried = [(s, n) for s, n, r in zip(steps, newton, rows)
               if int(r["continuations"]) > 0]
    cut = [(s, n) for s, n, r in zip(steps, newton, rows)
           if int(r["cutbacks"]) > 0]
    line, = axes.plot(steps, newton, "-", lw=1, label=label)
    if retried:
        axes.plot(*zip(*retried), "o", color=line.get_color(), mfc="none",
                  label=f"{label}: continuation")
    if cut:
        axes.plot(*zip(*cut), "x", color=line.get_color(),
                  label=f"{label}: cut back")
    print(f"{label}: steps {steps[0]}-{steps[-1]}, Newton iterations "
          f"{sum(newton)}, largest {max(newton)} (step "
          f"{steps[newton.index(max(newton))]}), continuations "
          f"{len(retried)}, cut-backs {len(cut)}")
axes.set_xlabel("load step")
axes.set_ylabel("Newton iterations")
axes.set_yscale("log")
axes.grid(True, alpha=0.3)
axes.legend(fontsize="small")
figure.tight_layout()
figure.savefig(picture, dpi=110)
