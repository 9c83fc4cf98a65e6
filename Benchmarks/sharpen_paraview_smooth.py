"""Surface Shock Sharpen after ParaView's Smooth on CGAL's CAD parts as they
come (docs/sharpening.md, "Designed roundings and coarse tessellations").

    pvpython Benchmarks/sharpen_paraview_smooth.py [--plugin PATH/ShockFilters.so] [--cad DIR]
        [--models a,b,...] [--iterations 20,40]

As a ParaView user does it: OpenDataFile(part.off) -> Triangulate -> Smooth
(its defaults, or NumberofIterations) -> SurfaceShockSharpen with nothing but
Input=, and with FeatureAngle 10 and 5. Each row: the mean angle between the
face normals and those of the part before Smooth, in degrees, over all faces,
area-weighted, and over the faces of curved surfaces (faces with an edge
turning by 3 to 30 degrees in the part before Smooth and none by more: the
facets of cylinders, cones and roundings); the largest point displacement
the sharpening made, in % of the diagonal. DIR (default
~/.cache/shockfilters/cad) is filled by Benchmarks/get_cad_meshes.sh.
"""
import argparse
import os
import sys

import numpy as np
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "Examples"))
import shock_example  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.environ.get(shock_example.PLUGIN_VARIABLE, shock_example.DEFAULT_PLUGIN))
parser.add_argument("--cad", default=os.path.join(os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")),
                                                  "shockfilters", "cad"))
parser.add_argument("--models", default="fandisk,anchor_dense,rotor_small,couplingdown,pinion,spool,oblong,joint,"
                                        "part,dragknob")
parser.add_argument("--iterations", default="20", help="Smooth's NumberofIterations, comma-separated (20: its default)")
args = parser.parse_args()
simple.LoadPlugin(args.plugin, ns=globals())

VARIANTS = [("defaults", {}), ("FeatureAngle 10", {"FeatureAngle": 10.0}), ("FeatureAngle 5", {"FeatureAngle": 5.0})]


def face_normals(mesh):
    normals = vtkPolyDataNormals()
    normals.SetInputData(mesh)
    normals.ComputeCellNormalsOn()
    normals.ComputePointNormalsOff()
    normals.SplittingOff()
    normals.ConsistencyOff()
    normals.AutoOrientNormalsOff()
    normals.Update()
    return vtk_to_numpy(normals.GetOutput().GetCellData().GetNormals()).astype(float)


def triangles(mesh):
    return vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)


def angles(a, b):
    """Degrees between corresponding unit rows."""
    return np.degrees(np.arccos(np.clip((a * b).sum(axis=1), -1.0, 1.0)))


def curved_faces(points, cells, normals):
    """Faces with an edge turning by 3 to 30 degrees and none by more (the two faces of each interior edge)."""
    edges = np.sort(np.concatenate([cells[:, [0, 1]], cells[:, [1, 2]], cells[:, [2, 0]]]), axis=1)
    faces = np.tile(np.arange(len(cells)), 3)
    order = np.lexsort((edges[:, 1], edges[:, 0]))
    edges, faces = edges[order], faces[order]
    pair = np.flatnonzero((edges[1:] == edges[:-1]).all(axis=1))
    first, second = faces[pair], faces[pair + 1]
    turn = angles(normals[first], normals[second])
    most = np.zeros(len(cells))
    np.maximum.at(most, first, turn)
    np.maximum.at(most, second, turn)
    some = np.zeros(len(cells), bool)
    bent = (turn > 3.0) & (turn <= 30.0)
    some[first[bent]] = True
    some[second[bent]] = True
    return some & (most <= 30.0)


def row(label, errors, area, curved, moved):
    print("| %s | %.2f | %.2f | %.2f | %s |" % (label, errors.mean(), (errors * area).sum() / area.sum(),
                                                errors[curved].mean() if curved.any() else float("nan"), moved),
          flush=True)


print("| part, what | mean normal error (deg) | area-weighted | on curved surfaces | largest displacement "
      "(% of the diagonal) |")
print("|---|---|---|---|---|")
for model in args.models.split(","):
    path = os.path.join(args.cad, model + ".off")
    if not os.path.exists(path):
        print("| %s | missing (Benchmarks/get_cad_meshes.sh) | | | |" % model)
        continue
    part = simple.Triangulate(Input=simple.OpenDataFile(path))
    original = servermanager.Fetch(part)
    points = vtk_to_numpy(original.GetPoints().GetData()).astype(float)
    cells = triangles(original)
    truth = face_normals(original)
    area = 0.5 * np.linalg.norm(np.cross(points[cells[:, 1]] - points[cells[:, 0]],
                                         points[cells[:, 2]] - points[cells[:, 0]]), axis=1)
    curved = curved_faces(points, cells, truth)
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    for iterations in (int(i) for i in args.iterations.split(",")):
        smooth = simple.Smooth(Input=part, NumberofIterations=iterations)
        blurred = servermanager.Fetch(smooth)
        before = vtk_to_numpy(blurred.GetPoints().GetData()).astype(float)
        row("%s (%d points, %d of %d faces curved), Smooth %d" % (model, len(points), curved.sum(), len(cells),
                                                                  iterations),
            angles(truth, face_normals(blurred)), area, curved, "")
        for label, settings in VARIANTS:
            sharpened = SurfaceShockSharpen(Input=smooth, **settings)  # noqa: F821 (LoadPlugin)
            result = servermanager.Fetch(sharpened)
            after = vtk_to_numpy(result.GetPoints().GetData()).astype(float)
            moved = np.linalg.norm(after - before, axis=1).max() / diagonal * 100.0
            row("  then Surface Shock Sharpen, %s" % label, angles(truth, face_normals(result)), area, curved,
                "%.2f" % moved)
            simple.Delete(sharpened)
        simple.Delete(smooth)
    simple.Delete(part)
