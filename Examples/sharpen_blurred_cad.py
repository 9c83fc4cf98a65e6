"""Sharpen a blurred CAD part with Surface Shock Sharpen.

    pvpython Examples/sharpen_blurred_cad.py [OUTPUT_FOLDER] [--plugin PATH/ShockFilters.so]

Makes a CAD-like part (an L-shaped block with a slot through one leg: convex
and concave creases), blurs it with windowed-sinc smoothing (all its creases
become rounded), sharpens it with the ShockFilters plugin at default settings
and writes OUTPUT_FOLDER/sharpen_blurred_cad.png (default examples-output/):
the blurred and the sharpened part side by side, each triangle coloured by
its normal, so that a rounded crease is a band of blended colours and a sharp
one a clean line. The sharpened part keeps its size (docs/sharpening.md).
"""
import os

from paraview import simple

import shock_example

arguments = shock_example.start(__doc__.splitlines()[0])

# The part: the boundary faces of the occupied cells of a 32 x 24 x 14 grid (cells of
# side 1/24), two triangles each, then windowed-sinc smoothing.
PART = r'''
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkWindowedSincPolyDataFilter
nx, ny, nz, h = 32, 24, 14, 1.0 / 24.0
def inside(i, j, k):
    return (0 <= i < nx and 0 <= j < ny and 0 <= k < nz and (i < 12 or j < 10)
            and not (20 <= i < 26 and k >= 6))
points, cells, ids = vtkPoints(), vtkCellArray(), {}
def point(g):
    if g not in ids:
        ids[g] = points.InsertNextPoint((g[0] - nx / 2) * h, (g[1] - ny / 2) * h, (g[2] - nz / 2) * h)
    return ids[g]
square = [(0, 0), (1, 0), (1, 1), (0, 1)]
for i in range(nx):
    for j in range(ny):
        for k in range(nz):
            if not inside(i, j, k):
                continue
            for axis in range(3):
                for side in (0, 1):
                    n = [i, j, k]
                    n[axis] += 1 if side else -1
                    if inside(*n):
                        continue
                    u, v = (axis + 1) % 3, (axis + 2) % 3
                    q = []
                    for c in range(4):
                        g = [i, j, k]
                        g[axis] += side
                        du, dv = square[c if side else 3 - c]
                        g[u] += du
                        g[v] += dv
                        q.append(point(tuple(g)))
                    cells.InsertNextCell(3, [q[0], q[1], q[2]])
                    cells.InsertNextCell(3, [q[0], q[2], q[3]])
part = vtkPolyData()
part.SetPoints(points)
part.SetPolys(cells)
blur = vtkWindowedSincPolyDataFilter()
blur.SetInputData(part)
blur.SetNumberOfIterations(20)
blur.SetPassBand(0.005)
blur.NormalizeCoordinatesOn()
blur.Update()
self.GetPolyDataOutput().ShallowCopy(blur.GetOutput())
'''
blurred = simple.ProgrammableSource(OutputDataSetType="vtkPolyData", Script=PART)
sharp = simple.SurfaceShockSharpen(Input=blurred)   # the defaults (FlowTime 256)


shock_example.before_after(blurred, sharp, shock_example.show_normal_colours,
                           os.path.join(arguments.output, "sharpen_blurred_cad.png"), arguments.size,
                           shock_example.looking_from([1.6, -1.9, 2.2], [0, 0, 1]),
                           ("Blurred CAD part", "Surface Shock Sharpen"))
