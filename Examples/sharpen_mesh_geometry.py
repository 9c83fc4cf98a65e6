"""Sharpen the geometry of a rounded box with Surface Shock Sharpen.

    pvpython Examples/sharpen_mesh_geometry.py [OUTPUT_FOLDER] [--plugin PATH/ShockFilters.so]

(under a headless machine: xvfb-run -a pvpython ...). Builds a box whose
edges and corners are rounded with radius 0.12 (Box, welded, triangulated and
subdivided, its points moved onto the box shrunk by 0.12 and grown again by a
ball of that radius), sharpens it with the ShockFilters plugin at default
settings (shock-filtered normals, then a screened Poisson fit of the points)
and writes
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
fine = simple.Subdivide(Input=triangles, NumberofSubdivisions=5)  # 12288 triangles
rounded = simple.ProgrammableFilter(Input=fine, Script='''
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
half, r = np.array([0.8, 0.5, 0.4]), 0.12
x = dsa.WrapDataObject(inputs[0].VTKObject).Points
nearest = np.clip(x, -(half - r), half - r)
away = x - nearest
length = np.linalg.norm(away, axis=1)[:, None]
output.Points = nearest + r * away / np.where(length > 0, length, 1)
''')

sharp = simple.SurfaceShockSharpen(Input=rounded)
sharp.FlowTime = 1024.0


shock_example.before_after(rounded, sharp, shock_example.show_normal_colours,
                           os.path.join(arguments.output, "sharpen_mesh_geometry.png"), arguments.size,
                           shock_example.looking_from([2.4, 2.6, 3.2], [0, 1, 0]),
                           ("Rounded box", "Surface Shock Sharpen"))
