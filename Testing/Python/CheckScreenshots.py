"""Check that PNG screenshots are real pictures, not blank windows.

Usage: pvpython CheckScreenshots.py [--min-colours N] [--min-covered F] PNG...

Each file must exist, decode, hold more than N distinct colours (default 200)
and have more than the fraction F (default 0.1) of its pixels different from
its most frequent colour (the background). Prints one line per file and
"N passed, M failed"; exits non-zero on any failure.
"""
import argparse
import os
import sys

import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkIOImage import vtkPNGReader

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--min-colours", type=int, default=200)
parser.add_argument("--min-covered", type=float, default=0.1)
parser.add_argument("files", nargs="+")
arguments = parser.parse_args()

passed, failed = 0, 0
for path in arguments.files:
    problem = None
    if not os.path.isfile(path):
        problem = "missing"
    else:
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        image = reader.GetOutput()
        if image.GetNumberOfPoints() == 0:
            problem = "not a PNG picture"
        else:
            pixels = np.asarray(dsa.WrapDataObject(image).PointData[0]).astype(np.int64)
            pixels = pixels.reshape(image.GetNumberOfPoints(), -1)[:, :3]
            codes = pixels[:, 0] * 65536 + pixels[:, 1] * 256 + pixels[:, 2]
            colours = len(np.unique(codes))
            covered = float(np.mean(codes != np.bincount(codes).argmax()))
            size = image.GetDimensions()[:2]
            print("%s: %dx%d, %d colours, %.0f%% not background, %d bytes"
                  % (path, size[0], size[1], colours, 100 * covered, os.path.getsize(path)))
            if colours <= arguments.min_colours:
                problem = "only %d colours" % colours
            elif covered <= arguments.min_covered:
                problem = "%.1f%% of the pixels differ from the background" % (100 * covered)
    if problem:
        failed += 1
        print("FAIL: %s: %s" % (path, problem))
    else:
        passed += 1
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
