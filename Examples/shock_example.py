"""Shared plumbing of the pvpython examples (sharpen_*.py): command line,
plugin loading and the side-by-side before/after screenshot.

Not an example by itself; the scripts import it from their own folder.
"""
import argparse
import os
import sys

from paraview import simple

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_PLUGIN = os.path.join(REPO, "build", "lib", "paraview-5.11", "plugins", "ShockFilters",
                              "ShockFilters.so")
PLUGIN_VARIABLE = "SHOCK_FILTERS_PLUGIN"


def start(description):
    """Parse the command line, load the plugin, return (arguments, output folder)."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("output", nargs="?", default="examples-output",
                        help="folder for the PNG screenshot (default: examples-output/)")
    parser.add_argument("--plugin", default=os.environ.get(PLUGIN_VARIABLE, DEFAULT_PLUGIN),
                        help="path of ShockFilters.so (default: $%s, else %s)"
                             % (PLUGIN_VARIABLE, os.path.relpath(DEFAULT_PLUGIN, REPO)))
    parser.add_argument("--size", type=int, nargs=2, default=[1200, 560], metavar=("WIDTH", "HEIGHT"),
                        help="screenshot size in pixels (default: 1200 560)")
    arguments = parser.parse_args()
    if not os.path.isfile(arguments.plugin):
        sys.exit("ShockFilters plugin not found at %s: build the project (cmake -S . -B build && "
                 "cmake --build build), or give its path with --plugin or $%s."
                 % (arguments.plugin, PLUGIN_VARIABLE))
    simple.LoadPlugin(arguments.plugin, remote=False)
    os.makedirs(arguments.output, exist_ok=True)
    return arguments


def _label(view, text):
    title = simple.Text(Text=text)
    display = simple.Show(title, view)
    display.WindowLocation = "Upper Center"
    display.FontSize = 22
    display.Bold = 1
    display.Color = [0.1, 0.1, 0.1]


def show_normal_colours(proxy, view):
    """Show a surface with each triangle coloured by its normal (x, y, z as red,
    green, blue): a rounded edge is a band of blended colours, a sharp crease a
    clean line."""
    normals = simple.GenerateSurfaceNormals(Input=proxy, ComputeCellNormals=1, Splitting=0)
    rgb = simple.Calculator(Input=normals, AttributeType="Cell Data", ResultArrayName="NormalColour",
                            Function="0.5*Normals + 0.5*(iHat + jHat + kHat)")
    display = simple.Show(rgb, view)
    simple.ColorBy(display, ("CELLS", "NormalColour"))
    display.MapScalars = 0    # the three components are the colour itself
    display.Ambient = 0.4
    display.Diffuse = 0.7


def looking_from(position, view_up, dolly=1.0):
    """A camera(view) for before_after: from `position` towards the origin, the
    data fitted, then moved closer by `dolly`."""
    def camera(view):
        view.CameraPosition = position
        view.CameraFocalPoint = [0, 0, 0]
        view.CameraViewUp = view_up
        simple.ResetCamera(view)
        if dolly != 1.0:
            view.GetActiveCamera().Dolly(dolly)
    return camera


def before_after(before, after, show, path, size, camera=None, titles=("Before", "After")):
    """Render `before` and `after` side by side in two linked views and save
    one PNG. `show(proxy, view)` displays a proxy in a view (colouring etc.);
    `camera(view)` places the camera (default: reset to the data)."""
    layout = simple.CreateLayout("Before and after")
    views = []
    for cell, (proxy, text) in zip([1, 2], [(before, titles[0]), (after, titles[1])]):
        view = simple.CreateView("RenderView")
        view.OrientationAxesVisibility = 0
        view.Background = [1, 1, 1]
        view.UseColorPaletteForBackground = 0
        if cell == 1:
            layout.SplitHorizontal(0, 0.5)
        simple.AssignViewToLayout(view=view, layout=layout, hint=cell)
        show(proxy, view)
        _label(view, text)
        views.append(view)
    if camera:
        camera(views[0])
    else:
        simple.ResetCamera(views[0])
    simple.AddCameraLink(views[0], views[1], "before-after")
    for view in views:
        view.CameraPosition = views[0].CameraPosition
        view.CameraFocalPoint = views[0].CameraFocalPoint
        view.CameraViewUp = views[0].CameraViewUp
        view.CameraParallelScale = views[0].CameraParallelScale
        view.CameraParallelProjection = views[0].CameraParallelProjection
        simple.Render(view)
    simple.SaveScreenshot(path, layout, SaveAllViews=1, ImageResolution=list(size), SeparatorWidth=4,
                          SeparatorColor=[0.6, 0.6, 0.6])
    print("wrote", path)
