"""Per-particle geometry of a deformed compact: mid-height sections and field statistics.

All functions take the merged grid of results.load_grid (cell array
particle_id, shared points), already warped by the displacement where the
deformed shape is wanted.
"""

import numpy as np

from results import require


def particle_ids(grid):
    """The particle ids present in the grid, sorted."""
    from vtk.util.numpy_support import vtk_to_numpy
    return sorted(int(p) for p in np.unique(vtk_to_numpy(grid.GetCellData().GetArray("particle_id"))))


def extract_particle(dataset, particle):
    """The cells of one particle (by the cell array particle_id) as an unstructured grid."""
    vtk = require("vtk", "python3-vtk9")
    threshold = vtk.vtkThreshold()
    threshold.SetInputData(dataset)
    threshold.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS, "particle_id")
    threshold.SetLowerThreshold(particle - 0.5)
    threshold.SetUpperThreshold(particle + 0.5)
    threshold.SetThresholdFunction(vtk.vtkThreshold.THRESHOLD_BETWEEN)
    threshold.Update()
    return threshold.GetOutput()


def surface(dataset):
    """The boundary surface of a (merged) volume mesh as linear triangles."""
    vtk = require("vtk", "python3-vtk9")
    surf = vtk.vtkDataSetSurfaceFilter()
    surf.SetInputData(dataset)
    surf.SetNonlinearSubdivisionLevel(2)
    surf.Update()
    tri = vtk.vtkTriangleFilter()
    tri.SetInputConnection(surf.GetOutputPort())
    tri.Update()
    return tri.GetOutput()


def mid_height(dataset):
    """Mid-height of a particle: the middle of its z extent, (z_min + z_max) / 2."""
    z_min, z_max = dataset.GetBounds()[4:6]
    return 0.5 * (z_min + z_max)


def section_loops(surf, z):
    """Closed loops (each an (n, 3) array, in order) where the plane at height z cuts a surface."""
    vtk = require("vtk", "python3-vtk9")
    from vtk.util.numpy_support import vtk_to_numpy
    plane = vtk.vtkPlane()
    plane.SetOrigin(0.0, 0.0, z)
    plane.SetNormal(0.0, 0.0, 1.0)
    cutter = vtk.vtkCutter()
    cutter.SetInputData(surf)
    cutter.SetCutFunction(plane)
    clean = vtk.vtkCleanPolyData()
    clean.SetInputConnection(cutter.GetOutputPort())
    clean.SetTolerance(1e-7)
    stripper = vtk.vtkStripper()
    stripper.SetInputConnection(clean.GetOutputPort())
    stripper.JoinContiguousSegmentsOn()
    stripper.Update()
    out = stripper.GetOutput()
    if out.GetNumberOfPoints() == 0:
        return []
    points = vtk_to_numpy(out.GetPoints().GetData())
    lines = out.GetLines()
    offsets = vtk_to_numpy(lines.GetOffsetsArray())
    connectivity = vtk_to_numpy(lines.GetConnectivityArray())
    loops = []
    for a, b in zip(offsets[:-1], offsets[1:]):
        ids = connectivity[a:b]
        if len(ids) >= 4 and ids[0] == ids[-1]:
            loops.append(points[ids[:-1]].astype(float))
    return loops


def polygon_area(loop):
    """Absolute area of a closed loop projected on the xy plane."""
    x, y = loop[:, 0], loop[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)))


def mid_height_section(particle_mesh):
    """(z, polygon) of one deformed particle: its largest loop cut at mid-height.

    polygon is an (n, 2) array of x, y in order, or None when the cut gives
    no closed loop.
    """
    z = mid_height(particle_mesh)
    loops = section_loops(surface(particle_mesh), z)
    if not loops:
        return z, None
    largest = max(loops, key=polygon_area)
    return z, largest[:, :2]


def integrate(particle_mesh, field):
    """(volume, integral of the point field) over one particle's cells.

    vtkIntegrateAttributes sums signed cell volumes; the signs are flipped
    when the cells are inverted, assuming one orientation for all cells of a
    particle (deal.II writes them so).
    """
    vtk = require("vtk", "python3-vtk9")
    integrator = vtk.vtkIntegrateAttributes()
    integrator.SetInputData(particle_mesh)
    integrator.Update()
    out = integrator.GetOutput()
    volume_array = out.GetCellData().GetArray("Volume")
    volume = volume_array.GetValue(0) if volume_array is not None else 0.0
    integral = None
    if field is not None and out.GetPointData().GetArray(field) is not None:
        integral = out.GetPointData().GetArray(field).GetValue(0)
    if volume < 0:
        volume = -volume
        integral = None if integral is None else -integral
    return volume, integral
