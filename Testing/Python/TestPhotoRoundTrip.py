"""A photograph's round trip through ParaView, as a user makes it.

pvpython TestPhotoRoundTrip.py PLUGIN SHOCKFILTER WORKDIR

1. The recipe of docs/paraview.md: open the PNG with the PNG reader (pixels as
   points, rows as in the file), Image Shock Advection (Flow Time 1024),
   SaveData('sharp.png'): the file is written, same size, and at Flow Time 0
   it is the photo itself.
2. OpenDataFile('photo.png') picks ParaView's GDAL raster reader (pixels as
   cells): the filter works on those cells, SaveData of a .vti keeps them, and
   `shockfilter image` takes that .vti (cell data) and writes the same pixels
   to a PNG, and again to a .vti, as ParaView computed them.
"""
import os
import subprocess
import sys

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

plugin, program, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
failures = []


def check(condition, message):
    print(("ok: " if condition else "FAIL: ") + message, flush=True)
    if not condition:
        failures.append(message)


def png_pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return image.GetDimensions(), vtk_to_numpy(image.GetPointData().GetScalars()).astype(float)


def vti_cells(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return vtk_to_numpy(image.GetCellData().GetArray(0)).astype(float)


# A blurred RGB "photo" that is not symmetric: a soft disc low on the left, a bright top band.
height, width = 48, 64
y, x = np.mgrid[0:height, 0:width]
disc = 1.0 / (1.0 + np.exp((np.hypot(x - 18, y - 14) - 9.0) / 1.5))
band = 1.0 / (1.0 + np.exp(-(y - 36.0) / 1.5))
rgb = np.stack([200 * disc + 30, 40 + 180 * band, 60 + 100 * disc * band], axis=-1).clip(0, 255).astype(np.uint8)
image = vtkImageData()
image.SetDimensions(width, height, 1)
values = numpy_to_vtk(rgb.reshape(-1, 3), deep=1)
values.SetName("PNGImage")
image.GetPointData().SetScalars(values)
photo = os.path.join(work, "photo.png")
writer = vtkPNGWriter()
writer.SetInputData(image)
writer.SetFileName(photo)
writer.Write()

LoadPlugin(plugin, ns=globals())

# 1. The PNG reader: SaveData('sharp.png') writes the sharpened photo.
source = PNGSeriesReader(FileNames=[photo])
sharp = ImageShockAdvection(Input=source, FlowTime=1024.0)
sharp_png = os.path.join(work, "sharp.png")
SaveData(sharp_png, proxy=sharp)
check(os.path.exists(sharp_png), "PNG reader: SaveData('sharp.png') writes the file")
dims, pixels = png_pixels(sharp_png)
_, original = png_pixels(photo)
check(tuple(dims) == (width, height, 1), "PNG reader: same size, got %s" % (dims,))
check(np.abs(pixels - original).max() >= 20, "PNG reader: the photo was sharpened (largest change %d)" % np.abs(pixels - original).max())
still = ImageShockAdvection(Input=source, FlowTime=0.0)
still_png = os.path.join(work, "still.png")
SaveData(still_png, proxy=still)
check(np.array_equal(png_pixels(still_png)[1], original), "PNG reader: Flow Time 0 gives the photo itself")

# 2. The GDAL raster reader (OpenDataFile's choice): cells; ParaView's .vti to the program.
opened = OpenDataFile(photo)
opened.UpdatePipeline()
check(opened.GetDataInformation().GetNumberOfCells() == width * height, "GDAL reader: one cell per pixel")
filtered = ImageShockAdvection(Input=opened, FlowTime=256.0)
paraview_vti = os.path.join(work, "paraview_cells.vti")
input_vti = os.path.join(work, "photo_cells.vti")
SaveData(paraview_vti, proxy=filtered)
SaveData(input_vti, proxy=opened)
for output in ("program.png", "program.vti"):
    run = subprocess.run([program, "image", input_vti, os.path.join(work, output), "--time", "256"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    check(run.returncode == 0, "shockfilter image on ParaView's cell-data .vti -> %s: exit %d %s"
          % (output, run.returncode, run.stderr.strip()))
expected = vti_cells(paraview_vti)
check(np.array_equal(vti_cells(os.path.join(work, "program.vti")), expected),
      "the program's .vti equals ParaView's result (cells kept)")
dims, written = png_pixels(os.path.join(work, "program.png"))
check(tuple(dims) == (width, height, 1) and np.array_equal(written, expected.reshape(written.shape)),
      "the program's PNG holds ParaView's pixels, one per cell")

print("%d failed" % len(failures))
sys.exit(1 if failures else 0)
