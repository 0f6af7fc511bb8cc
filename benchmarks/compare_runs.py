#!/usr/bin/env python3
"""Two runs of one scene side by side at their common stations.

Usage: python3 benchmarks/compare_runs.py RUN/statistics.csv FINER/statistics.csv [EVERY]

For every EVERY-th station (default 16) that both files hold at the same
punch displacement, and the last: the upper punch force of each, the first
run's force relative to the second's, the relative density of each and their
difference in percentage points, and the smallest cell volume ratio of each.
Then the largest relative force difference over the stations where the
second run's force is at least a tenth of its last (below, the forces of a
loose bed are a few newtons and their ratios mean little). doc/accuracy.md uses it for the explicit
step-count lever.
"""
import csv
import sys


def read(path):
    with open(path) as f:
        return {int(r["step"]): r for r in csv.DictReader(f)}


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    a, b = read(sys.argv[1]), read(sys.argv[2])
    every = int(sys.argv[3]) if len(sys.argv) > 3 else 16
    common = [s for s in sorted(a) if s in b and
              abs(float(a[s]["punch_displacement"]) -
                  float(b[s]["punch_displacement"])) < 1e-9]
    if not common:
        sys.exit("compare_runs.py: no common stations")
    floor = 0.1 * float(b[common[-1]]["upper_punch_force"])
    print("step  punch_mm  F_a_N  F_b_N  F_a/F_b-1_%  density_a_%  density_b_%"
          "  diff_pp  min_V/V0_a  min_V/V0_b")
    worst = (0., None)
    for s in common:
        ra, rb = a[s], b[s]
        fa, fb = float(ra["upper_punch_force"]), float(rb["upper_punch_force"])
        rel = 100. * (fa / fb - 1.) if fb != 0. else float("nan")
        if fb >= floor and abs(rel) > abs(worst[0]):
            worst = (rel, s)
        if s % every == 0 or s == common[-1]:
            da = 100. * float(ra["relative_density"])
            db = 100. * float(rb["relative_density"])
            print(f"{s:4d}  {float(ra['punch_displacement']):7.3f}  {fa:9.1f}  {fb:9.1f}"
                  f"  {rel:+7.2f}  {da:7.2f}  {db:7.2f}  {da - db:+6.2f}"
                  f"  {float(ra['min_cell_volume_ratio']):.3f}  {float(rb['min_cell_volume_ratio']):.3f}")
    print(f"largest force difference where the second force is above a tenth"
          f" of its last ({floor:.1f} N): {worst[0]:+.2f} % at step {worst[1]}")


if __name__ == "__main__":
    main()
