"""The files a user brings, written into the current folder.

photo.png (RGB, soft shapes), ct.vti (a soft ball, point array "density"),
scan.ply (a sphere with soft colour bands, per-vertex RGB) and script.py (a
pvbatch script). Used by the documentation snippets and the first-contact
tests. Needs ParaView's vtkmodules (pvpython or the python3 ParaView uses).
"""
import math
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOPLY import vtkPLYWriter
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

def blurred_disc(x, y, cx, cy, r, width):
    return 0.5 + 0.5 * math.tanh((r - math.hypot(x - cx, y - cy)) / width)

# photo.png: RGB, a soft red disc and a soft blue square on grey.
photo = vtkImageData(); photo.SetDimensions(96, 64, 1)
rgb = vtkUnsignedCharArray(); rgb.SetNumberOfComponents(3); rgb.SetName("PNGImage")
for y in range(64):
    for x in range(96):
        d = blurred_disc(x, y, 30, 32, 16, 3.0)
        s = (0.5 + 0.5 * math.tanh((12 - abs(x - 70)) / 3.0)) * (0.5 + 0.5 * math.tanh((12 - abs(y - 32)) / 3.0))
        rgb.InsertNextTuple3(round(60 + 180 * d), 60, round(60 + 180 * s))
photo.GetPointData().SetScalars(rgb)
writer = vtkPNGWriter(); writer.SetInputData(photo); writer.SetFileName("photo.png"); writer.Write()

# ct.vti: a soft ball, point array "density".
ct = vtkImageData(); ct.SetDimensions(24, 24, 24); ct.SetSpacing(0.5, 0.5, 0.5)
density = vtkFloatArray(); density.SetName("density")
for z in range(24):
    for y in range(24):
        for x in range(24):
            r = math.sqrt((x - 11.5) ** 2 + (y - 11.5) ** 2 + (z - 11.5) ** 2)
            density.InsertNextValue(1000.0 * (0.5 + 0.5 * math.tanh((7.0 - r) / 2.0)))
ct.GetPointData().AddArray(density)
writer = vtkXMLImageDataWriter(); writer.SetInputData(ct); writer.SetFileName("ct.vti"); writer.Write()

# scan.ply: a sphere with soft colour bands (red, green, blue per vertex).
sphere = vtkSphereSource(); sphere.SetThetaResolution(48); sphere.SetPhiResolution(24); sphere.Update()
mesh = sphere.GetOutput()
colours = vtkUnsignedCharArray(); colours.SetNumberOfComponents(3); colours.SetName("RGB")
for i in range(mesh.GetNumberOfPoints()):
    x, y, z = mesh.GetPoint(i)
    colours.InsertNextTuple3(round(255 * (0.5 + 0.5 * math.tanh(8 * z))), 80, round(255 * (0.5 + 0.5 * math.tanh(8 * x))))
mesh.GetPointData().SetScalars(colours)
writer = vtkPLYWriter(); writer.SetInputData(mesh); writer.SetArrayName("RGB"); writer.SetFileName("scan.ply"); writer.Write()

# script.py: what a user passes to pvbatch.
with open("script.py", "w") as script:
    script.write("""from paraview.simple import *
LoadPlugin("build/lib/paraview-5.11/plugins/ShockFilters/ShockFilters.so", ns=globals())
shock = ImageShockAdvection(Input=Wavelet())
SaveData("wavelet_sharp.pvti", proxy=shock)
""")
