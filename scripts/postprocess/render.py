#!/usr/bin/python3
"""Off-screen pictures of the deformed compact, coloured by plastic strain.

Usage: render.py OUTPUT_DIR [--step N] [--out DIR] [--field NAME] [--scale S] [--size W H]

Reads the last graphical output step (or --step N) listed in
OUTPUT_DIR/solution.pvd, moves the mesh by its displacement (times --scale,
default 1: the true deformed shape), and writes view_top.png (looking down
the pressing axis) and view_oblique.png, each with a colour bar. The colour
is the equivalent plastic strain, or the von Mises stress when the run has
no plastic strain field (an elastic run), or --field.

Debian's VTK 9.1 renders through X only. Without a DISPLAY the script runs
itself again under xvfb-run (Debian packages xvfb and xauth).
"""

import argparse
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from results import PostprocessError, fail, load_grid, require, select_steps, warped  # noqa: E402

LABELS = {"plastic_strain": "equivalent plastic strain",
          "von_mises": "von Mises stress (MPa)",
          "pressure": "pressure (MPa)",
          "contact_pressure": "contact pressure (MPa)"}


def ensure_display():
    """Re-run this script under xvfb-run when there is no X display."""
    if os.environ.get("DISPLAY") or os.environ.get("DENSIFY_RENDER_NO_XVFB"):
        return
    xvfb = shutil.which("xvfb-run")
    if xvfb is None:
        raise PostprocessError("no X display and no xvfb-run: install the Debian packages "
                               "xvfb and xauth (bash scripts/setup.sh does) or set DISPLAY")
    env = dict(os.environ, DENSIFY_RENDER_NO_XVFB="1")
    command = [xvfb, "-a", "-s", "-screen 0 1600x1200x24", sys.executable] + sys.argv
    # VTK aborts (SIGABRT, exit 134) when it cannot connect to the X server
    # that xvfb-run started, which happens now and then on a loaded machine
    # (seen under ctest -j2): a fresh server is tried twice more
    for attempt in range(3):
        status = subprocess.call(command, env=env)
        if status != 134:
            break
        print(f"render.py: the virtual X server did not accept the connection "
              f"(attempt {attempt + 1} of 3)", file=sys.stderr)
    sys.exit(status)


def pick_field(grid, requested):
    """The point field to colour by."""
    names = [grid.GetPointData().GetArrayName(i) for i in range(grid.GetPointData().GetNumberOfArrays())]
    if requested:
        if requested not in names:
            raise PostprocessError(f"no point field '{requested}' (available: {', '.join(names)})")
        return requested
    for name in ("plastic_strain", "von_mises"):
        if name in names:
            return name
    raise PostprocessError("the solution has neither plastic_strain nor von_mises")


def build_scene(vtk, surf, field, title):
    """Renderers: the coloured surface with a caption (left), the colour bar (right)."""
    surf.GetPointData().SetActiveScalars(field)
    low, high = surf.GetPointData().GetArray(field).GetRange()
    if high <= low:
        high = low + 1e-12
    lut = vtk.vtkLookupTable()
    lut.SetHueRange(0.667, 0.0)
    lut.SetNumberOfTableValues(256)
    lut.SetTableRange(low, high)
    lut.Build()

    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(surf)
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray(field)
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(low, high)
    mapper.ScalarVisibilityOn()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)

    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(LABELS.get(field, field))
    bar.SetNumberOfLabels(5)
    bar.SetLabelFormat("%.3g")
    bar.SetOrientationToVertical()
    bar.SetPosition(0.1, 0.08)
    bar.SetWidth(0.8)
    bar.SetHeight(0.84)
    bar.UnconstrainedFontSizeOn()
    for prop in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        prop.SetColor(0.1, 0.1, 0.1)
        prop.SetFontSize(16)
        prop.ItalicOff()
        prop.ShadowOff()

    caption = vtk.vtkTextActor()
    caption.SetInput(title)
    caption.GetTextProperty().SetFontSize(18)
    caption.GetTextProperty().SetColor(0.1, 0.1, 0.1)
    caption.SetPosition(10, 10)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.SetViewport(0.0, 0.0, 0.8, 1.0)
    renderer.AddActor(actor)
    renderer.AddActor2D(caption)
    legend = vtk.vtkRenderer()
    legend.SetBackground(1.0, 1.0, 1.0)
    legend.SetViewport(0.8, 0.0, 1.0, 1.0)
    legend.AddActor2D(bar)
    return renderer, legend


def snapshot(vtk, renderers, size, path, elevation, azimuth, zoom):
    """Render one view off-screen and write it as PNG."""
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*size)
    for r in renderers:
        window.AddRenderer(r)
    renderer = renderers[0]
    camera = renderer.GetActiveCamera()
    bounds = renderer.ComputeVisiblePropBounds()
    centre = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]
    camera.SetFocalPoint(*centre)
    camera.SetPosition(centre[0], centre[1], centre[2] + 10.0)
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.Elevation(elevation)
    camera.Azimuth(azimuth)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera()
    camera.Zoom(zoom)
    renderer.ResetCameraClippingRange()
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.ReadFrontBufferOff()
    image.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    window.Finalize()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", help="Densify output directory (Output/Directory)")
    parser.add_argument("--step", type=int, default=-1, help="output step (default: the last)")
    parser.add_argument("--out", help="directory for the pictures (default: OUTPUT_DIR)")
    parser.add_argument("--field", help="point field to colour by (default: plastic_strain, "
                                        "else von_mises)")
    parser.add_argument("--scale", type=float, default=1.0, help="displacement scale (default 1)")
    parser.add_argument("--size", type=int, nargs=2, default=[1200, 900], metavar=("W", "H"),
                        help="picture size in pixels (default 1200 900)")
    args = parser.parse_args()
    try:
        (step, path), = select_steps(args.directory, args.step)
        vtk = require("vtk", "python3-vtk9")
        ensure_display()
        grid = load_grid(path)
        field = pick_field(grid, args.field)
        deformed = warped(grid, args.scale)
        surface_filter = vtk.vtkDataSetSurfaceFilter()
        surface_filter.SetInputData(deformed)
        surface_filter.SetNonlinearSubdivisionLevel(2)
        normals = vtk.vtkPolyDataNormals()
        normals.SetInputConnection(surface_filter.GetOutputPort())
        normals.SetFeatureAngle(60.0)
        normals.Update()
        surf = normals.GetOutput()
        out_dir = args.out or args.directory
        os.makedirs(out_dir, exist_ok=True)
        scale = "" if args.scale == 1.0 else f", displacement x{args.scale:g}"
        title = f"step {step}: {LABELS.get(field, field)}{scale}"
        for name, elevation, azimuth, zoom in [("view_top.png", 0.0, 0.0, 1.3),
                                               ("view_oblique.png", -55.0, 25.0, 1.0)]:
            renderers = build_scene(vtk, surf, field, title)
            snapshot(vtk, renderers, args.size, os.path.join(out_dir, name), elevation, azimuth,
                     zoom)
    except PostprocessError as exc:
        fail(str(exc))
    print(f"wrote view_top.png, view_oblique.png (step {step}, {field}) into {out_dir}")


if __name__ == "__main__":
    main()
