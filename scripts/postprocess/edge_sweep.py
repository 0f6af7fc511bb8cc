#!/usr/bin/python3
"""Score edge-counter settings on synthetic polygons with known edge counts.

Usage: edge_sweep.py [--angle-tolerance T ...] [--min-edge-fraction F ...]
                     [--noise E ...] [--smoothing S ...] [--show N]

The shapes, for seeds 0-9 and Gaussian point noise sigma = 0, 0.002, 0.003,
0.004 R: a circle of 1000 points (0 edges), regular polygons with 4-8 sides
sampled with about 100 points per side, random convex pentagons, hexagons
and heptagons inscribed in the unit circle with every side at least 10 % of
the perimeter (sampled with 40 points per side); plus squares with rounded
corners (radius 0.05, 0.15, 0.3 of the side) and clean circles of 20, 26 and
40 points (sections of coarse sphere meshes). Prints, for every combination
of the given settings, the number of wrong counts and which shapes they hit,
best first. The defaults of edges.py came from this sweep.
"""

import argparse
import itertools
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import fail, missing_module  # noqa: E402

try:
    import numpy as np
    import edges
except ImportError as error:
    fail(missing_module(error, "python3-numpy"))


def sample(corners, per_side, sigma, seed):
    """Points along the sides of a closed polygon with Gaussian noise sigma."""
    corners = np.asarray(corners, dtype=float)
    t = np.arange(per_side)[:, None] / per_side
    points = np.vstack([a + (b - a) * t for a, b in zip(corners, np.roll(corners, -1, axis=0))])
    return points + sigma * np.random.default_rng(seed).standard_normal(points.shape)


def regular(n):
    a = 0.3 + 2 * np.pi * np.arange(n) / n
    return np.column_stack([np.cos(a), np.sin(a)])


def irregular(n, seed):
    """A random convex n-gon in the unit circle whose sides are all >= 10 % of the perimeter."""
    rng = np.random.default_rng(100 + seed)
    while True:
        a = np.sort(rng.uniform(0, 2 * np.pi, n))
        p = np.column_stack([np.cos(a), np.sin(a)])
        sides = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)
        if sides.min() / sides.sum() >= 0.1:
            return p


def circle(n, sigma=0.0, seed=0):
    a = 2 * np.pi * np.arange(n) / n
    r = 1 + sigma * np.random.default_rng(seed).standard_normal(n)
    return np.column_stack([r * np.cos(a), r * np.sin(a)])


def rounded_square(radius, per_corner=30):
    c = 0.5 - radius
    points = []
    for k, (cx, cy) in enumerate([(c, c), (-c, c), (-c, -c), (c, -c)]):
        for a in np.linspace(0, np.pi / 2, per_corner) + k * np.pi / 2:
            points.append((cx + radius * np.cos(a), cy + radius * np.sin(a)))
    return np.array(points)


def shapes():
    """(name, points, expected edge count) of every test shape."""
    cases = []
    for seed in range(10):
        for sigma in (0.0, 0.002, 0.003, 0.004):
            cases.append((f"circle sigma={sigma}", circle(1000, sigma, seed), 0))
            for n in (4, 5, 6, 7, 8):
                cases.append((f"regular {n}-gon sigma={sigma}", sample(regular(n), 480 // n, sigma, seed), n))
            for n in (5, 6, 7):
                cases.append((f"random {n}-gon sigma={sigma}", sample(irregular(n, seed), 40, sigma, seed), n))
    for radius in (0.05, 0.15, 0.3):
        cases.append((f"rounded square r={radius}", rounded_square(radius), 4))
    for n in (20, 26, 40):
        cases.append((f"circle of {n} points", circle(n), 0))
    return cases


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--angle-tolerance", type=float, nargs="+", default=[edges.DEFAULT_ANGLE_TOLERANCE])
    parser.add_argument("--min-edge-fraction", type=float, nargs="+", default=[edges.DEFAULT_MIN_EDGE_FRACTION])
    parser.add_argument("--noise", type=float, nargs="+", default=[edges.DEFAULT_NOISE])
    parser.add_argument("--smoothing", type=float, nargs="+", default=[edges.DEFAULT_SMOOTHING])
    parser.add_argument("--show", type=int, default=10, help="print the best N settings (default 10)")
    args = parser.parse_args()
    cases = shapes()
    results = []
    for tol, fraction, noise, smoothing in itertools.product(
            args.angle_tolerance, args.min_edge_fraction, args.noise, args.smoothing):
        wrong = {}
        for name, points, expected in cases:
            if edges.count_straight_edges(points, tol, fraction, smoothing, noise) != expected:
                wrong[name] = wrong.get(name, 0) + 1
        results.append((sum(wrong.values()), tol, fraction, noise, smoothing, wrong))
    results.sort(key=lambda r: r[0])
    print(f"{len(cases)} shapes")
    for n_wrong, tol, fraction, noise, smoothing, wrong in results[:args.show]:
        detail = ", ".join(f"{name}: {n}" for name, n in sorted(wrong.items())) or "-"
        print(f"angle_tolerance={tol:g} min_edge_fraction={fraction:g} noise={noise:g} "
              f"smoothing={smoothing:g}: {n_wrong} wrong ({detail})")


if __name__ == "__main__":
    main()
