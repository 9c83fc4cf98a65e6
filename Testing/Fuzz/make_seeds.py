#!/usr/bin/env python3
"""Writes the seed files of the fuzz targets into seeds/<format>/ (valid small
files and a few damaged ones, from ../Robustness/make_corpus.py).

    make_seeds.py SHOCKFILTER

Run once; the seeds are committed. Inputs that crashed a target are added to
seeds/<format>/ by hand (named crash-<what>) and stay there.
"""
import os
import shutil
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "Robustness"))
work = tempfile.mkdtemp()
sys.argv = [sys.argv[0], work, sys.argv[1]]
import make_corpus as corpus  # noqa: E402  (reads OUT and PROGRAM from sys.argv)

corpus.W, corpus.H = 6, 4
small_box = corpus.rounded_box(n=1, rounding=0.0)
corpus.rounded_box = lambda n=6, rounding=0.4: small_box
for make in (corpus.png_kinds, corpus.pnm_kinds, corpus.bmp_kinds, corpus.tiff_kinds, corpus.vtk_image_kinds,
             corpus.jpeg_kinds, corpus.mesh_kinds):
    make()
wanted = {"png": "png_", "jpg": "jpeg_", "tif": "tiff_", "bmp": "bmp_", "ppm": "pnm_", "vtk": "vtk_",
          "vti": "vti_", "off": "off_", "ply": "ply_", "stl": "stl_", "obj": "obj_", "vtp": "vtp_"}
for extension, prefix in wanted.items():
    target = os.path.join(here, "seeds", extension)
    os.makedirs(target, exist_ok=True)
    for kind in corpus.KINDS:
        name = kind["name"]
        size = os.path.getsize(os.path.join(work, name))
        if name.startswith(prefix) and name.endswith("." + extension) and size <= 4096 and "huge" not in name:
            shutil.copyfile(os.path.join(work, name), os.path.join(target, name))
shutil.rmtree(work)
