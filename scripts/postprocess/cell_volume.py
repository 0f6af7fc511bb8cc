#!/usr/bin/python3
"""Cell volume ratios of a Densify run at each graphical output step.

Usage: cell_volume.py OUTPUT_DIR [--step N] [--worst K]

For each tetrahedron the ratio of its deformed to its initial volume,
V / V0 (the cell's own det F). The plastic metals are nearly incompressible,
so the material's volume change stays below a per cent; the nodal-averaged
F-bar element (doc/theory.md) gives the material the volume change averaged
over each vertex's patch, and lets a single cell's own volume drift far from
it. A cell whose ratio approaches zero is about to be inverted. Prints one
line per step (the smallest ratio, the cells below 0.5 and 0.7) and the K
worst cells of the last step with their particle and centre.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import (PostprocessError, fail, load_grid, point_array,  # noqa: E402
                     require, select_steps)


def volume_ratios(grid):
    """Per cell: (V / V0, particle id, deformed centre)."""
    np = require("numpy", "python3-numpy")
    from vtk.util.numpy_support import vtk_to_numpy
    X = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    u = point_array(grid, "displacement")
    if u is None:
        raise PostprocessError("the solution has no displacement field")
    u = u.astype(float)
    cells = grid.GetCells()
    conn = vtk_to_numpy(cells.GetConnectivityArray())
    offsets = vtk_to_numpy(cells.GetOffsetsArray())
    if len(offsets) < 2 or not np.all(np.diff(offsets) == 4):
        raise PostprocessError("the mesh is not made of linear tetrahedra only")
    conn = conn.reshape(-1, 4)

    def volumes(P):
        a, b, c, d = (P[conn[:, k]] for k in range(4))
        return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) / 6.

    ratio = volumes(X + u) / volumes(X)
    particle = vtk_to_numpy(grid.GetCellData().GetArray("particle_id"))
    centre = (X + u)[conn].mean(axis=1)
    return ratio, particle, centre


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory")
    parser.add_argument("--step", type=int, default=None,
                        help="only this output step (-1: the last)")
    parser.add_argument("--worst", type=int, default=5,
                        help="worst cells listed for the last step")
    args = parser.parse_args()
    np = require("numpy", "python3-numpy")
    try:
        steps = select_steps(args.directory, args.step)
        print("step  cells  min V/V0  cells V/V0<0.5  cells V/V0<0.7")
        for step, path in steps:
            ratio, particle, centre = volume_ratios(load_grid(path))
            print("%4d %6d %9.4f %15d %15d" % (step, len(ratio), ratio.min(),
                                               (ratio < 0.5).sum(),
                                               (ratio < 0.7).sum()))
        print("worst cells at step %d:" % steps[-1][0])
        for k in np.argsort(ratio)[:args.worst]:
            print("  V/V0 %.4f  particle %d  centre (%.3f, %.3f, %.3f) mm"
                  % (ratio[k], particle[k], *centre[k]))
    except PostprocessError as e:
        fail(str(e))


if __name__ == "__main__":
    main()
