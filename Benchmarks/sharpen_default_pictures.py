"""Before/after pictures of Surface Shock Sharpen's default flow time (docs/sharpening.md,
"Choosing the flow time").

    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython Benchmarks/sharpen_default_pictures.py \\
        [OUTPUT_FOLDER] [--plugin PATH/ShockFilters.so] [--cad DIR]

Three panels per picture: the blurred input, Surface Shock Sharpen with the
defaults at the former default FlowTime 64, and with nothing but Input= (the
default, 256); each triangle coloured by its normal, so that a rounded crease
is a band of blended colours and a sharp one a clean line. Pictures, in
OUTPUT_FOLDER (default docs/images/):

- sharpen_default_cad.png: the CAD-like part of Examples/sharpen_blurred_cad.py
  (an L-shaped block with a slot, cells of side 1/24), blurred by windowed-sinc
  smoothing (20 iterations, pass band 0.005);
- sharpen_default_box.png: Box(1.6, 1, 0.8), cleaned, triangulated, subdivided 5
  times, its points moved onto the box rounded with radius 0.1 (about 4 to 8
  rows of triangles across each rounding), as Testing/Python/TestSharpenDefaults.py
  makes it;
- sharpen_default_fandisk.png, when DIR (default ~/.cache/shockfilters/cad, from
  Benchmarks/get_cad_meshes.sh) has fandisk.off: CGAL's fandisk, subdivided once
  linearly and blurred as sharpen_eval.py's sinc2 (its normal error falls
  from 7.1 to 0.77 x at t = 64, 0.50 x at 256).
"""
import argparse
import os
import sys

from paraview import simple

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(REPO, "Examples"))
import shock_example  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("output", nargs="?", default=os.path.join(REPO, "docs", "images"))
parser.add_argument("--plugin", default=os.environ.get(shock_example.PLUGIN_VARIABLE, shock_example.DEFAULT_PLUGIN))
parser.add_argument("--cad", default=os.path.join(os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")),
                                                  "shockfilters", "cad"))
parser.add_argument("--size", type=int, nargs=2, default=[1500, 520], metavar=("WIDTH", "HEIGHT"))
arguments = parser.parse_args()
simple.LoadPlugin(arguments.plugin, remote=False)
os.makedirs(arguments.output, exist_ok=True)

# The part of Examples/sharpen_blurred_cad.py, as its script makes it.
with open(os.path.join(REPO, "Examples", "sharpen_blurred_cad.py")) as example:
    PART = example.read().split("PART = r'''")[1].split("'''")[0]

ROUNDED = '''
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
half, r = np.array([0.8, 0.5, 0.4]), 0.1
x = dsa.WrapDataObject(inputs[0].VTKObject).Points
nearest = np.clip(x, -(half - r), half - r)
away = x - nearest
length = np.linalg.norm(away, axis=1)[:, None]
output.Points = nearest + r * away / np.where(length > 0, length, 1)
'''

SINC2 = '''
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkTriangleFilter, vtkWindowedSincPolyDataFilter
from vtkmodules.vtkFiltersModeling import vtkLinearSubdivisionFilter
clean = vtkCleanPolyData()
clean.SetInputData(inputs[0].VTKObject)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(clean.GetOutputPort())
finer = vtkLinearSubdivisionFilter()
finer.SetInputConnection(triangles.GetOutputPort())
finer.SetNumberOfSubdivisions(1)
blur = vtkWindowedSincPolyDataFilter()
blur.SetInputConnection(finer.GetOutputPort())
blur.SetNumberOfIterations(20)
blur.SetPassBand(0.005)
blur.NormalizeCoordinatesOn()
blur.FeatureEdgeSmoothingOff()
blur.BoundarySmoothingOn()
blur.Update()
self.GetPolyDataOutput().ShallowCopy(blur.GetOutput())
'''


def three_panels(blurred, path, camera, title):
    former = simple.SurfaceShockSharpen(Input=blurred, FlowTime=64)
    default = simple.SurfaceShockSharpen(Input=blurred)
    layout = simple.CreateLayout(title)
    views = []
    panels = [(blurred, title), (former, "t = 64 (former default)"),
              (default, "defaults (t = %g)" % default.FlowTime)]
    for cell, (proxy, text) in zip([1, 5, 6], panels):
        view = simple.CreateView("RenderView")
        view.OrientationAxesVisibility = 0
        view.Background = [1, 1, 1]
        view.UseColorPaletteForBackground = 0
        views.append((cell, view, proxy, text))
    layout.SplitHorizontal(0, 1.0 / 3.0)
    layout.SplitHorizontal(2, 0.5)
    for cell, view, proxy, text in views:
        simple.AssignViewToLayout(view=view, layout=layout, hint=cell)
        shock_example.show_normal_colours(proxy, view)
        label = simple.Show(simple.Text(Text=text), view)
        label.WindowLocation = "Upper Center"
        label.FontSize = 15
        label.Bold = 1
        label.Color = [0.1, 0.1, 0.1]
    first = views[0][1]
    camera(first)
    for _, view, _, _ in views:
        view.CameraPosition = first.CameraPosition
        view.CameraFocalPoint = first.CameraFocalPoint
        view.CameraViewUp = first.CameraViewUp
        view.CameraParallelScale = first.CameraParallelScale
        simple.Render(view)
    simple.SaveScreenshot(path, layout, SaveAllViews=1, ImageResolution=list(arguments.size), SeparatorWidth=4,
                          SeparatorColor=[0.6, 0.6, 0.6])
    print("wrote", path)


part = simple.ProgrammableSource(OutputDataSetType="vtkPolyData", Script=PART)
three_panels(part, os.path.join(arguments.output, "sharpen_default_cad.png"),
             shock_example.looking_from([1.6, -1.9, 2.2], [0, 0, 1]), "Blurred CAD part")

box = simple.Subdivide(Input=simple.Triangulate(Input=simple.Clean(Input=simple.Box(XLength=1.6, YLength=1.0,
                                                                                   ZLength=0.8))),
                       NumberofSubdivisions=5)
rounded = simple.ProgrammableFilter(Input=box, Script=ROUNDED)
three_panels(rounded, os.path.join(arguments.output, "sharpen_default_box.png"),
             shock_example.looking_from([2.4, 2.6, 3.2], [0, 1, 0]), "Rounded box (r = 0.1)")

fandisk = os.path.join(arguments.cad, "fandisk.off")
if os.path.exists(fandisk):
    blurred = simple.ProgrammableFilter(Input=simple.OpenDataFile(fandisk), Script=SINC2)
    three_panels(blurred, os.path.join(arguments.output, "sharpen_default_fandisk.png"),
                 shock_example.looking_from([1.5, -2.0, 1.2], [0, 0, 1]), "fandisk, sinc2 blur")
else:
    print("no %s (Benchmarks/get_cad_meshes.sh): fandisk skipped" % fandisk)
