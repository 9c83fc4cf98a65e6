"""The three shock filters in a plain VTK pipeline in Python (no ParaView).

    PYTHONPATH=build/lib/python3.11/site-packages python3 Examples/vtk_pipeline.py [OUTPUT_DIR]

Runs with pvpython or with the python3 ParaView was built with (both have
ParaView's vtkmodules); PYTHONPATH points at the folder holding the package
shockfilters (in an installed tree: <prefix>/lib/python3.11/site-packages).
Writes blurred_image.vti, sharpened_image.vti, sharpened_band.vtp and
sharpened_box.vtp into OUTPUT_DIR (default examples-output) and prints what
changed.
"""
import math
import os
import sys

from shockfilters import (vtkImageShockAdvectionFilter, vtkPolyDataShockAdvectionFilter,
                          vtkPolyDataShockSharpenFilter)
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkLogger
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource, vtkSuperquadricSource
from vtkmodules.vtkImagingGeneral import vtkImageGaussianSmooth
from vtkmodules.vtkImagingSources import vtkImageCanvasSource2D
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter, vtkXMLPolyDataWriter

out = sys.argv[1] if len(sys.argv) > 1 else "examples-output"
os.makedirs(out, exist_ok=True)
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_WARNING)


def write(writer_type, algorithm, name):
    writer = writer_type()
    writer.SetInputConnection(algorithm.GetOutputPort())
    writer.SetFileName(os.path.join(out, name))
    writer.Write()


def steepest_step(image):
    """Largest difference between neighbouring pixels along x."""
    values = image.GetPointData().GetScalars()
    nx, ny, _ = image.GetDimensions()
    return max(abs(values.GetTuple1(y * nx + x + 1) - values.GetTuple1(y * nx + x))
               for y in range(ny) for x in range(nx - 1))


# 1. An image: a white square on black, blurred, then sharpened.
canvas = vtkImageCanvasSource2D()
canvas.SetExtent(0, 63, 0, 63, 0, 0)
canvas.SetScalarTypeToFloat()
canvas.SetNumberOfScalarComponents(1)
canvas.SetDrawColor(0.0)
canvas.FillBox(0, 63, 0, 63)
canvas.SetDrawColor(255.0)
canvas.FillBox(20, 43, 20, 43)
blur = vtkImageGaussianSmooth()
blur.SetInputConnection(canvas.GetOutputPort())
blur.SetStandardDeviations(2.5, 2.5, 0.0)
image_shock = vtkImageShockAdvectionFilter()   # the active scalars by default
image_shock.SetInputConnection(blur.GetOutputPort())
image_shock.SetFlowTime(1024.0)
image_shock.Update()
write(vtkXMLImageDataWriter, blur, "blurred_image.vti")
write(vtkXMLImageDataWriter, image_shock, "sharpened_image.vti")
before, after = steepest_step(blur.GetOutput()), steepest_step(image_shock.GetOutput())
print("image: steepest step %.1f blurred, %.1f sharpened" % (before, after))

# 2. A signal on a surface: a soft band around a sphere, sharpened over it.
sphere = vtkSphereSource()
sphere.SetThetaResolution(64)
sphere.SetPhiResolution(64)
sphere.Update()
mesh = sphere.GetOutput()
band = vtkFloatArray()
band.SetName("Band")
for i in range(mesh.GetNumberOfPoints()):
    band.InsertNextValue(0.5 + 0.5 * math.tanh(6.0 * mesh.GetPoint(i)[2]))
mesh.GetPointData().SetScalars(band)
surface_shock = vtkPolyDataShockAdvectionFilter()
surface_shock.SetInputData(mesh)
surface_shock.SetInputArrayToProcess(0, 0, 0, 0, "Band")  # 0: point data
surface_shock.SetFlowTime(4096.0)
surface_shock.Update()
write(vtkXMLPolyDataWriter, surface_shock, "sharpened_band.vtp")
sharp_band = surface_shock.GetOutput().GetPointData().GetArray("Band")
low, high = sharp_band.GetRange()
moved = max(abs(sharp_band.GetValue(i) - band.GetValue(i)) for i in range(band.GetNumberOfTuples()))
print("surface: Band range %.3f to %.3f (input %.3f to %.3f), values moved by up to %.3f"
      % (low, high, band.GetRange()[0], band.GetRange()[1], moved))

# 3. Geometry: a box with rounded edges, its creases sharpened.
box = vtkSuperquadricSource()
box.SetPhiRoundness(0.3)
box.SetThetaRoundness(0.3)
box.SetPhiResolution(48)
box.SetThetaResolution(48)
box.ToroidalOff()
triangles = vtkTriangleFilter()
triangles.SetInputConnection(box.GetOutputPort())
sharpen = vtkPolyDataShockSharpenFilter()
sharpen.SetInputConnection(triangles.GetOutputPort())
sharpen.SetFlowTime(256.0)
sharpen.Update()
write(vtkXMLPolyDataWriter, sharpen, "sharpened_box.vtp")
print("box: %d points, largest displacement %.4f of the diagonal, %d flipped triangles"
      % (sharpen.GetOutput().GetNumberOfPoints(), sharpen.GetLastMaxDisplacement(),
         sharpen.GetLastFlippedTriangles()))

ok = after > 1.5 * before and band.GetRange()[0] <= low and high <= band.GetRange()[1] and moved > 0.05 and sharpen.GetLastMaxDisplacement() > 0.0
sys.exit(0 if ok else 1)
