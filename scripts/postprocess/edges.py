"""Count the straight edges of a closed planar polygon (numpy only).

The paper's finding to test: after compaction, the mid-height cross-section
of each particle is a polygon whose number of straight edges equals its
number of contact neighbours. A section cut from a tetrahedral mesh is itself
a polygon with many short facets, often with noise, so "straight edge" needs
a definition that ignores facets and noise:

1. Deviations smaller than ``noise * R`` (R = sqrt(area / pi), the
   equivalent radius; default noise 0.02) are removed by a Douglas-Peucker
   simplification of the closed curve.
2. The simplified curve is resampled at equal arc-length steps of
   ``smoothing * perimeter`` (default 0.01); each step is a chord.
3. The chord directions are grouped greedily into runs: a run grows while the
   spread (largest minus smallest direction) of its chords stays within
   ``angle_tolerance`` degrees (default 10). The scan starts just after the
   sharpest turn, so no run is split by the start point.
4. A run is a straight edge when its length is at least
   ``min_edge_fraction * perimeter`` (default 0.08, i.e. 8 %).

With the defaults a circle has no edge (the simplification turns it into a
polygon of chords 6.4 % of the perimeter long that turn by 23 degrees, so no
run reaches 8 %), a regular polygon with up to 12 sides (8.3 % each) has all
its edges, and rounded corners do not add edges. Facets of a coarse mesh
can count as edges when single facets come close to 8 % of the perimeter.
The defaults were
chosen by a sweep over synthetic shapes described in doc/postprocessing.md.
"""

import math

import numpy as np

DEFAULT_ANGLE_TOLERANCE = 10.0
DEFAULT_MIN_EDGE_FRACTION = 0.08
DEFAULT_SMOOTHING = 0.01
DEFAULT_NOISE = 0.02


def _clean(points):
    """Return the polygon as an (n, 2) float array without repeated points."""
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] < 2 or len(p) < 3:
        raise ValueError("a polygon needs at least 3 points of 2 coordinates")
    p = p[:, :2]
    if np.allclose(p[0], p[-1]):
        p = p[:-1]
    scale = np.ptp(p, axis=0).max()
    step = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)
    p = p[step > 1e-12 * max(scale, 1e-300)]
    if len(p) < 3:
        raise ValueError("the polygon is degenerate")
    return p


def signed_area(points):
    """Signed area of a closed polygon (positive when counter-clockwise)."""
    p = _clean(points)
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def perimeter(points):
    """Length of the closed polygon."""
    p = _clean(points)
    return float(np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1).sum())


def resample(points, n):
    """Return n points at equal arc-length steps along the closed polygon."""
    p = _clean(points)
    closed = np.vstack([p, p[:1]])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(closed, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], n, endpoint=False)
    return np.column_stack([np.interp(t, s, closed[:, 0]), np.interp(t, s, closed[:, 1])])


def _simplify_open(p, eps):
    """Douglas-Peucker simplification of an open polyline; keeps both ends."""
    keep = np.zeros(len(p), dtype=bool)
    keep[0] = keep[-1] = True
    stack = [(0, len(p) - 1)]
    while stack:
        a, b = stack.pop()
        if b - a < 2:
            continue
        d = p[b] - p[a]
        length = math.hypot(d[0], d[1])
        rel = p[a + 1:b] - p[a]
        if length > 0:
            dist = np.abs(rel[:, 0] * d[1] - rel[:, 1] * d[0]) / length
        else:
            dist = np.linalg.norm(rel, axis=1)
        k = int(np.argmax(dist))
        if dist[k] > eps:
            m = a + 1 + k
            keep[m] = True
            stack += [(a, m), (m, b)]
    return p[keep]


def simplify(points, eps):
    """Douglas-Peucker simplification of a closed polygon with tolerance eps."""
    p = _clean(points)
    far = int(np.argmax(np.linalg.norm(p - p[0], axis=1)))
    first = _simplify_open(p[:far + 1], eps)
    second = _simplify_open(np.vstack([p[far:], p[:1]]), eps)
    return np.vstack([first, second[1:-1]])


def straight_runs(points, angle_tolerance=DEFAULT_ANGLE_TOLERANCE,
                  smoothing=DEFAULT_SMOOTHING, noise=DEFAULT_NOISE):
    """Split the closed polygon into runs of nearly parallel chords.

    Returns a list of (fraction_of_perimeter, mean_direction_degrees), one per
    run, in order along the curve (counter-clockwise).
    """
    p = _clean(points)
    if signed_area(p) < 0:
        p = p[::-1]
    if noise > 0:
        radius = math.sqrt(abs(signed_area(p)) / math.pi)
        p = simplify(p, noise * radius)
    n = max(12, int(math.ceil(1.0 / smoothing)))
    q = resample(p, n)
    d = np.roll(q, -1, axis=0) - q
    angle = np.arctan2(d[:, 1], d[:, 0])
    turn = np.angle(np.exp(1j * (np.roll(angle, -1) - angle)))  # turn after chord i
    start = (int(np.argmax(np.abs(turn))) + 1) % n
    order = [(start + k) % n for k in range(n)]
    # direction of each chord relative to the first one, unwrapped along the curve
    rel = np.concatenate([[0.0], np.cumsum(turn[order][:-1])])
    tol = math.radians(angle_tolerance)
    runs, first, lo, hi = [], 0, rel[0], rel[0]
    for k in range(1, n):
        lo2, hi2 = min(lo, rel[k]), max(hi, rel[k])
        if hi2 - lo2 > tol:
            runs.append((first, k))
            first, lo2, hi2 = k, rel[k], rel[k]
        lo, hi = lo2, hi2
    runs.append((first, n))
    result = []
    for a, b in runs:
        mean = math.degrees(angle[order[a]] + float(np.mean(rel[a:b] - rel[a])))
        result.append(((b - a) / n, (mean + 180.0) % 360.0 - 180.0))
    return result


def count_straight_edges(points, angle_tolerance=DEFAULT_ANGLE_TOLERANCE,
                         min_edge_fraction=DEFAULT_MIN_EDGE_FRACTION,
                         smoothing=DEFAULT_SMOOTHING, noise=DEFAULT_NOISE):
    """Number of straight edges of a closed polygon given as ordered 2D points.

    points: (n, 2) (or (n, 3), z ignored) vertices in order along the curve,
    either orientation, the closing point may be repeated.
    angle_tolerance: largest spread of direction (degrees) along one edge.
    min_edge_fraction: shortest edge as a fraction of the perimeter.
    smoothing: resampling step as a fraction of the perimeter.
    noise: Douglas-Peucker tolerance as a fraction of the equivalent radius
    sqrt(area / pi); deviations below it are ignored (0 disables).
    """
    runs = straight_runs(points, angle_tolerance, smoothing, noise)
    return sum(1 for fraction, _ in runs if fraction >= min_edge_fraction - 1e-12)
