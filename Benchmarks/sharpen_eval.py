#!/usr/bin/env python3
"""Geometry sharpening on real CAD parts blurred in ways the filter was not
designed around (issue 34; docs/sharpening.md, "An evaluation set of real CAD
parts").

    Benchmarks/get_cad_meshes.sh; Benchmarks/get_scan_meshes.sh
    nice -n 19 /usr/bin/python3 Benchmarks/sharpen_eval.py table [--build build]
        [--meshes cad|scan] [--cad DIR] [--scan DIR] [--out DIR] [--models a,b] [--blurs sinc1,gauss2]
        [--set Name=Value ...] [--correct NAME] [--no-smooth]
    nice -n 19 /usr/bin/python3 Benchmarks/sharpen_eval.py study [same options]
        [--variants "defaults,FeatureAngle 60"] [--correct all|NAME,...]
    nice -n 19 /usr/bin/python3 Benchmarks/sharpen_eval.py times [same options] [--times 64,128,...]
    nice -n 19 /usr/bin/python3 Benchmarks/sharpen_eval.py widths [--set ...] [--times 16,32,...]
    /usr/bin/python3 Benchmarks/sharpen_eval.py cases [--set ...]
    nice -n 19 /usr/bin/python3 Benchmarks/sharpen_eval.py slivers [--set ...]

Models: ten closed CAD parts of CGAL's data (get_cad_meshes.sh), cleaned,
triangulated, linearly subdivided (vtkLinearSubdivisionFilter: creases and
facets stay as they are) the fewest times that give at least 15 000 points,
centred and scaled to a unit diagonal (--meshes cad, the default). With
--meshes scan, the scan set: the same parts as a scanner samples them
(get_scan_meshes.sh: remeshed evenly by CGAL's isotropic remeshing to about
24 000 points on the original surface, the creases of more than 30 degrees
kept as edges; no subdivision). Each is blurred six ways, with the same
parameters for every model (in units of the mesh: iterations, edge lengths):

- sinc1, sinc2: vtkWindowedSincPolyDataFilter, 20 iterations, pass band 0.05
  and 0.005 (normalised coordinates, no feature-edge smoothing);
- laplace1, laplace2: vtkSmoothPolyDataFilter (Laplacian, ParaView's Smooth),
  relaxation 0.1, 40 and 120 iterations (shrinks the shape);
- gauss1, gauss2: a Gaussian of the vertex positions, sigma 1.5 and 3 mean edge
  lengths, over the points within ceil(3 sigma) edges (so that the two sides
  of a thin wall do not mix), weighted by their Euclidean distance, plus
  isotropic Gaussian noise of 0.02 times the mean length of each point's edges
  (fixed seeds).

The blurred points are kept in OUT/blurred/ for later runs. Each blurred mesh
is sharpened by vtkPolyDataShockSharpenFilter with its defaults (or --set) at
the default FlowTime (read from the filter: 256, 64 before issue 33) and 256, 512, 1024,
2048, 4096, on one thread (the result does not depend on it). Measured against the original (same
connectivity, so per face and per point): the normal error (mean angle between
the face normals, weighted by the original's areas, degrees); the RMS point
distance (same vertex correspondence, % of the diagonal; the table also gives
the RMS distance of the points to the original surface); the volume change
(vtkMassProperties, %); flipped triangles (face normal against the original's
< 0, for the input and the output; the filter's LastFlippedTriangles counts
against its input); and the exact shape's normal error ratio (Reference.exact_shape_error:
each blurred triangle given the normal of the original triangle nearest to its
centroid, over the input's normal error: what a filter restoring the shape
exactly would still score where the blur slid triangles across a crease).
The goal of issue 34: normal error <= 0.70 x the blurred
input's AND RMS distance <= 1.0 x the blurred input's at some t in 256 ... 4096.
Per model and blur the table gives the t that meets it with the lowest normal
error, else the t nearest to it (lowest max(normal ratio / 0.7, RMS ratio)).

Smooth shapes must not move: vtkSphereSource at resolutions 8, 12, 16, 32, 64,
a torus (vtkParametricTorus, radii 1 and 0.5, vtkParametricFunctionSource) at
resolutions 8, 16, 32, 64, a blob (an icosphere, 642 and 10242 points, displaced
by a low-frequency function): the largest point displacement / diagonal at
t = 64 and t = 2048 (goal <= 1 %).

`table` prints both tables (Markdown; about 5 minutes) and writes
OUT/sharpen_eval.md and OUT/sharpen_eval.csv (every model, blur and t).
`study` runs the set for each variant of STUDY (filter settings changed from
the defaults: one at a time, then combinations) and each post-fit correction
given (CORRECTIONS, computed in Python from the blurred input and the output
only), one line per variant and correction (about 40 s per variant without
corrections); OUT/sharpen_study.csv has the per-pair rows. --set Name=Value
calls the filter's SetName (repeatable), e.g. --set ScreeningWeight=10;
--correct applies a correction in `table` too.

`times` (the measurements behind the default FlowTime, docs/sharpening.md
"Choosing the flow time"; about 6 minutes): every model and blur, plus a
uniform box (48 x 32 x 24 squares of side 1/32, two triangles each) blurred by
a Gaussian of its positions (sigma 1.5 and 3 edges, no noise) and rounded
with radius 2, 4 and 8 cells (its points moved onto the inner box grown by a
ball: evenly spaced across the rounding, as a scanner samples it), sharpened
at each t of DEFAULT_TIMES (or --times): per pair the normal error and RMS
ratios; per group and t the medians, the pairs visibly sharpened (normal
ratio <= VISIBLE), the pairs worse than the input (a ratio > WORSE), the worst
ratios; the smooth shapes' largest displacement at every t.
OUT/sharpen_times.md and .csv.

`widths` (which t sharpens which blur width: the guidance table; about 1
minute): the box Gaussian-blurred (BOX_SIGMAS) and rounded (BOX_RADII); for
each, the width of its creases' band (faces turned by >= BAND_DEGREES from
every side, counted in rows of squares), the normal error and RMS ratios at
each of WIDTH_TIMES, and the smallest t within SHARP_MARGIN of the lowest
normal ratio. OUT/sharpen_widths.md and .csv.

`cases` (issue 34's two cases; a few seconds): CGAL's fandisk as it comes
(6475 points) blurred by windowed sinc (20 iterations, pass band 0.05) at the
default FlowTime and 2048, normal error and RMS distance against the blurred
input's; vtkSphereSource at resolutions 8, 12, 16: the largest move.

`slivers` (about a minute): a box of sides 1, 0.8, 0.6 in cells of 16 x 12 x 10,
2 x 16 x 12 and 1 x 24 x 18 (square-ish, then long thin cells along x), linearly
subdivided 3 times, blurred sinc1, laplace1 and gauss1: the goal at the best t
of TIMES, per tessellation.
"""
import argparse
import csv
import glob
import math
import os
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# name, linear subdivision levels: the fewest that give at least 15 000 points
MODELS = [("fandisk", 1), ("anchor_dense", 1), ("rotor_small", 2), ("couplingdown", 2),
          ("pinion", 3), ("spool", 3), ("oblong", 3), ("joint", 4), ("part", 4), ("dragknob", 4)]
BLURS = ["sinc1", "sinc2", "laplace1", "laplace2", "gauss1", "gauss2"]
# DEFAULT_T, the filter's default FlowTime, is read from the filter (after the imports below)
TIMES = [256.0, 512.0, 1024.0, 2048.0, 4096.0]
SMOOTH_TIMES = [64.0, 2048.0]
GOAL_NORMAL = 0.70
GOAL_RMS = 1.0
GOAL_SMOOTH = 1.0  # % of the diagonal
# times: the flow times compared for the default; widths: the times tried per blur width
DEFAULT_TIMES = [64.0, 128.0, 256.0, 512.0, 1024.0, 2048.0]
WIDTH_TIMES = [16.0, 32.0, 64.0, 128.0, 256.0, 512.0, 1024.0, 2048.0, 4096.0, 8192.0]
# times: a normal error ratio at or below VISIBLE is a visible sharpening (the
# width of the blended band of normals falls by a fifth); a ratio above WORSE
# (normal error or RMS distance) is worse than the blurred input.
VISIBLE = 0.8
WORSE = 1.02
# widths: the box (cells of side 1/BOX_CELLS: 48 x 32 x 24), the blurs (Gaussian of
# the positions, sigma in edge lengths, no noise) and what counts as the band
# of a blurred crease (faces turned by at least BAND_DEGREES from both sides: 10 %
# of the box's 90 degrees, the 10-90 % rise of README's "Choosing t").
BOX_CELLS = 32
BOX_SIZE = (48, 32, 24)
BOX_SIGMAS = [1.0, 2.0, 3.0, 4.0]
BOX_RADII = [1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0]
BAND_DEGREES = 9.0
# widths: the t that sharpens a blur is the smallest whose normal error ratio is within
# SHARP_MARGIN of the lowest over WIDTH_TIMES (the rest of the reduction is no longer visible)
SHARP_MARGIN = 0.05
NOISE = 0.02       # of the mean length of the edges at each point

# The study: one filter setting at a time, then combinations (a dict of Set* calls).
STUDY = [
    ("defaults", {}),
    ("FitTarget Shear", {"FitTarget": 2}),
    ("FitTarget Projection", {"FitTarget": 0}),
    ("ScreeningWeight 0.1", {"ScreeningWeight": 0.1}),
    ("ScreeningWeight 10", {"ScreeningWeight": 10.0}),
    ("ScreeningWeight 100", {"ScreeningWeight": 100.0}),
    ("FeatureAngle 15", {"FeatureAngle": 15.0}),
    ("FeatureAngle 60", {"FeatureAngle": 60.0}),
    ("FeatureAngle 180", {"FeatureAngle": 180.0}),
    ("NormalSmoothingPasses 1", {"NormalSmoothingPasses": 1}),
    ("NormalSmoothingPasses 2", {"NormalSmoothingPasses": 2}),
    ("NormalSmoothingPasses 4", {"NormalSmoothingPasses": 4}),
    ("SmoothingPasses 0", {"SmoothingPasses": 0}),
    ("SmoothingPasses 4", {"SmoothingPasses": 4}),
    ("Sampling Nearest", {"Sampling": 1}),
    ("SolverIterations 100", {"SolverIterations": 100}),
    ("Solver exact", {"Solver": 2}),
    ("NormalSmoothingPasses 2, ScreeningWeight 10", {"NormalSmoothingPasses": 2, "ScreeningWeight": 10.0}),
    ("NormalSmoothingPasses 2, SmoothingPasses 4", {"NormalSmoothingPasses": 2, "SmoothingPasses": 4}),
    ("NormalSmoothingPasses 2, FeatureAngle 60", {"NormalSmoothingPasses": 2, "FeatureAngle": 60.0}),
    ("FeatureAngle 180, ScreeningWeight 10", {"FeatureAngle": 180.0, "ScreeningWeight": 10.0}),
]


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=["table", "study", "times", "widths", "cases", "slivers"])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"),
                        help="build tree (its lib/python3.*/site-packages has shockfilters)")
    parser.add_argument("--cad", default=os.environ.get("SHOCK_CAD_DIR", os.path.join(
        os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "shockfilters", "cad")))
    parser.add_argument("--scan", default=os.environ.get("SHOCK_SCAN_DIR", os.path.join(
        os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "shockfilters", "scan")))
    parser.add_argument("--meshes", choices=["cad", "scan"], default="cad",
                        help="the CAD tessellations (--cad, subdivided) or the scan set "
                        "(--scan, get_scan_meshes.sh: the same parts remeshed evenly)")
    parser.add_argument("--models", default=",".join(m for m, _ in MODELS))
    parser.add_argument("--blurs", default=",".join(BLURS))
    parser.add_argument("--out", default=os.path.join(ROOT, "build", "sharpen-eval"))
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--correct", default="none")
    parser.add_argument("--no-smooth", action="store_true", help="skip the smooth shapes")
    parser.add_argument("--times", default=None,
                        help="times, widths: comma-separated flow times (default: %s; widths: %s)"
                        % (",".join("%g" % t for t in DEFAULT_TIMES), ",".join("%g" % t for t in WIDTH_TIMES)))
    parser.add_argument("--variants", default=None,
                        help="study: comma-separated variant names (default: all)")
    return parser.parse_args()


ARGS = arguments()
SITE = sorted(glob.glob(os.path.join(ARGS.build, "lib", "python3*", "site-packages")))
sys.path.insert(0, SITE[0] if SITE else ARGS.build)
from shockfilters import vtkOFFReader, vtkPolyDataShockSharpenFilter  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkCommonComputationalGeometry import vtkParametricTorus  # noqa: E402
from vtkmodules.vtkFiltersCore import (vtkCleanPolyData, vtkImplicitPolyDataDistance,  # noqa: E402
                                       vtkMassProperties, vtkSmoothPolyDataFilter,
                                       vtkTriangleFilter, vtkWindowedSincPolyDataFilter)
from vtkmodules.vtkFiltersModeling import vtkLinearSubdivisionFilter  # noqa: E402
from vtkmodules.vtkFiltersSources import (vtkParametricFunctionSource,  # noqa: E402
                                          vtkPlatonicSolidSource, vtkSphereSource)
import scipy.sparse as sparse  # noqa: E402
from scipy.sparse.linalg import factorized  # noqa: E402
from scipy.spatial import cKDTree  # noqa: E402

DEFAULT_T = vtkPolyDataShockSharpenFilter().GetFlowTime()


# ---------------------------------------------------------------- meshes
class Mesh:
    """A triangle mesh as numpy arrays, with the vtkPolyData it came from."""

    def __init__(self, polydata):
        self.polydata = polydata
        self.points = vtk_to_numpy(polydata.GetPoints().GetData()).astype(float)
        self.faces = vtk_to_numpy(polydata.GetPolys().GetConnectivityArray()).reshape(-1, 3)
        edges = np.sort(np.concatenate([self.faces[:, [0, 1]], self.faces[:, [1, 2]],
                                        self.faces[:, [2, 0]]]), axis=1)
        self.edges, counts = np.unique(edges, axis=0, return_counts=True)
        self.closed = bool((counts == 2).all())
        self.diagonal = float(np.linalg.norm(self.points.max(0) - self.points.min(0)))
        self.edge_length = float(np.linalg.norm(
            self.points[self.edges[:, 0]] - self.points[self.edges[:, 1]], axis=1).mean())

    def with_points(self, points):
        out = vtkPolyData()
        out.ShallowCopy(self.polydata)
        p = vtkPoints()
        p.SetData(numpy_to_vtk(np.ascontiguousarray(points), deep=1))
        out.SetPoints(p)
        return out

    def adjacency(self):
        n = len(self.points)
        e = self.edges
        a = sparse.coo_matrix((np.ones(2 * len(e)), (np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]])),
                              shape=(n, n)).tocsr()
        a.data[:] = 1.0
        return a


def face_normals(points, faces):
    n = np.cross(points[faces[:, 1]] - points[faces[:, 0]], points[faces[:, 2]] - points[faces[:, 0]])
    area = np.linalg.norm(n, axis=1)
    return n / np.maximum(area, 1e-300)[:, None], 0.5 * area


def point_normals(points, faces):
    n = np.cross(points[faces[:, 1]] - points[faces[:, 0]], points[faces[:, 2]] - points[faces[:, 0]])
    out = np.zeros_like(points)
    for k in range(3):
        np.add.at(out, faces[:, k], n)
    return out / np.maximum(np.linalg.norm(out, axis=1), 1e-300)[:, None]


def volume(polydata):
    m = vtkMassProperties()
    m.SetInputData(polydata)
    m.Update()
    return m.GetVolume()


def normalised(polydata, levels=0):
    """Clean, triangulate, subdivide `levels` times linearly, centre, scale to a unit diagonal."""
    clean = vtkCleanPolyData()
    clean.SetInputData(polydata)
    clean.PointMergingOn()
    clean.SetTolerance(1e-10)  # of the diagonal: the seams of parametric sources
    tri = vtkTriangleFilter()
    tri.SetInputConnection(clean.GetOutputPort())
    tri.PassVertsOff()
    tri.PassLinesOff()
    last = tri
    if levels:
        sub = vtkLinearSubdivisionFilter()
        sub.SetInputConnection(tri.GetOutputPort())
        sub.SetNumberOfSubdivisions(levels)
        clean2 = vtkCleanPolyData()
        clean2.SetInputConnection(sub.GetOutputPort())
        last = clean2
    last.Update()
    pd = vtkPolyData()
    pd.SetPoints(last.GetOutput().GetPoints())
    pd.SetPolys(last.GetOutput().GetPolys())
    p = vtk_to_numpy(pd.GetPoints().GetData()).astype(float)
    lo, hi = p.min(0), p.max(0)
    p = (p - 0.5 * (lo + hi)) / np.linalg.norm(hi - lo)
    return Mesh(Mesh(pd).with_points(p))


def load_model(name, levels, directory=None):
    path = os.path.join(directory or ARGS.cad, name + ".off")
    if not os.path.exists(path):
        sys.exit("sharpen_eval.py: no %s (run Benchmarks/get_%s_meshes.sh)" % (
            path, "scan" if directory == ARGS.scan else "cad"))
    reader = vtkOFFReader()
    reader.SetFileName(path)
    reader.Update()
    return normalised(reader.GetOutput(), levels)


# ---------------------------------------------------------------- blurs
def vtk_blur(mesh, algorithm):
    algorithm.SetInputData(mesh.polydata)
    algorithm.Update()
    out = vtk_to_numpy(algorithm.GetOutput().GetPoints().GetData()).astype(float)
    assert out.shape == mesh.points.shape
    return out


def windowed_sinc(mesh, pass_band):
    f = vtkWindowedSincPolyDataFilter()
    f.SetNumberOfIterations(20)
    f.SetPassBand(pass_band)
    f.NormalizeCoordinatesOn()
    f.FeatureEdgeSmoothingOff()
    f.BoundarySmoothingOn()
    return vtk_blur(mesh, f)


def laplacian(mesh, iterations):
    f = vtkSmoothPolyDataFilter()
    f.SetNumberOfIterations(iterations)
    f.SetRelaxationFactor(0.1)
    f.FeatureEdgeSmoothingOff()
    f.BoundarySmoothingOn()
    f.SetConvergence(0.0)
    return vtk_blur(mesh, f)


def gaussian(mesh, sigma_edges, seed, noise=NOISE):
    """Gaussian of the positions over the points within ceil(3 sigma) edges, plus noise."""
    p = mesh.points
    sigma = sigma_edges * mesh.edge_length
    hops = int(math.ceil(3 * sigma_edges))
    a = mesh.adjacency() + sparse.identity(len(p), format="csr")
    reach = sparse.identity(len(p), format="csr")
    for _ in range(hops):
        reach = reach @ a
        reach.data[:] = 1.0
    reach = reach.tocoo()
    d2 = ((p[reach.row] - p[reach.col]) ** 2).sum(1)
    w = np.exp(-0.5 * d2 / sigma ** 2)
    w[d2 > (3 * sigma) ** 2] = 0.0
    weights = sparse.csr_matrix((w, (reach.row, reach.col)), shape=reach.shape)
    out = (weights @ p) / np.asarray(weights.sum(1))
    # noise: NOISE times the mean length of the edges at each point
    e = mesh.edges
    length = np.linalg.norm(p[e[:, 0]] - p[e[:, 1]], axis=1)
    local = np.bincount(e.ravel(), np.r_[length, length], len(p)) / np.maximum(
        np.bincount(e.ravel(), minlength=len(p)), 1)
    rng = np.random.default_rng(seed)
    return out + rng.normal(0.0, 1.0, p.shape) * (noise * local)[:, None]


BLUR_PARAMETERS = {"sinc1": ("pass band", 0.05), "sinc2": ("pass band", 0.005),
                   "laplace1": ("iterations", 40), "laplace2": ("iterations", 120),
                   "gauss1": ("sigma", 1.5), "gauss2": ("sigma", 3.0)}


def blur(mesh, name, seed):
    value = BLUR_PARAMETERS[name][1]
    if name.startswith("sinc"):
        return windowed_sinc(mesh, value)
    if name.startswith("laplace"):
        return laplacian(mesh, value)
    return gaussian(mesh, value, seed)


# ---------------------------------------------------------------- corrections
def smooth_field(mesh, values, passes):
    """`passes` umbrella (uniform) averaging passes of a per-point field."""
    a = mesh.adjacency() + sparse.identity(len(mesh.points), format="csr")
    a = sparse.diags(1.0 / np.asarray(a.sum(1)).ravel()) @ a
    for _ in range(passes):
        values = a @ values
    return values


def lumped_mass(points, faces):
    """A third of the area of the triangles around each point."""
    _, area = face_normals(points, faces)
    out = np.zeros(len(points))
    for k in range(3):
        np.add.at(out, faces[:, k], area / 3.0)
    return out


def cotangent_stiffness(points, faces):
    """The cotangent Laplacian (S_ij = -(cot a + cot b) / 2), positive semi-definite."""
    rows, cols, values = [], [], []
    for k in range(3):
        i, j, o = faces[:, k], faces[:, (k + 1) % 3], faces[:, (k + 2) % 3]
        u, v = points[i] - points[o], points[j] - points[o]
        w = 0.5 * (u * v).sum(1) / np.maximum(np.linalg.norm(np.cross(u, v), axis=1), 1e-300)
        rows += [i, j, i, j]
        cols += [j, i, i, j]
        values += [-w, -w, w, w]
    n = len(points)
    return sparse.coo_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(n, n)).tocsr()


def correct(name, mesh, blurred, sharpened):
    """A Python post-fit correction of the sharpened points (knows only the blurred input)."""
    if name == "none":
        return sharpened
    if name == "volume":
        # offset along the point normals so that the volume is the blurred input's
        if not mesh.closed:
            return sharpened
        n = point_normals(sharpened, mesh.faces)
        _, area = face_normals(sharpened, mesh.faces)
        v0 = volume(mesh.with_points(blurred))
        out = sharpened
        for _ in range(3):
            v = volume(mesh.with_points(out))
            out = out + n * ((v0 - v) / area.sum())
        return out
    if name == "normal":
        # keep only the displacement along the blurred input's point normals
        n = point_normals(blurred, mesh.faces)
        d = sharpened - blurred
        return blurred + n * (d * n).sum(1)[:, None]
    if name.startswith("lowpass"):
        # remove the low-frequency part of the displacement (umbrella passes)
        passes = int(name[len("lowpass"):] or 50)
        d = sharpened - blurred
        return sharpened - smooth_field(mesh, d, passes)
    if name.startswith("heat"):
        # remove the displacement's local mean: its heat diffusion over sigma mean edges
        # ((M + sigma^2 l^2 S) d_low = M d on the blurred input, lumped M, cotangent S)
        sigma = float(name[len("heat"):] or 2) * mesh.edge_length
        d = sharpened - blurred
        mass = sparse.diags(lumped_mass(blurred, mesh.faces))
        solve = factorized((mass + sigma * sigma * cotangent_stiffness(blurred, mesh.faces)).tocsc())
        return sharpened - np.stack([solve(mass @ d[:, k]) for k in range(3)], 1)
    if name.startswith("blend"):
        # move only where the normals turned: weight min(1, turn / 10 deg), spread by 2 passes
        n0, _ = face_normals(blurred, mesh.faces)
        n1, _ = face_normals(sharpened, mesh.faces)
        turn = np.degrees(np.arccos(np.clip((n0 * n1).sum(1), -1, 1)))
        limit = float(name[len("blend"):] or 10)
        w = np.zeros(len(mesh.points))
        for k in range(3):
            np.maximum.at(w, mesh.faces[:, k], np.minimum(1.0, turn / limit))
        w = smooth_field(mesh, w, 2)
        return blurred + w[:, None] * (sharpened - blurred)
    raise ValueError(name)


CORRECTIONS = ["none", "volume", "lowpass100", "blend10"]


# ---------------------------------------------------------------- the filter
def make_filter(settings):
    f = vtkPolyDataShockSharpenFilter()
    f.SetNumberOfThreads(1)
    for key, value in settings.items():
        getattr(f, "Set" + key)(value)
    return f


def parse_settings(items):
    settings = {}
    for item in items:
        key, value = item.split("=", 1)
        settings[key] = float(value) if "." in value or "e" in value else int(value)
    return settings


class Reference:
    """The original mesh's measures, against which every result is compared."""

    def __init__(self, mesh):
        self.mesh = mesh
        self.normals, self.areas = face_normals(mesh.points, mesh.faces)
        self.volume = volume(mesh.polydata) if mesh.closed else float("nan")
        self.distance = None
        self.samples = None

    # Barycentric sample points per original triangle, for the nearest original triangle.
    SAMPLES = np.array([[1, 1, 1], [4, 1, 1], [1, 4, 1], [1, 1, 4], [8, 1, 1], [1, 8, 1], [1, 1, 8],
                        [4.5, 4.5, 1], [4.5, 1, 4.5], [1, 4.5, 4.5]], float)

    def exact_shape_error(self, points):
        """The normal error (degrees) that a perfect restoration of the original
        shape would still have where the blur slid triangles across a crease: each
        triangle is given the normal of the original triangle nearest to its
        blurred centroid (the part of the surface it now covers), against its own
        original normal (the nearest triangle found through the nearest of ten
        points spread over each original triangle). About the least any filter
        that restores the shape, without knowing the original numbering,
        scores in this measure."""
        m = self.mesh
        if self.samples is None:
            bary = self.SAMPLES / self.SAMPLES.sum(1)[:, None]
            self.samples = cKDTree(np.einsum("kj,fjd->fkd", bary, m.points[m.faces]).reshape(-1, 3))
        _, index = self.samples.query(points[m.faces].mean(1))
        nearest = self.normals[index // len(self.SAMPLES)]
        angle = np.degrees(np.arccos(np.clip((nearest * self.normals).sum(1), -1.0, 1.0)))
        return float((angle * self.areas).sum() / self.areas.sum())

    def measure(self, points, surface=False):
        m = self.mesh
        n, _ = face_normals(points, m.faces)
        dot = (n * self.normals).sum(1)
        angle = np.degrees(np.arccos(np.clip(dot, -1.0, 1.0)))
        vol = volume(m.with_points(points)) if m.closed else float("nan")
        out = {
            "normal_deg": float((angle * self.areas).sum() / self.areas.sum()),
            "rms_pct": 100 * float(np.sqrt(((points - m.points) ** 2).sum(1).mean())) / m.diagonal,
            "volume_pct": 100 * (vol - self.volume) / self.volume,
            "flipped": int((dot < 0).sum()),
        }
        if surface:
            out["surface_rms_pct"] = self.surface_rms(points)
        return out

    def surface_rms(self, points):
        """RMS distance of the points to the original surface (% of the diagonal; slow)."""
        if self.distance is None:
            self.distance = vtkImplicitPolyDataDistance()
            self.distance.SetInput(self.mesh.polydata)
        values = numpy_to_vtk(np.ascontiguousarray(points), deep=1)
        out = numpy_to_vtk(np.zeros(len(points)), deep=1)
        self.distance.FunctionValue(values, out)
        return 100 * float(np.sqrt((vtk_to_numpy(out) ** 2).mean())) / self.mesh.diagonal


# ---------------------------------------------------------------- runs
def prepare(model_names, blur_names):
    """Originals and blurred inputs (computed once per process)."""
    cases = []
    scan = ARGS.meshes == "scan"
    # the scan set is even already: no subdivision
    levels = {} if scan else dict(MODELS)
    for mi, name in enumerate(model_names):
        mesh = load_model(name, 0, ARGS.scan) if scan else load_model(name, levels.get(name, 0))
        ref = Reference(mesh)
        for bi, b in enumerate(blur_names):
            # the blurred points are kept in OUT/blurred (the Gaussian takes a while)
            cache = os.path.join(ARGS.out, "blurred", "%s%s-%d-%s-%g-%g-%d.npy" % (
                "scan-" if scan else "", name, levels.get(name, 0), b, BLUR_PARAMETERS[b][1], NOISE, 1000 * mi + bi))
            if os.path.exists(cache):
                points = np.load(cache)
            else:
                points = blur(mesh, b, seed=1000 * mi + bi)
                os.makedirs(os.path.dirname(cache), exist_ok=True)
                np.save(cache, points)
            cases.append({"model": name, "blur": b, "mesh": mesh, "ref": ref, "blurred": points,
                          "input": ref.measure(points)})
    return cases


def sharpen(mesh, points, settings, times):
    """The filter's output points at each flow time (one filter: FlowTime alone changes)."""
    f = make_filter(settings)
    f.SetInputData(mesh.with_points(points))
    outputs = []
    for t in times:
        f.SetFlowTime(t)
        f.Update()
        outputs.append((t, vtk_to_numpy(f.GetOutput().GetPoints().GetData()).astype(float),
                        f.GetLastFlippedTriangles()))
    return outputs


def measure_case(case, outputs, correction):
    """Rows (one per flow time) of one blurred mesh's outputs after `correction`."""
    rows = []
    for t, points, filter_flipped in outputs:
        points = correct(correction, case["mesh"], case["blurred"], points)
        m = case["ref"].measure(points)
        m.update(t=t, points=points, filter_flipped=filter_flipped,
                 normal_ratio=m["normal_deg"] / case["input"]["normal_deg"],
                 rms_ratio=m["rms_pct"] / case["input"]["rms_pct"])
        rows.append(m)
    return rows


def best(rows):
    """The row of t in TIMES meeting the goal with the lowest normal error, else the nearest."""
    candidates = [r for r in rows if r["t"] in TIMES]
    passing = [r for r in candidates if r["normal_ratio"] <= GOAL_NORMAL and r["rms_ratio"] <= GOAL_RMS]
    if passing:
        return min(passing, key=lambda r: r["normal_ratio"]), True
    return min(candidates, key=lambda r: max(r["normal_ratio"] / GOAL_NORMAL, r["rms_ratio"] / GOAL_RMS)), False


def smooth_shapes():
    shapes = []
    for res in (8, 12, 16, 32, 64):
        s = vtkSphereSource()
        s.SetThetaResolution(res)
        s.SetPhiResolution(res)
        s.Update()
        shapes.append(("sphere %d" % res, normalised(s.GetOutput())))
    for res in (8, 16, 32, 64):
        s = vtkParametricFunctionSource()
        s.SetParametricFunction(vtkParametricTorus())
        s.SetUResolution(res)
        s.SetVResolution(res)
        s.Update()
        shapes.append(("torus %d" % res, normalised(s.GetOutput())))
    for levels in (3, 5):
        ico = vtkPlatonicSolidSource()
        ico.SetSolidTypeToIcosahedron()
        sub = vtkLinearSubdivisionFilter()
        sub.SetInputConnection(ico.GetOutputPort())
        sub.SetNumberOfSubdivisions(levels)
        sub.Update()
        m = normalised(sub.GetOutput())
        p = m.points / np.linalg.norm(m.points, axis=1)[:, None]
        x, y, z = p.T
        r = 1.0 + 0.15 * np.sin(2 * x + 1) * np.cos(3 * y) + 0.1 * z * z
        m = normalised(m.with_points(p * r[:, None]))
        shapes.append(("blob %d" % len(m.points), m))
    return shapes


def smooth_outputs(shapes, settings):
    return [(name, mesh, sharpen(mesh, mesh.points, settings, SMOOTH_TIMES)) for name, mesh in shapes]


def measure_smooth(outputs, correction):
    rows = []
    for name, mesh, results in outputs:
        row = {"shape": name, "points": len(mesh.points)}
        for t, points, _ in results:
            points = correct(correction, mesh, mesh.points, points)
            row[t] = 100 * float(np.linalg.norm(points - mesh.points, axis=1).max()) / mesh.diagonal
        rows.append(row)
    return rows


# ---------------------------------------------------------------- output
def fmt_vol(v):
    return "-" if math.isnan(v) else "%+.1f" % v


def table(cases, settings, correction, shapes):
    os.makedirs(ARGS.out, exist_ok=True)
    lines = ["| model | points | blur | input: normal error (deg), RMS (% diag) | best t "
             "| normal error ratio | RMS ratio | exact shape: normal error ratio | surface RMS input → output (% diag) "
             "| volume input → output (%) | flipped input → output (filter) | t = DEFAULT (default): normal, RMS ratio "
             "| goal |".replace("DEFAULT", "%g" % DEFAULT_T),
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    allrows = []
    passed = 0
    for case in cases:
        outputs = sharpen(case["mesh"], case["blurred"], settings, [DEFAULT_T] + TIMES)
        rows = measure_case(case, outputs, correction)
        b, ok = best(rows)
        passed += ok
        r64 = rows[0]
        surface_in = case["ref"].surface_rms(case["blurred"])
        surface_out = case["ref"].surface_rms(b["points"])
        exact = case["ref"].exact_shape_error(case["blurred"]) / case["input"]["normal_deg"]
        lines.append("| %s | %d | %s | %.2f, %.3f | %g | %.2f | %.2f | %.2f | %.3f → %.3f | %s → %s | %d → %d (%d) "
                     "| %.2f, %.2f | %s |" % (
                         case["model"], len(case["mesh"].points), case["blur"], case["input"]["normal_deg"],
                         case["input"]["rms_pct"], b["t"], b["normal_ratio"], b["rms_ratio"], exact,
                         surface_in, surface_out, fmt_vol(case["input"]["volume_pct"]),
                         fmt_vol(b["volume_pct"]), case["input"]["flipped"], b["flipped"],
                         b["filter_flipped"], r64["normal_ratio"], r64["rms_ratio"],
                         "pass" if ok else "fail"))
        print(lines[-1], flush=True)
        for r in rows:
            allrows.append(dict(model=case["model"], blur=case["blur"], t=r["t"],
                                input_normal_deg=case["input"]["normal_deg"],
                                input_rms_pct=case["input"]["rms_pct"],
                                input_volume_pct=case["input"]["volume_pct"],
                                input_flipped=case["input"]["flipped"], exact_shape_ratio=exact,
                                **{k: r[k] for k in ("normal_deg", "rms_pct", "volume_pct", "flipped",
                                                     "filter_flipped", "normal_ratio", "rms_ratio")},
                                best=int(r is b), goal=int(ok and r is b)))
    summary = "goal met on %d of %d model × blur pairs" % (passed, len(cases))
    lines += ["", summary]
    print("\n" + summary, flush=True)
    if shapes:
        srows = measure_smooth(smooth_outputs(shapes, settings), correction)
        lines += ["", "| smooth shape | points | largest displacement at t = 64 (% diag) | at t = 2048 "
                  "| goal (≤ 1 %) |", "|---|---|---|---|---|"]
        for r in srows:
            ok = max(r[t] for t in SMOOTH_TIMES) <= GOAL_SMOOTH
            lines.append("| %s | %d | %.3f | %.3f | %s |" % (r["shape"], r["points"], r[64.0], r[2048.0],
                                                           "pass" if ok else "fail"))
            print(lines[-1], flush=True)
            allrows.append(dict(model=r["shape"], blur="none", t="64/2048",
                                rms_pct="%.4f/%.4f" % (r[64.0], r[2048.0]), goal=int(ok)))
    with open(os.path.join(ARGS.out, "sharpen_eval.csv"), "w", newline="") as out:
        w = csv.DictWriter(out, fieldnames=list(allrows[0].keys()))
        w.writeheader()
        for r in allrows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
    with open(os.path.join(ARGS.out, "sharpen_eval.md"), "w") as out:
        out.write("\n".join(lines) + "\n")


def study(cases, shapes):
    os.makedirs(ARGS.out, exist_ok=True)
    variants = STUDY
    if ARGS.variants:
        wanted = ARGS.variants.split(",")
        variants = [v for v in STUDY if v[0] in wanted]
    corrections = CORRECTIONS if ARGS.correct == "all" else ARGS.correct.split(",")
    print("| settings | correction | goal met (of %d) | median normal ratio | median RMS ratio "
          "| failing models (pairs) | smooth: largest displacement at t = 64 / 2048 (%% diag), failing |"
          % len(cases))
    print("|---|---|---|---|---|---|---|")
    out = []
    for vname, settings in variants:
        t0 = time.time()
        raw = [sharpen(c["mesh"], c["blurred"], settings, TIMES) for c in cases]
        sraw = smooth_outputs(shapes, settings) if shapes else []
        for correction in corrections:
            results = []
            for case, outputs in zip(cases, raw):
                b, ok = best(measure_case(case, outputs, correction))
                results.append((case, b, ok))
            srows = measure_smooth(sraw, correction)
            s64 = max((r[64.0] for r in srows), default=float("nan"))
            s2048 = max((r[2048.0] for r in srows), default=float("nan"))
            sfail = [r["shape"] for r in srows if max(r[64.0], r[2048.0]) > GOAL_SMOOTH]
            failing = {}
            for c, _, ok in results:
                if not ok:
                    failing[c["model"]] = failing.get(c["model"], 0) + 1
            print("| %s | %s | %d | %.2f | %.2f | %s | %.2f / %.2f, %d of %d: %s |" % (
                vname, correction, sum(ok for _, _, ok in results),
                statistics.median(b["normal_ratio"] for _, b, _ in results),
                statistics.median(b["rms_ratio"] for _, b, _ in results),
                " ".join("%s (%d)" % kv for kv in failing.items()), s64, s2048, len(sfail), len(srows),
                ", ".join(sfail)), flush=True)
            for c, b, ok in results:
                out.append(dict(settings=vname, correction=correction, model=c["model"], blur=c["blur"],
                                t=b["t"], goal=int(ok), normal_ratio="%.4f" % b["normal_ratio"],
                                rms_ratio="%.4f" % b["rms_ratio"], volume_pct="%.3f" % b["volume_pct"],
                                flipped=b["flipped"], smooth_t64="", smooth_t2048=""))
            for r in srows:
                out.append(dict(settings=vname, correction=correction, model=r["shape"], blur="none",
                                t="", goal=int(max(r[64.0], r[2048.0]) <= GOAL_SMOOTH), normal_ratio="",
                                rms_ratio="", volume_pct="", flipped="", smooth_t64="%.4f" % r[64.0],
                                smooth_t2048="%.4f" % r[2048.0]))
        sys.stderr.write("  (%s: %.0f s)\n" % (vname, time.time() - t0))
    with open(os.path.join(ARGS.out, "sharpen_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(out[0].keys()))
        w.writeheader()
        w.writerows(out)


# ---------------------------------------------------------------- default flow time, blur widths
def box_mesh(size=BOX_SIZE, lengths=None):
    """The faces of a box of `size` cells, two triangles per cell, centred: by
    default cells of side 1/BOX_CELLS (a uniform mesh whose sharp original is
    known); with `lengths`, the box's sides, whose cells may be long and thin."""
    lengths = lengths or [s / float(BOX_CELLS) for s in size]
    ids, points, faces = {}, [], []

    def point(g):
        if g not in ids:
            ids[g] = len(points)
            points.append([(g[a] / float(size[a]) - 0.5) * lengths[a] for a in range(3)])
        return ids[g]

    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, 1):
            for i in range(size[u]):
                for j in range(size[v]):
                    quad = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        g = [0, 0, 0]
                        g[axis] = side * size[axis]
                        g[u], g[v] = i + du, j + dv
                        quad.append(point(tuple(g)))
                    if not side:
                        quad.reverse()  # outward normals
                    faces += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    pd = vtkPolyData()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.asarray(points, dtype=float), deep=1))
    pd.SetPoints(p)
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    cells = vtkCellArray()
    for f in faces:
        cells.InsertNextCell(3, f)
    pd.SetPolys(cells)
    return Mesh(pd)


def band_width(mesh, points):
    """Width of a blurred box's creases in cells of the grid (the rows of squares a user
    counts across a rounded band): the faces turned by at least BAND_DEGREES from every
    side of the box (the 10-90 % rise of the normal across a 90-degree crease), counted by
    their area in the original (2 triangles a cell), over the length of the 12 creases."""
    n, _ = face_normals(points, mesh.faces)
    turned = np.degrees(np.arccos(np.clip(np.abs(n).max(1), 0.0, 1.0)))
    _, area = face_normals(mesh.points, mesh.faces)
    length = 4.0 * sum(BOX_SIZE) / BOX_CELLS
    return float(area[turned >= BAND_DEGREES].sum()) / length * BOX_CELLS


def rounded(mesh, radius_cells):
    """The box's points moved onto the box rounded with radius `radius_cells` cells (the
    inner box grown by a ball, as Examples/sharpen_mesh_geometry.py makes it): each point
    goes to the nearest point of the inner box plus `radius` along the way out. The points
    stay nearly evenly spaced across the rounding, as a scanner samples a rounded crease."""
    half = 0.5 * np.asarray(BOX_SIZE, dtype=float) / BOX_CELLS
    r = radius_cells / BOX_CELLS
    x = mesh.points
    nearest = np.clip(x, -(half - r), half - r)
    away = x - nearest
    length = np.linalg.norm(away, axis=1)[:, None]
    return nearest + r * away / np.where(length > 0, length, 1.0)


def box_cases(sigmas, radii=()):
    """The box blurred by a Gaussian of its positions (sigma in edge lengths, no noise) and
    rounded with each radius (in cells)."""
    mesh = box_mesh()
    ref = Reference(mesh)
    cases = []
    blurs = [("gauss %g" % s, gaussian(mesh, s, seed=k, noise=0.0)) for k, s in enumerate(sigmas)]
    blurs += [("round %g" % r, rounded(mesh, r)) for r in radii]
    for name, points in blurs:
        cases.append({"model": "box", "blur": name, "mesh": mesh, "ref": ref,
                      "blurred": points, "input": ref.measure(points),
                      "width": band_width(mesh, points)})
    return cases


def parse_times(default):
    return [float(t) for t in ARGS.times.split(",")] if ARGS.times else list(default)


def times(cases, settings, shapes):
    """Normal error and RMS ratios at each flow time, per pair and summed up, and how far the
    smooth shapes move at each (the measurements behind the default FlowTime)."""
    os.makedirs(ARGS.out, exist_ok=True)
    ts = parse_times(DEFAULT_TIMES)
    lines = ["| model | blur | input: normal (deg), RMS (% diag) | " + " | ".join(
        "t = %g: normal / RMS ratio" % t for t in ts) + " |", "|---|---|---|" + "---|" * len(ts)]
    rows = []
    for case in cases:
        measured = measure_case(case, sharpen(case["mesh"], case["blurred"], settings, ts), "none")
        lines.append("| %s | %s | %.2f, %.3f | %s |" % (
            case["model"], case["blur"], case["input"]["normal_deg"], case["input"]["rms_pct"],
            " | ".join("%.2f / %.2f" % (r["normal_ratio"], r["rms_ratio"]) for r in measured)))
        print(lines[-1], flush=True)
        for r in measured:
            rows.append(dict(model=case["model"], blur=case["blur"], t=r["t"],
                             input_normal_deg=case["input"]["normal_deg"], input_rms_pct=case["input"]["rms_pct"],
                             normal_ratio=r["normal_ratio"], rms_ratio=r["rms_ratio"],
                             flipped_in=case["input"]["flipped"], flipped_out=r["flipped"]))
    groups = [("CAD parts (all ten)", lambda r: r["model"] != "box"),
              ("uniform meshes (fandisk, anchor_dense)", lambda r: r["model"] in ("fandisk", "anchor_dense")),
              ("CAD tessellations (the other eight parts)",
               lambda r: r["model"] not in ("fandisk", "anchor_dense", "box")),
              ("boxes (Gaussian sigma 1.5, 3 edges; rounded r = 2, 4, 8 cells)", lambda r: r["model"] == "box")]
    lines += ["", "| pairs | t | median normal / RMS ratio | normal ratio ≤ %.2f (visible) | worse than the "
              "input (a ratio > %.2f): normal, RMS | worst normal / RMS ratio | more flipped triangles than the input |"
              % (VISIBLE, WORSE), "|---|---|---|---|---|---|---|"]
    for gname, member in groups:
        for t in ts:
            sel = [r for r in rows if r["t"] == t and member(r)]
            if not sel:
                continue
            lines.append("| %s (%d) | %g | %.2f / %.2f | %d | %d, %d | %.2f / %.2f | %d |" % (
                gname, len(sel), t, statistics.median(r["normal_ratio"] for r in sel),
                statistics.median(r["rms_ratio"] for r in sel),
                sum(r["normal_ratio"] <= VISIBLE for r in sel),
                sum(r["normal_ratio"] > WORSE for r in sel), sum(r["rms_ratio"] > WORSE for r in sel),
                max(r["normal_ratio"] for r in sel), max(r["rms_ratio"] for r in sel),
                sum(r["flipped_out"] > r["flipped_in"] for r in sel)))
            print(lines[-1], flush=True)
    if shapes:
        lines += ["", "| smooth shape | points | " + " | ".join("t = %g" % t for t in ts) +
                  " | goal (≤ 1 % at every t) |", "|---|---|" + "---|" * (len(ts) + 1)]
        for name, mesh in shapes:
            moved = [100 * float(np.linalg.norm(p - mesh.points, axis=1).max()) / mesh.diagonal
                     for _, p, _ in sharpen(mesh, mesh.points, settings, ts)]
            lines.append("| %s | %d | %s | %s |" % (name, len(mesh.points), " | ".join("%.3f" % m for m in moved),
                                                    "pass" if max(moved) <= GOAL_SMOOTH else "fail"))
            print(lines[-1], flush=True)
            for t, m in zip(ts, moved):
                rows.append(dict(model=name, blur="none", t=t, input_normal_deg="", input_rms_pct="",
                                 normal_ratio="", rms_ratio=m, flipped_in="", flipped_out=""))
    with open(os.path.join(ARGS.out, "sharpen_times.csv"), "w", newline="") as out:
        w = csv.DictWriter(out, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
    with open(os.path.join(ARGS.out, "sharpen_times.md"), "w") as out:
        out.write("\n".join(lines) + "\n")


def widths(settings):
    """Which flow time sharpens which blur width: Gaussian-blurred boxes (BOX_SIGMAS), the band
    of each measured in edge lengths, the normal error and RMS ratios at each of WIDTH_TIMES."""
    os.makedirs(ARGS.out, exist_ok=True)
    ts = parse_times(WIDTH_TIMES)
    lines = ["| blur | crease band (cells) | input: normal (deg), RMS (% diag) | " +
             " | ".join("t = %g" % t for t in ts) + " | t that sharpens |", "|---|---|---|" + "---|" * (len(ts) + 1)]
    rows = []
    for case in box_cases(BOX_SIGMAS, BOX_RADII):
        measured = measure_case(case, sharpen(case["mesh"], case["blurred"], settings, ts), "none")
        lowest = min(r["normal_ratio"] for r in measured)
        enough = next(r for r in measured if r["normal_ratio"] <= lowest + SHARP_MARGIN)
        lines.append("| %s | %.1f | %.2f, %.3f | %s | %g (%.2f / %.2f) |" % (
            case["blur"], case["width"], case["input"]["normal_deg"], case["input"]["rms_pct"],
            " | ".join("%.2f / %.2f" % (r["normal_ratio"], r["rms_ratio"]) for r in measured),
            enough["t"], enough["normal_ratio"], enough["rms_ratio"]))
        print(lines[-1], flush=True)
        for r in measured:
            rows.append(dict(blur=case["blur"], band_cells=case["width"], t=r["t"],
                             input_normal_deg=case["input"]["normal_deg"], input_rms_pct=case["input"]["rms_pct"],
                             normal_ratio=r["normal_ratio"], rms_ratio=r["rms_ratio"], sharpens=int(r is enough)))
    with open(os.path.join(ARGS.out, "sharpen_widths.csv"), "w", newline="") as out:
        w = csv.DictWriter(out, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
    with open(os.path.join(ARGS.out, "sharpen_widths.md"), "w") as out:
        out.write("\n".join(lines) + "\n")


# slivers: the box of sides SLIVER_BOX in cells of these counts per axis, linearly
# subdivided 3 times: square-ish cells, then cells 10 and about 24 times longer
# than wide along x (a CAD tessellation's long thin triangles), on a shape
# without curved faces.
SLIVER_BOX = [1.0, 0.8, 0.6]
SLIVER_CELLS = [(16, 12, 10), (2, 16, 12), (1, 24, 18)]


def slivers(settings):
    """The same box tessellated with square-ish and with long thin cells,
    blurred sinc1, laplace1 and gauss1: whether the tessellation alone makes
    the sinc and Laplacian blurs fail (docs/sharpening.md)."""
    print("| cells (x, y, z) | points | triangle aspect (area-weighted median of longest / shortest edge) | blur "
          "| input: normal (deg), RMS (% diag) | best t | normal ratio | RMS ratio | exact shape: normal ratio | goal |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    passed = total = 0
    for cells in SLIVER_CELLS:
        mesh = normalised(box_mesh(cells, SLIVER_BOX).polydata, 3)
        ref = Reference(mesh)
        p, f = mesh.points, mesh.faces
        edges = np.stack([np.linalg.norm(p[f[:, k]] - p[f[:, (k + 1) % 3]], axis=1) for k in range(3)], 1)
        ratio = edges.max(1) / edges.min(1)
        _, area = face_normals(p, f)
        order = np.argsort(ratio)
        aspect = float(ratio[order][np.searchsorted(np.cumsum(area[order]), 0.5 * area.sum())])
        for b in ("sinc1", "laplace1", "gauss1"):
            blurred = blur(mesh, b, seed=7)
            case = {"mesh": mesh, "ref": ref, "blurred": blurred, "input": ref.measure(blurred)}
            row, ok = best(measure_case(case, sharpen(mesh, blurred, settings, TIMES), "none"))
            passed += ok
            total += 1
            print("| %s | %d | %.1f | %s | %.2f, %.3f | %g | %.2f | %.2f | %.2f | %s |" % (
                cells, len(p), aspect, b, case["input"]["normal_deg"], case["input"]["rms_pct"], row["t"],
                row["normal_ratio"], row["rms_ratio"], ref.exact_shape_error(blurred) / case["input"]["normal_deg"],
                "pass" if ok else "fail"), flush=True)
    print("\ngoal met on %d of %d" % (passed, total))


def issue_cases(settings):
    """Issue 34's two cases: CGAL's fandisk as it comes (6475 points, no
    subdivision) blurred by windowed sinc (20 iterations, pass band 0.05),
    and vtkSphereSource at resolutions 8, 12 and 16, sharpened at the default
    FlowTime and at 2048 with the defaults and `settings`."""
    mesh = load_model("fandisk", 0)
    ref = Reference(mesh)
    blurred = windowed_sinc(mesh, 0.05)
    before = ref.measure(blurred)
    print("| case | t | normal error (deg) | ratio | RMS distance (% diag) | ratio |")
    print("|---|---|---|---|---|---|")
    print("| fandisk (%d points), windowed sinc | input | %.2f | | %.3f | |" % (
        len(mesh.points), before["normal_deg"], before["rms_pct"]))
    for t, points, _ in sharpen(mesh, blurred, settings, [DEFAULT_T, 2048.0]):
        after = ref.measure(points)
        print("| | %g | %.2f | %.2f | %.3f | %.2f |" % (t, after["normal_deg"], after["normal_deg"] / before["normal_deg"],
                                                    after["rms_pct"], after["rms_pct"] / before["rms_pct"]))
    for res in (8, 12, 16):
        s = vtkSphereSource()
        s.SetThetaResolution(res)
        s.SetPhiResolution(res)
        s.Update()
        sphere = Mesh(s.GetOutput())
        for t, points, _ in sharpen(sphere, sphere.points, settings, [DEFAULT_T, 2048.0]):
            move = np.linalg.norm(points - sphere.points, axis=1).max() / sphere.diagonal
            print("| vtkSphereSource %d: largest move (%% diag) | %g | | | %.3f | |" % (res, t, 100 * move))


def main():
    t0 = time.time()
    if ARGS.mode == "cases":
        issue_cases(parse_settings(ARGS.set))
        return
    if ARGS.mode == "slivers":
        slivers(parse_settings(ARGS.set))
        return
    if ARGS.mode == "widths":
        widths(parse_settings(ARGS.set))
        sys.stderr.write("%.0f s\n" % (time.time() - t0))
        return
    cases = prepare(ARGS.models.split(","), ARGS.blurs.split(",")) if ARGS.models else []
    if ARGS.mode == "times":
        cases += box_cases([1.5, 3.0], [2.0, 4.0, 8.0])
    shapes = [] if ARGS.no_smooth else smooth_shapes()
    sys.stderr.write("prepared %d blurred meshes in %.0f s\n" % (len(cases), time.time() - t0))
    if ARGS.mode == "table":
        table(cases, parse_settings(ARGS.set), ARGS.correct, shapes)
    elif ARGS.mode == "times":
        times(cases, parse_settings(ARGS.set), shapes)
    else:
        study(cases, shapes)
    sys.stderr.write("%.0f s\n" % (time.time() - t0))


if __name__ == "__main__":
    main()
