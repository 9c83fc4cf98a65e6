"""The input files of Benchmarks/userbench.py, written once into a cache folder.

Each input is made by the tool that defines it, so that the harness measures
the same data as the other benchmarks:
- photos: windows of the real photograph of Benchmarks/get_photo.sh (native
  pixels; the 8000 x 8000 one is the centred square window resampled);
- meshes: `meshbench MODE --write-input` (the scans of Benchmarks/get_meshes.sh,
  Loop-subdivided, with meshbench's blurred Voronoi colours for "colors");
- volumes: `shockbench --write-volume N` (the volume of shockbench's volume mode);
- the small mesh: a UV sphere of 482 vertices with blurred colour bands.
A file already in the cache is reused (delete it to make it anew).
"""
import os
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkImagingCore import vtkExtractVOI, vtkImageResize
from vtkmodules.vtkIOImage import vtkJPEGReader, vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

HERE = os.path.dirname(os.path.abspath(__file__))


def log(*words):
    print("userbench:", *words, file=sys.stderr, flush=True)


class Inputs:
    """Paths of the inputs, each made on first use."""

    def __init__(self, cache, tools, photo=None, mesh_dir=None):
        self.cache = cache
        self.tools = tools  # folder with meshbench and shockbench
        self.photo_path = photo
        self.mesh_dir = mesh_dir
        os.makedirs(cache, exist_ok=True)

    def _path(self, name, make):
        path = os.path.join(self.cache, name)
        if not os.path.exists(path):
            log("making", path)
            partial = path + ".partial" + os.path.splitext(name)[1]
            make(partial)
            os.replace(partial, path)
        return path

    def _tool(self, name):
        tool = os.path.join(self.tools, name)
        if not os.access(tool, os.X_OK):
            sys.exit("userbench: %s not found: build it (cmake --build BUILD --target %s) "
                     "or give --tools DIR" % (tool, name))
        return tool

    def photo(self):
        if not self.photo_path:
            self.photo_path = subprocess.run(
                ["sh", os.path.join(HERE, "get_photo.sh")], check=True,
                stdout=subprocess.PIPE, text=True).stdout.strip()
        return self.photo_path

    def _window(self, path, width, height, resize=None):
        """The centred width x height window of the photo, resampled to `resize`."""
        reader = vtkJPEGReader()
        reader.SetFileName(self.photo())
        reader.Update()
        full_w, full_h, _ = reader.GetOutput().GetDimensions()
        x0, y0 = (full_w - width) // 2, (full_h - height) // 2
        voi = vtkExtractVOI()
        voi.SetInputConnection(reader.GetOutputPort())
        voi.SetVOI(x0, x0 + width - 1, y0, y0 + height - 1, 0, 0)
        last = voi
        if resize:
            last = vtkImageResize()
            last.SetInputConnection(voi.GetOutputPort())
            last.SetOutputDimensions(resize[0], resize[1], 1)
        writer = vtkPNGWriter()
        writer.SetInputConnection(last.GetOutputPort())
        writer.SetFileName(path)
        writer.Write()

    def photo_1368x1824(self):
        return self._path("photo-1368x1824.png", lambda p: self._window(p, 1368, 1824))

    def photo_8000x8000(self):
        return self._path("photo-8000x8000.png",
                          lambda p: self._window(p, 2448, 2448, resize=(8000, 8000)))

    def photo_64x48(self):
        return self._path("photo-64x48.png", lambda p: self._window(p, 64, 48))

    def _meshbench(self, path, mode, mesh, levels):
        # The real scans (meshbench would otherwise make a synthetic stand-in of a
        # missing one, which is not the row's input).
        fetch = ["sh", os.path.join(HERE, "get_meshes.sh")] + ([self.mesh_dir] if self.mesh_dir else [])
        subprocess.run(fetch, check=True, stdout=sys.stderr)
        command = [self._tool("meshbench"), mode, "--mesh", mesh, "--levels", str(levels),
                   "--write-input", path]
        if self.mesh_dir:
            command += ["--mesh-dir", self.mesh_dir]
        subprocess.run(command, check=True)

    def armadillo_colours(self):
        return self._path("armadillo-2x-colours.ply",
                          lambda p: self._meshbench(p, "colors", "armadillo", 2))

    def dragon(self, levels):
        return self._path("dragon-%dx.ply" % levels,
                          lambda p: self._meshbench(p, "sharpen", "ChineseDragon-10kv", levels))

    def volume(self, n):
        return self._path("volume-%d.vti" % n, lambda p: subprocess.run(
            [self._tool("shockbench"), "--write-volume", str(n), p], check=True))

    def small_mesh(self):
        return self._path("sphere-482-colours.vtp", write_small_mesh)


def write_small_mesh(path):
    """A UV sphere of 482 vertices with blurred RGB bands (unsigned char "Colors")."""
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(32)
    sphere.SetPhiResolution(17)
    sphere.Update()
    mesh = sphere.GetOutput()
    points = np.array([mesh.GetPoint(i) for i in range(mesh.GetNumberOfPoints())])
    x, y, z = points[:, 0] / 0.5, points[:, 1] / 0.5, points[:, 2] / 0.5
    rgb = np.stack([0.5 + 0.5 * np.tanh(3 * np.sin(5 * x + 2 * y)),
                    0.5 + 0.5 * np.tanh(3 * np.sin(4 * z)),
                    0.35 + 0.3 * np.tanh(3 * np.sin(4 * y - 3 * z))], axis=1)
    colours = numpy_to_vtk(np.rint(255 * rgb).astype(np.uint8), deep=1)
    colours.SetName("Colors")
    mesh.GetPointData().SetScalars(colours)
    mesh.GetPointData().RemoveArray("Normals")
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(mesh)
    writer.SetFileName(path)
    writer.Write()
