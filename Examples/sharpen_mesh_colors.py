"""Sharpen blurred colours on a surface mesh with Surface Shock Advection.

    pvpython Examples/sharpen_mesh_colors.py [OUTPUT_FOLDER] [--plugin PATH/ShockFilters.so]

(under a headless machine: xvfb-run -a pvpython ...). Paints a blurred colour
pattern (smooth transitions between three colours) on a fine sphere,
sharpens it over the surface with the ShockFilters plugin and writes
OUTPUT_FOLDER/sharpen_mesh_colors.png (default examples-output/) with the
blurred and the sharpened colours side by side. The geometry is not changed:
only the per-vertex RGB array is advected along the surface.
"""
import os

from paraview import simple

import shock_example

arguments = shock_example.start(__doc__.splitlines()[0])

sphere = simple.Sphere(ThetaResolution=256, PhiResolution=128)
# Two smooth wave fields on the sphere give blurred bands and blobs; each
# becomes one colour channel (values in [0, 1], transitions a few edges wide).
colours = simple.Calculator(Input=sphere, ResultArrayName="Colour")
colours.Function = (
    "(0.5 + 0.5*tanh(3*sin(10*coordsX + 4*coordsY)))*iHat"
    " + (0.5 + 0.5*tanh(3*sin(9*coordsZ)*cos(7*coordsX)))*jHat"
    " + (0.35 + 0.3*tanh(3*sin(8*coordsY - 5*coordsZ)))*kHat")

sharp = simple.SurfaceShockAdvection(Input=colours)
sharp.InputArray = ["POINTS", "Colour"]
sharp.FlowTime = 4096.0
sharp.SmoothingPasses = 1


def show(proxy, view):
    display = simple.Show(proxy, view)
    simple.ColorBy(display, ("POINTS", "Colour"))
    display.MapScalars = 0    # the three components are the colour itself
    display.Specular = 0.2


shock_example.before_after(colours, sharp, show, os.path.join(arguments.output, "sharpen_mesh_colors.png"),
                           arguments.size, shock_example.looking_from([1.6, 1.2, 2.2], [0, 1, 0], 1.15),
                           ("Blurred colours", "Surface Shock Advection"))
