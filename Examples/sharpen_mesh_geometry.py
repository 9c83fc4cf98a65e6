"""Sharpen the geometry of a rounded box with Surface Shock Sharpen.

    pvpython Examples/sharpen_mesh_geometry.py [OUTPUT_FOLDER] [--plugin PATH/ShockFilters.so]

(under a headless machine: xvfb-run -a pvpython ...). Builds a box whose
edges and corners are rounded (Box, welded and triangulated, subdivided and
smoothed), sharpens it with the ShockFilters plugin (shock-filtered normals,
then a screened Poisson fit of the points) and writes
OUTPUT_FOLDER/sharpen_mesh_geometry.png (default examples-output/) with the
rounded and the sharpened box side by side, each triangle coloured by its
normal, so that rounded edges show as blended bands and creases as lines.
"""
import os

from paraview import simple

import shock_example

arguments = shock_example.start(__doc__.splitlines()[0])

box = simple.Box(XLength=1.6, YLength=1.0, ZLength=0.8)
welded = simple.Clean(Input=box)                          # one point per corner, so the faces connect
triangles = simple.Triangulate(Input=welded)
fine = simple.Subdivide(Input=triangles, NumberofSubdivisions=4)  # 3072 triangles
rounded = simple.Smooth(Input=fine, NumberofIterations=300)  # rounds edges and corners

sharp = simple.SurfaceShockSharpen(Input=rounded)
sharp.FlowTime = 256.0
sharp.ScreeningWeight = 1.0
sharp.SolverIterations = 50


def show(proxy, view):
    # Colour each triangle by its normal (x, y, z mapped to red, green, blue):
    # a rounded edge is a band of blended colours, a sharp crease a clean line.
    normals = simple.GenerateSurfaceNormals(Input=proxy, ComputeCellNormals=1, Splitting=0)
    rgb = simple.Calculator(Input=normals, AttributeType="Cell Data", ResultArrayName="NormalColour",
                            Function="0.5*Normals + 0.5*(iHat + jHat + kHat)")
    display = simple.Show(rgb, view)
    simple.ColorBy(display, ("CELLS", "NormalColour"))
    display.MapScalars = 0    # the three components are the colour itself
    display.Ambient = 0.4
    display.Diffuse = 0.7


def camera(view):
    view.CameraPosition = [2.4, 2.6, 3.2]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    simple.ResetCamera(view)


shock_example.before_after(rounded, sharp, show, os.path.join(arguments.output, "sharpen_mesh_geometry.png"),
                           arguments.size, camera, ("Rounded box", "Surface Shock Sharpen"))
