#!/usr/bin/env python3
"""Summarise a run's statistics.csv in blocks of load steps: step time,
Newton iterations, time per Newton iteration, cut-backs and the relative
density at the end of each block, then the totals.

Usage (from the source root):
  python3 benchmarks/step_blocks.py OUTPUT_DIR/statistics.csv [steps per block]

The block-by-block figures of doc/performance.md ("The paper's scene, block
by block") come from it, after
  mpirun -np 2 build/densify prm/single_layer_sn.prm --set Output/Directory=DIR
"""
import csv
import sys


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: step_blocks.py STATISTICS.csv [steps per block]")
    try:
        with open(sys.argv[1], newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"step_blocks.py: cannot read {sys.argv[1]}: {e.strerror}")
    if not rows:
        sys.exit(f"step_blocks.py: {sys.argv[1]} has no load steps")
    block = int(sys.argv[2]) if len(sys.argv) == 3 else 50
    if block < 1:
        sys.exit("step_blocks.py: the block size must be at least 1")

    print("| steps | relative density at the end | step time | Newton iterations "
          "| Newton per step | s per Newton iteration | cut-backs |")
    print("|---|---|---|---|---|---|---|")
    total_time = 0.0
    total_newton = 0
    for start in range(0, len(rows), block):
        part = rows[start:start + block]
        seconds = sum(float(r["step_seconds"]) for r in part)
        newton = [int(r["newton_iterations"]) for r in part]
        cutbacks = sum(int(r["cutbacks"]) for r in part)
        total_time += seconds
        total_newton += sum(newton)
        print(f"| {part[0]['step']}–{part[-1]['step']} "
              f"| {100 * float(part[-1]['relative_density']):.2f} % "
              f"| {seconds / 60:.1f} min | {sum(newton)} "
              f"| {min(newton)}–{max(newton)} "
              f"| {seconds / max(sum(newton), 1):.2f} | {cutbacks} |")
    print(f"\n{len(rows)} steps: {total_time / 60:.1f} min of step time, "
          f"{total_newton} Newton iterations "
          f"({total_time / max(total_newton, 1):.2f} s each); wall time at "
          f"the last step {float(rows[-1]['wall_seconds']) / 60:.1f} min")


if __name__ == "__main__":
    main()
