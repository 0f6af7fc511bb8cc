"""Read Densify's output directory: CSV tables, the .pvd step list and the VTU meshes.

The VTK parts are imported lazily, so plot_statistics.py works without VTK.
Run the scripts with Debian's /usr/bin/python3 (python3-numpy,
python3-matplotlib, python3-vtk9; `bash scripts/setup.sh` installs them).
"""

import csv
import math
import os
import re
import sys
import xml.etree.ElementTree as ET


class PostprocessError(Exception):
    """An error to report as one line and exit non-zero."""


def fail(message):
    """Print a one-line error naming the script and exit with status 2."""
    print(f"{os.path.basename(sys.argv[0])}: error: {message}", file=sys.stderr)
    sys.exit(2)


def missing_module(exc, debian_package):
    """The one-line message for a failed import."""
    return (f"a Python module is missing ({exc}); install the Debian package "
            f"{debian_package} (bash scripts/setup.sh does) and run the script with "
            f"/usr/bin/python3 (now: {sys.executable})")


def require(module_name, debian_package):
    """Import a module or raise a PostprocessError naming the Debian package."""
    try:
        return __import__(module_name)
    except ImportError as exc:
        raise PostprocessError(missing_module(exc, debian_package)) from exc


def output_file(directory, name):
    """Path of a file in the output directory; PostprocessError when absent."""
    if not os.path.isdir(directory):
        raise PostprocessError(f"output directory '{directory}' does not exist")
    path = os.path.join(directory, name)
    if not os.path.isfile(path):
        raise PostprocessError(f"'{path}' does not exist")
    return path


def to_float(text):
    """Parse a CSV cell as float; empty or unparsable cells give nan."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def read_csv(path):
    """Read a CSV file with a header into a list of dicts (values as strings)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise PostprocessError(f"'{path}' has no data rows")
    return rows


def output_steps(directory):
    """Map step number -> .pvtu (or .vtu) path, from solution.pvd.

    The step number is the NNNNN of solution_NNNNN.pvtu (the load step).
    """
    pvd = output_file(directory, "solution.pvd")
    try:
        root = ET.parse(pvd).getroot()
    except ET.ParseError as exc:
        raise PostprocessError(f"'{pvd}' is not valid XML: {exc}") from exc
    steps = {}
    for dataset in root.iter("DataSet"):
        name = dataset.get("file", "")
        match = re.search(r"_(\d+)\.p?vtu$", name)
        if match:
            steps[int(match.group(1))] = os.path.join(directory, name)
    if not steps:
        raise PostprocessError(f"'{pvd}' lists no solution files")
    return steps


def select_steps(directory, step=None):
    """The (step, path) pairs to process: all, or the one asked for."""
    steps = output_steps(directory)
    if step is None:
        return sorted(steps.items())
    if step == -1:
        last = max(steps)
        return [(last, steps[last])]
    if step not in steps:
        raise PostprocessError(
            f"step {step} has no graphical output (available: {', '.join(map(str, sorted(steps)))})")
    return [(step, steps[step])]


def load_grid(path):
    """Read a .pvtu/.vtu into a merged vtkUnstructuredGrid (see merge_points)."""
    vtk = require("vtk", "python3-vtk9")
    if not os.path.isfile(path):
        raise PostprocessError(f"'{path}' does not exist")
    reader = (vtk.vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu")
              else vtk.vtkXMLUnstructuredGridReader())
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or grid.GetNumberOfCells() == 0:
        raise PostprocessError(f"'{path}' holds no cells")
    return merge_points(grid)


def merge_points(grid):
    """Give every cell a cell array particle_id and merge duplicated points.

    deal.II writes each cell (patch) with its own copies of the vertices, so
    neighbouring cells share no point ids and every face looks like a
    boundary face. Points at the same position in the same particle are
    merged here, so the surface filter finds the real particle surfaces.
    particle_id is read from the cell data, or from the point data (deal.II
    9.4 writes cell vectors as point data).
    """
    import numpy as np
    vtk = require("vtk", "python3-vtk9")
    from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy

    cells = grid.GetCells()
    offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
    connectivity = vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)
    n_cells = grid.GetNumberOfCells()
    cell_of_entry = np.repeat(np.arange(n_cells), np.diff(offsets))

    if grid.GetCellData().GetArray("particle_id") is not None:
        cell_particle = vtk_to_numpy(grid.GetCellData().GetArray("particle_id"))
    elif grid.GetPointData().GetArray("particle_id") is not None:
        point_particle = vtk_to_numpy(grid.GetPointData().GetArray("particle_id"))
        cell_particle = point_particle[connectivity[offsets[:-1]]]
    else:
        raise PostprocessError("the solution has no particle_id field")
    cell_particle = np.rint(cell_particle).astype(np.int64)

    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float64)
    point_particle = np.full(len(points), -1, dtype=np.int64)
    point_particle[connectivity] = cell_particle[cell_of_entry]
    size = max(float(np.ptp(points, axis=0).max()), 1e-30)
    key = np.column_stack([np.rint(points / (1e-6 * size)).astype(np.int64), point_particle])
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)

    merged = vtk.vtkUnstructuredGrid()
    new_points = vtk.vtkPoints()
    new_points.SetData(numpy_to_vtk(points[first], deep=True))
    merged.SetPoints(new_points)
    cell_array = vtk.vtkCellArray()
    cell_array.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
                       numpy_to_vtkIdTypeArray(inverse[connectivity], deep=True))
    cell_types = vtk_to_numpy(grid.GetCellTypesArray()).astype(np.uint8)
    merged.SetCells(numpy_to_vtk(cell_types, deep=True,
                                 array_type=vtk.VTK_UNSIGNED_CHAR), cell_array)
    point_data = grid.GetPointData()
    for i in range(point_data.GetNumberOfArrays()):
        array = point_data.GetArray(i)
        name = array.GetName()
        if name in ("particle_id", "mpi_rank"):
            continue
        values = vtk_to_numpy(array)[first]
        new = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
        new.SetName(name)
        merged.GetPointData().AddArray(new)
    particle = numpy_to_vtk(cell_particle.astype(np.int32), deep=True)
    particle.SetName("particle_id")
    merged.GetCellData().AddArray(particle)
    return merged


def point_array(grid, name):
    """A point field as a numpy array, or None when the grid has no such field."""
    from vtk.util.numpy_support import vtk_to_numpy
    array = grid.GetPointData().GetArray(name)
    return None if array is None else vtk_to_numpy(array)


def warped(grid, scale=1.0):
    """The grid moved by its displacement field (the deformed configuration)."""
    vtk = require("vtk", "python3-vtk9")
    if grid.GetPointData().GetArray("displacement") is None:
        raise PostprocessError("the solution has no displacement field")
    grid.GetPointData().SetActiveVectors("displacement")
    warp = vtk.vtkWarpVector()
    warp.SetInputData(grid)
    warp.SetScaleFactor(scale)
    warp.Update()
    return warp.GetOutput()
