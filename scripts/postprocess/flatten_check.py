#!/usr/bin/python3
"""Check the edge counter on a run's real sphere meshes, flattened onto k planes.

Usage: flatten_check.py OUTPUT_DIR [--step N] [--apothem A] [--planes K ...]

Until particle-particle contact flattens real particles, this is the check
of the section path on the solver's own meshes: every point of each particle
is moved (in x, y only) inside k vertical planes at distance A * R from the
particle's axis (R: its radius, A default 0.85), like a particle pressed by k
neighbours, replacing the run's displacement. The mid-height section is then
counted (edges.py defaults) and must have k edges. Prints one line per k and
exits 1 when a count differs.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import PostprocessError, fail, load_grid, require, select_steps, warped  # noqa: E402


def flattening(points, owner, particles, planes, apothem):
    """Displacement moving each particle's points inside `planes` planes at apothem * R."""
    np = require("numpy", "python3-numpy")
    displacement = np.zeros_like(points)
    for particle in particles:
        mine = owner == particle
        xy = points[mine, :2]
        centre = 0.5 * (xy.min(axis=0) + xy.max(axis=0))
        radius = 0.5 * (xy[:, 0].max() - xy[:, 0].min())
        moved = xy - centre
        for j in range(planes):
            angle = 2 * math.pi * j / planes + 0.2
            normal = np.array([math.cos(angle), math.sin(angle)])
            moved -= np.clip(moved @ normal - apothem * radius, 0, None)[:, None] * normal
        displacement[mine, :2] = moved - (xy - centre)
    return displacement


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", help="Densify output directory (Output/Directory)")
    parser.add_argument("--step", type=int, default=-1, help="output step (default: the last)")
    parser.add_argument("--apothem", type=float, default=0.85,
                        help="distance of the planes from the axis, in radii (default 0.85)")
    parser.add_argument("--planes", type=int, nargs="+", default=[3, 4, 5, 6, 7, 8],
                        help="numbers of planes to try (default 3 4 5 6 7 8)")
    args = parser.parse_args()
    try:
        np = require("numpy", "python3-numpy")
        require("vtk", "python3-vtk9")
        from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
        import edges
        from sections import extract_particle, mid_height_section, particle_ids

        (step, path), = select_steps(args.directory, args.step)
        grid = load_grid(path)
        points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
        owner = np.full(len(points), -1)
        cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
        offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray())
        cell_particle = vtk_to_numpy(grid.GetCellData().GetArray("particle_id"))
        owner[cells] = np.repeat(cell_particle, np.diff(offsets))
        particles = particle_ids(grid)
        wrong = 0
        for k in args.planes:
            array = numpy_to_vtk(flattening(points, owner, particles, k, args.apothem), deep=True)
            array.SetName("displacement")
            grid.GetPointData().AddArray(array)
            deformed = warped(grid)
            counts = []
            for particle in particles:
                _, polygon = mid_height_section(extract_particle(deformed, particle))
                counts.append(None if polygon is None else edges.count_straight_edges(polygon))
            wrong += sum(c != k for c in counts)
            print(f"step {step}, {k} planes at {args.apothem:g} R: edges {counts}")
    except PostprocessError as exc:
        fail(str(exc))
    sys.exit(1 if wrong else 0)


if __name__ == "__main__":
    main()
