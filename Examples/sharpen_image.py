"""Sharpen a blurred colour picture with Image Shock Advection.

    pvpython Examples/sharpen_image.py [OUTPUT_FOLDER] [--plugin PATH/ShockFilters.so]

(under a headless machine: xvfb-run -a pvpython ...). Builds a synthetic RGB
picture (a disc, a square and stripes with hard edges), blurs it with a
Gaussian, sharpens the blurred picture with the ShockFilters plugin and
writes OUTPUT_FOLDER/sharpen_image.png (default examples-output/) with the
blurred and the sharpened picture side by side. All three colour channels
share one flow, so the edges stay aligned and do not fringe.
"""
import os

from paraview import simple

import shock_example

arguments = shock_example.start(__doc__.splitlines()[0])

# The picture: hard-edged shapes, then a Gaussian blur of 2.5 pixels, made
# with numpy in a Programmable Source (256 x 192 pixels, 3 components in [0, 1]).
picture = simple.ProgrammableSource(OutputDataSetType="vtkImageData")
picture.ScriptRequestInformation = """
from paraview import util
util.SetOutputWholeExtent(self, [0, 255, 0, 191, 0, 0])
"""
picture.Script = """
import numpy as np
from vtkmodules.util import numpy_support
nx, ny, sigma = 256, 192, 2.5
y, x = np.mgrid[0:ny, 0:nx].astype(float)
rgb = np.zeros((ny, nx, 3))
rgb[..., :] = 0.08                                                  # dark background
disc = (x - 80) ** 2 + (y - 100) ** 2 < 55 ** 2
rgb[disc] = [0.9, 0.2, 0.15]                                        # red disc
square = (abs(x - 175) < 45) & (abs(y - 85) < 45)
rgb[square] = [0.2, 0.55, 0.95]                                     # blue square
stripes = (y > 150) & (np.floor(x / 16) % 2 == 0)
rgb[stripes] = [0.95, 0.85, 0.2]                                    # yellow stripes
rgb[disc & square] = [0.75, 0.3, 0.85]                              # purple overlap
radius = int(3 * sigma)
kernel = np.exp(-0.5 * (np.arange(-radius, radius + 1) / sigma) ** 2)
kernel /= kernel.sum()
for axis in (0, 1):                                                 # separable Gaussian blur
    padded = np.pad(rgb, [(radius, radius) if a == axis else (0, 0) for a in range(3)], mode="edge")
    rgb = sum(kernel[k] * np.take(padded, range(k, k + rgb.shape[axis]), axis=axis)
              for k in range(len(kernel)))
output = self.GetOutput()
output.SetExtent(0, nx - 1, 0, ny - 1, 0, 0)
colours = numpy_support.numpy_to_vtk(rgb.reshape(-1, 3).copy(), deep=1)
colours.SetName("Colour")
output.GetPointData().SetScalars(colours)
"""

sharp = simple.ImageShockAdvection(Input=picture)
sharp.InputArray = ["POINTS", "Colour"]
sharp.FlowTime = 4096.0       # long enough for a blur of a few pixels to become an edge
sharp.SmoothingPasses = 1


def show(proxy, view):
    display = simple.Show(proxy, view)
    display.SetRepresentationType("Slice")
    simple.ColorBy(display, ("POINTS", "Colour"))
    display.MapScalars = 0    # the three components are the colour itself
    display.Interpolation = "Flat"


def camera(view):
    view.InteractionMode = "2D"
    view.CameraPosition = [127.5, 95.5, 600]
    view.CameraFocalPoint = [127.5, 95.5, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 106


shock_example.before_after(picture, sharp, show, os.path.join(arguments.output, "sharpen_image.png"),
                           arguments.size, camera, ("Blurred picture", "Image Shock Advection"))
