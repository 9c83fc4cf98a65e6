"""Parallel robustness of the shock filters (surfaces, and the image filter's gradient domain): bad pieces, disagreeing ranks, aborts.

Usage: mpirun -np N pvbatch --symmetric --mpi TestShockFiltersMPIRobustness.py PLUGIN_PATH OUTPUT_DIR [CASES]

Every process runs this script (--symmetric). Each one builds its own piece
with plain VTK classes and runs the project's VTK classes directly, as a VTK
user would: filter.SetController(global controller), SetInputData(piece),
UpdatePiece(rank, N, 0). The classes come from the Python package
`shockfilters` of the build tree, found next to PLUGIN_PATH (or on
PYTHONPATH); the plugin itself is not loaded. OUTPUT_DIR is created but
nothing is written there: the records travel through the controller.
CASES (optional) is a comma-separated list of case names or dotted prefixes
of them to run (default: all; e.g. "abort,bad_cell_id.sharpen"), for debugging.

A piece is the rank-th of N slabs of a triangulated sphere (cells sorted by
the z of their centre), with the point scalar "Elevation" (active). Every
case gathers one record per process (return value of UpdatePiece, the errors
vtkOutputWindow received, output sizes) onto process 0 with the controller;
process 0 prints a MEASURE line with what each process did and checks:

- replicated: every process holds the same whole sphere: the result is the
  serial one (the plumbing of this script; the filter works on process 0).
- source pieces: vtkSphereSource (64 x 64) -> vtkElevationFilter -> advection,
  the source cutting its own pieces: the points not marked in vtkGhostType
  are exactly the serial points (matched by coordinates), with the serial
  advected Elevation (1e-9 of its range); as many cells as serial.
- nan coordinate: a NaN coordinate in the bad process's piece (advection and
  sharpen): UpdatePiece returns 0 on every process, each logs exactly one
  error, the same text everywhere, naming the bad process ("process K" or
  "rank K") and saying NaN / not finite.
- isolated far point: a point used by no cell at x = 1e200 appended to the
  bad piece (advection): no crash, no hang, every process returns the same status.
- bad cell id: a triangle, a line and a vertex (separately) with a point id
  out of range in the bad piece (advection and sharpen): every process fails
  with the same one-line error naming the bad process; no crash.
- array name mismatch: the active point scalars are "Heat" on the processes
  and "Temperature" on the bad one (advection): every process fails with the
  same error (naming the mismatch), and no process outputs filtered values.
- array layout mismatch: the active point scalars "Elevation" with 3
  components, or as unsigned char, on the bad process (advection): every
  process fails with the same one-line error naming what differs.
- iterations mismatch: SolverIterations 25 and 30 on the bad process
  (sharpen): every process fails with the same error about the iterations.
- flow mode mismatch: Composed with 4 updates (no ring stencil) on the bad
  process, Fixed on the others (both surface filters): every process fails
  with the same error naming FlowMode.
- a filter before the shock filter fails on the bad process (a Python
  algorithm whose RequestData returns 0 there; the surface filters on a
  piece, the image filter on vtkRTAnalyticSource's pieces): every process
  fails with the same one-line error naming the bad process and saying its
  input failed to update (the shock filter still executes there to tell the
  others, which wait in a collective step), and the outputs are empty. The
  same pipeline without a controller (serial), or with it but no pieces: the
  shock filter does not execute and adds no error of its own. The same again
  after the failing filter changed.
- a filter before the shock filter fails on the bad process in its
  information pass (RequestInformation returns 0 there, as a reader whose
  file is missing on one node): the same checks, through the VTK classes'
  executive and through ParaView's (the VTK object of a plugin proxy).
- the same in its data-object pass (RequestDataObject returns 0 there, as a
  reader that cannot tell its output's type): the same checks, both
  executives, and the failing filter, which has no output object there, is
  asked for nothing more (no information, update extent or data).
- image grid differs: vtkRTAnalyticSource's pieces, the bad process's image
  with another whole extent, spacing or origin: every process fails with the
  same one-line error naming the image's grid and what differs (before, the
  pieces were filtered as if they fitted, and samples were owned by no
  process); the bad process's grid mended and the change applied on every
  process, the same filters run and their pieces tile the image.
- image piece asked twice: the bad process asks for the piece of the one
  before it: every process fails with the same one-line error naming the bad
  process (before, both filtered that piece with success, and the halos
  beside the piece no one asked for were wrong: values 0.5 % of the range
  off); each asking for its own piece, all then run.
- input of another type: a vtkImageData before a surface filter, a
  vtkPolyData before the image filter, on the bad process: VTK refused it
  there alone and the other processes hung; now every process stops with
  the same one-line error naming the type (the last error on the bad
  process, after VTK's own); without a controller VTK refuses it on the bad
  process only.
- image Domain Gradients on pieces: vtkRTAnalyticSource -> the image filter
  with Domain Gradients, the source cutting its pieces: every process fails
  with the same one-line error (the solve needs the whole image), empty output.
- image abort on process 0: the same during Image Shock Advection of a
  diagonal step whose pieces would grow their halo: every process returns
  after one attempt (the abort is agreed with the halo's reduction).
- image abort with pieces read with their halo: vtkRTAnalyticSource feeds
  the filter directly (each piece read with its halo), process 0 aborts at
  its first progress report: every process returns, and process 0's output
  holds its piece's own values (not an empty array).
- abort on process 0: a ProgressEvent observer on process 0 only sets
  AbortExecute during a sharpening of a 200 x 200 sphere: every process
  returns from UpdatePiece and reaches the Barrier after it.

The bad process is 1; with 3 or more processes each failure case runs again
with the last process bad. "Exactly one error" counts the filter's own
errors: the executive's "returned failure for request" that follows any
failed RequestData is left out, and texts are compared without their
"ERROR: In file, line" header and object address.

A hang is not detected here: the test's `timeout` ends the run (cases that
may hang come last). Prints "FAIL: ..." per failed check and ends with
"N passed, M failed" on process 0; the exit code is 1 on any failure (on
every process). An exception in a case is a failure and the remaining cases
still run; every process reaches every gather.
"""
import glob
import itertools
import os
import pickle
import re
import sys
import time
import traceback

import numpy as np

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.util.vtkAlgorithm import VTKPythonAlgorithmBase
from vtkmodules.util.vtkConstants import VTK_STRING, VTK_UNSIGNED_CHAR
from vtkmodules.vtkCommonCore import vtkIdTypeArray, vtkOutputWindow, vtkPoints, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkElevationFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkParallelCore import vtkMultiProcessController

PLUGIN, OUTPUT = sys.argv[1], sys.argv[2]
SELECTED = set(sys.argv[3].split(",")) if len(sys.argv) > 3 and sys.argv[3] else None
os.makedirs(OUTPUT, exist_ok=True)


def find_package():
    """Put the build tree's `shockfilters` package (the directory of vtkFiltersShock*.so)
    on sys.path, unless it is importable already (PYTHONPATH)."""
    try:
        import shockfilters  # noqa: F401
        return
    except ImportError:
        pass
    directory = os.path.dirname(os.path.abspath(PLUGIN))
    while not os.path.exists(os.path.join(directory, "CMakeCache.txt")):  # up to the build tree
        if os.path.dirname(directory) == directory:
            return
        directory = os.path.dirname(directory)
    usual = glob.glob(os.path.join(directory, "lib*", "python*", "site-packages", "shockfilters"))
    anywhere = (root for root, dirs, files in os.walk(directory) if os.path.basename(root) == "shockfilters")
    for package in itertools.chain(usual, anywhere):
        if glob.glob(os.path.join(package, "vtkFiltersShock*.so")):
            sys.path.insert(0, os.path.dirname(package))
            return


find_package()
from shockfilters import (vtkImageShockAdvectionFilter, vtkPolyDataShockAdvectionFilter,  # noqa: E402
                          vtkPolyDataShockSharpenFilter)
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource  # noqa: E402

controller = vtkMultiProcessController.GetGlobalController()
RANK = controller.GetLocalProcessId() if controller else 0
PROCESSES = controller.GetNumberOfProcesses() if controller else 1

passed = 0
failures = []


def check(condition, message):
    """A check, judged on process 0."""
    global passed
    if condition:
        passed += 1
    else:
        failures.append(message)
        print("FAIL:", message, flush=True)
    return condition


class Messages:
    """Errors reaching vtkOutputWindow on this process."""

    def __init__(self):
        self.errors = []
        vtkOutputWindow.GetInstance().AddObserver("ErrorEvent", self._error)

    @calldata_type(VTK_STRING)
    def _error(self, caller, event, text):
        self.errors.append(text)

    def take(self):
        """The filter errors since the last take, as message texts (see message_text)."""
        texts = [message_text(e) for e in self.errors if "returned failure for request" not in e]
        del self.errors[:]
        return texts


def message_text(error):
    """An error without its "ERROR: In file, line N" header and "Class (0x...): " prefix."""
    lines = error.strip().splitlines()
    if lines and lines[0].startswith("ERROR: In "):
        lines = lines[1:]
    return re.sub(r"^\w+ \(0x[0-9a-fA-F]+\): ", "", "\n".join(lines).strip())


messages = Messages()


# --- Gathering records onto process 0 -----------------------------------------------

def all_gather_bytes(data):
    """Every process's `data` (bytes), in rank order, on every process."""
    if PROCESSES == 1:
        return [data]
    length = vtkIdTypeArray()
    length.InsertNextValue(len(data))
    lengths = vtkIdTypeArray()
    controller.AllGather(length, lengths)
    sizes = [int(lengths.GetValue(k)) for k in range(PROCESSES)]
    width = max(max(sizes), 1)
    send = numpy_to_vtk(np.frombuffer(data.ljust(width, b"\0"), np.uint8).copy(), deep=1,
                        array_type=VTK_UNSIGNED_CHAR)
    received = vtkUnsignedCharArray()
    controller.AllGather(send, received)
    flat = vtk_to_numpy(received).tobytes()
    return [flat[k * width:k * width + sizes[k]] for k in range(PROCESSES)]


def gather(record):
    """Every process's record (any picklable object), in rank order, on every process."""
    return [pickle.loads(b) for b in all_gather_bytes(pickle.dumps(record))]


def broadcast_int(value):
    if PROCESSES == 1:
        return value
    array = vtkIdTypeArray()
    array.InsertNextValue(value)
    controller.Broadcast(array, 0)
    return int(array.GetValue(0))


# --- Pieces ----------------------------------------------------------------------------

def sphere(resolution):
    source = vtkSphereSource()
    source.SetThetaResolution(resolution)
    source.SetPhiResolution(resolution)
    source.SetOutputPointsPrecision(1)  # double
    source.Update()
    return source.GetOutput()


def triangles(mesh):
    polys = mesh.GetPolys()
    return vtk_to_numpy(polys.GetConnectivityArray()).reshape(-1, 3).astype(np.int64)


def cell_array(connectivity, size):
    """A vtkCellArray of cells of `size` points from a flat id list (ids are not checked)."""
    connectivity = np.ascontiguousarray(connectivity, dtype=np.int64).ravel()
    offsets = np.arange(0, len(connectivity) + 1, size, dtype=np.int64)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=1), numpy_to_vtkIdTypeArray(connectivity, deep=1))
    return cells


def make_polydata(points, polys, scalars_name="Elevation"):
    """Triangles over double points, with the active point scalars `scalars_name` (a blurred step)."""
    mesh = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    vtk_points.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=1))
    mesh.SetPoints(vtk_points)
    mesh.SetPolys(cell_array(polys, 3))
    finite = np.nan_to_num(points, nan=0.0, posinf=0.0, neginf=0.0)
    values = numpy_to_vtk(np.tanh((finite[:, 2] + 0.3 * finite[:, 0]) * 6.0), deep=1)
    values.SetName(scalars_name)
    mesh.GetPointData().SetScalars(values)
    return mesh


def slab(resolution, rank=None, pieces=None, scalars_name="Elevation"):
    """The rank-th of `pieces` slabs of a sphere (cells by the z of their centre), its
    points compacted; the whole sphere when rank is None. Returns (points, triangles)."""
    whole = sphere(resolution)
    points = vtk_to_numpy(whole.GetPoints().GetData()).astype(float)
    cells = triangles(whole)
    if rank is not None:
        order = np.argsort(points[cells].mean(axis=1)[:, 2], kind="stable")
        cells = cells[np.sort(np.array_split(order, pieces)[rank])]
        used = np.unique(cells)
        renumber = np.full(len(points), -1, np.int64)
        renumber[used] = np.arange(len(used))
        points, cells = points[used], renumber[cells]
    return points, cells


def piece_mesh(resolution=32, scalars_name="Elevation"):
    return make_polydata(*slab(resolution, RANK, PROCESSES), scalars_name=scalars_name)


# --- Running a filter on this process's piece ---------------------------------------------

FILTERS = {"advection": vtkPolyDataShockAdvectionFilter, "sharpen": vtkPolyDataShockSharpenFilter}


def run(kind, piece, label, configure=None, observe=None):
    """UpdatePiece(rank, N, 0) of a fresh filter on `piece`; this process's record."""
    algorithm = FILTERS[kind]()
    algorithm.SetController(controller)
    algorithm.SetNumberOfThreads(1)
    if configure:
        configure(algorithm)
    if observe:
        algorithm.AddObserver("ProgressEvent", observe)
    algorithm.SetInputData(piece)
    messages.take()
    start = time.time()
    rc = algorithm.UpdatePiece(RANK, PROCESSES, 0)
    seconds = time.time() - start
    print("rank %d: %s returned %s after %.2f s" % (RANK, label, rc, seconds), flush=True)
    output = algorithm.GetOutput()
    record = {"rank": RANK, "rc": rc, "errors": messages.take(), "seconds": seconds,
              "points": output.GetNumberOfPoints(), "cells": output.GetNumberOfCells()}
    return record, algorithm


def owned_points(mesh, array_name):
    """(coordinates, values) of the points not marked in vtkGhostType (all without the array)."""
    if mesh.GetNumberOfPoints() == 0:
        return np.zeros((0, 3)), np.zeros(0)
    coordinates = vtk_to_numpy(mesh.GetPoints().GetData()).astype(float)
    array = mesh.GetPointData().GetArray(array_name)
    values = vtk_to_numpy(array).astype(float) if array else np.full(len(coordinates), np.nan)
    ghost = mesh.GetPointData().GetArray("vtkGhostType")
    owned = vtk_to_numpy(ghost) == 0 if ghost else np.ones(len(coordinates), bool)
    return coordinates[owned], values[owned]


def describe(records):
    """One line: what each process did."""
    parts = []
    for r in records:
        if "exception" in r:
            parts.append("rank %d: exception %s" % (r["rank"], r["exception"].strip().splitlines()[-1]))
            continue
        errors = "; ".join(e.replace("\n", " | ")[:220] for e in r["errors"])
        parts.append("rank %d: rc=%s %.2fs out=%dp/%dc errors(%d)=[%s]" % (
            r["rank"], r["rc"], r["seconds"], r["points"], r["cells"], len(r["errors"]), errors))
    return " || ".join(parts)


def names_rank(text, rank):
    return re.search(r"\b(process|rank)\s+%d\b" % rank, text, re.IGNORECASE) is not None


def check_agreed_failure(label, records, about, about_what, bad=None, one_line=False):
    """Every process failed (UpdatePiece 0) with exactly one error, the same text on all,
    matching `about` (a function of the text); naming process `bad` when given."""
    if not check(all("exception" not in r for r in records),
                 "%s: exception on a process:\n%s" % (label, "".join(r.get("exception", "") for r in records))):
        return
    check(all(r["rc"] == 0 for r in records),
          "%s: UpdatePiece returned %s (rank order), expected 0 everywhere" % (label, [r["rc"] for r in records]))
    counts = [len(r["errors"]) for r in records]
    if not check(counts == [1] * len(records), "%s: errors per process %s, expected exactly 1 each" % (label, counts)):
        if min(counts) == 0:
            return
    texts = [r["errors"][0] for r in records]
    check(len(set(texts)) == 1, "%s: the error differs between processes: %s" % (label, texts))
    text = texts[0]
    if bad is not None:
        check(names_rank(text, bad), "%s: the error does not name process %d: %r" % (label, bad, text))
    check(about(text), "%s: the error does not say %s: %r" % (label, about_what, text))
    if one_line:
        check("\n" not in text, "%s: the error is not one line: %r" % (label, text))


def bad_ranks():
    """The process with the bad piece: 1, and the last one too when there are more than 2."""
    return [1] + ([PROCESSES - 1] if PROCESSES > 2 else [])


# --- The cases -----------------------------------------------------------------------------------
#
# Each case is a pair: local() runs on every process and returns its record;
# judge(records) runs on process 0 with the records of all processes.

def compare_with_serial(label, records, serial, array_name):
    """The union of the processes' unmarked points against the serial output."""
    serial_points = vtk_to_numpy(serial.GetPoints().GetData()).astype(float)
    serial_values = vtk_to_numpy(serial.GetPointData().GetArray(array_name)).astype(float)
    points = np.concatenate([r["owned"][0] for r in records])
    values = np.concatenate([r["owned"][1] for r in records])
    cells = sum(r["cells"] for r in records)
    check(cells == serial.GetNumberOfCells(),
          "%s: %d cells over the processes, serial has %d" % (label, cells, serial.GetNumberOfCells()))
    check(len(points) == len(serial_points),
          "%s: %d unmarked points over the processes, serial has %d" % (label, len(points), len(serial_points)))
    # Match by exact coordinates, then the nearest point within 1e-12.
    index = {tuple(p): k for k, p in enumerate(points)}
    matched = np.full(len(serial_points), -1, np.int64)
    for k, p in enumerate(serial_points):
        matched[k] = index.get(tuple(p), -1)
    for k in np.flatnonzero(matched < 0):
        if len(points):
            distance = np.linalg.norm(points - serial_points[k], axis=1)
            if distance.min() <= 1e-12:
                matched[k] = int(distance.argmin())
    missing = int((matched < 0).sum())
    repeated = len(matched[matched >= 0]) - len(np.unique(matched[matched >= 0]))
    # Unmarked parallel points that match no serial point (e.g. a second copy of one).
    extra = np.setdiff1d(np.arange(len(points)), matched[matched >= 0])
    nearest = max((np.linalg.norm(serial_points - points[k], axis=1).min() for k in extra), default=0.0)
    scale = max(np.ptp(serial_values), 1e-300)
    found = matched >= 0
    difference = np.abs(values[matched[found]] - serial_values[found]) / scale if found.any() else np.zeros(1)
    worst = np.nanmax(difference) if len(difference) and not np.isnan(difference).all() else np.nan
    print("MEASURE %-40s cells %d (serial %d), unmarked points %d (serial %d), %d serial points unmatched, "
          "%d matched twice, %d unmarked points left over (at most %.3g from a serial point), "
          "max |%s - serial|/range = %.3g" % (
              label, cells, serial.GetNumberOfCells(), len(points), len(serial_points), missing, repeated,
              len(extra), nearest, array_name, worst), flush=True)
    check(missing == 0, "%s: %d serial points have no unmarked parallel point" % (label, missing))
    check(repeated == 0, "%s: %d serial points match several unmarked points" % (label, repeated))
    check(np.all(difference <= 1e-9),
          "%s: %d points differ from serial by more than 1e-9 of the range (max %.3g)" % (
              label, int((~(difference <= 1e-9)).sum()), worst))


def succeeds_as_serial(label, records, whole):
    """Every process succeeded without error, and their unmarked points equal
    the serial advection of `whole` (the whole mesh)."""
    print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
    check(all(r.get("rc") == 1 and not r.get("errors") for r in records),
          "%s: every process succeeds without error" % label)
    algorithm = vtkPolyDataShockAdvectionFilter()
    algorithm.SetController(None)
    algorithm.SetNumberOfThreads(1)
    algorithm.SetInputData(whole)
    algorithm.UpdatePiece(0, 1, 0)
    compare_with_serial(label, records, algorithm.GetOutput(), "Elevation")


def replicated_case():
    label = "replicated np=%d" % PROCESSES

    def local():
        record, algorithm = run("advection", make_polydata(*slab(48)), label)
        record["owned"] = owned_points(algorithm.GetOutput(), "Elevation")
        return record

    def judge(records):
        succeeds_as_serial(label, records, make_polydata(*slab(48)))

    return local, judge


def source_pieces_case():
    label = "source pieces np=%d" % PROCESSES

    def pipeline():
        source = vtkSphereSource()
        source.SetThetaResolution(64)
        source.SetPhiResolution(64)
        elevation = vtkElevationFilter()  # "Elevation", the active point scalars
        elevation.SetInputConnection(source.GetOutputPort())
        algorithm = vtkPolyDataShockAdvectionFilter()
        algorithm.SetNumberOfThreads(1)
        algorithm.SetInputConnection(elevation.GetOutputPort())
        return algorithm, [source, elevation]

    def local():
        algorithm, keep = pipeline()
        algorithm.SetController(controller)
        messages.take()
        start = time.time()
        rc = algorithm.UpdatePiece(RANK, PROCESSES, 0)
        print("rank %d: %s returned %s after %.2f s" % (RANK, label, rc, time.time() - start), flush=True)
        output = algorithm.GetOutput()
        return {"rank": RANK, "rc": rc, "errors": messages.take(), "seconds": time.time() - start,
                "points": output.GetNumberOfPoints(), "cells": output.GetNumberOfCells(),
                "owned": owned_points(output, "Elevation")}

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check(all(r.get("rc") == 1 and not r.get("errors") for r in records),
              "%s: every process succeeds without error" % label)
        algorithm, keep = pipeline()
        algorithm.SetController(None)
        algorithm.UpdatePiece(0, 1, 0)
        compare_with_serial(label, records, algorithm.GetOutput(), "Elevation")

    return local, judge


def noncontiguous_array_case():
    """The filtered array in an array class that does not hold its values in one
    block (struct-of-arrays): the ghost rings carry it the general way."""
    label = "non-contiguous array np=%d" % PROCESSES

    def soa(mesh):
        from vtkmodules.vtkCommonCore import vtkSOADataArrayTemplate
        values = vtk_to_numpy(mesh.GetPointData().GetScalars())
        array = vtkSOADataArrayTemplate["float64"]()
        array.SetName("Elevation")
        array.SetNumberOfComponents(1)
        array.SetNumberOfTuples(len(values))
        for k, v in enumerate(values):
            array.SetValue(k, float(v))
        mesh.GetPointData().SetScalars(array)
        return mesh

    def local():
        record, algorithm = run("advection", soa(piece_mesh()), label)
        record["owned"] = owned_points(algorithm.GetOutput(), "Elevation")
        return record

    def judge(records):
        succeeds_as_serial(label, records, make_polydata(*slab(32)))

    return local, judge


def nan_coordinate_case(kind, bad):
    label = "nan coordinate %s bad=%d np=%d" % (kind, bad, PROCESSES)

    def local():
        points, cells = slab(32, RANK, PROCESSES)
        if RANK == bad:
            points[cells[len(cells) // 2, 0], 0] = np.nan  # a point of a triangle
        return run(kind, make_polydata(points, cells), label)[0]

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check_agreed_failure(label, records, lambda t: re.search(r"\bnan\b|not finite|non-finite", t, re.I),
                             "NaN / not finite", bad=bad)

    return local, judge


def isolated_far_point_case(bad):
    label = "isolated point x=1e200 bad=%d np=%d" % (bad, PROCESSES)

    def local():
        points, cells = slab(32, RANK, PROCESSES)
        if RANK == bad:
            points = np.vstack([points, [1e200, 0.0, 0.0]])  # used by no cell
        return run("advection", make_polydata(points, cells), label)[0]

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        if check(all("exception" not in r for r in records), "%s: exception on a process" % label):
            statuses = [r["rc"] for r in records]
            check(len(set(statuses)) == 1, "%s: the processes disagree on the status: %s" % (label, statuses))

    return local, judge


def bad_cell_id_case(kind, cell, bad):
    label = "bad %s id %s bad=%d np=%d" % (cell, kind, bad, PROCESSES)

    def local():
        points, cells = slab(32, RANK, PROCESSES)
        mesh = make_polydata(points, cells)
        if RANK == bad:
            wrong = len(points) + 5
            if cell == "triangle":
                mesh.SetPolys(cell_array(np.vstack([cells, [[0, 1, wrong]]]), 3))
            elif cell == "line":
                mesh.SetLines(cell_array([0, wrong], 2))
            else:
                mesh.SetVerts(cell_array([wrong], 1))
        return run(kind, mesh, label)[0]

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check_agreed_failure(label, records, lambda t: True, "", bad=bad, one_line=True)

    return local, judge


def array_name_case(bad):
    label = "array name mismatch bad=%d np=%d" % (bad, PROCESSES)

    def local():
        name = "Temperature" if RANK == bad else "Heat"
        piece = piece_mesh(scalars_name=name)
        low, high = piece.GetPointData().GetScalars().GetRange()
        record, algorithm = run("advection", piece, label)
        record["input_range"] = (low, high)
        output = algorithm.GetOutput()
        array = output.GetPointData().GetArray(name)
        record["values"] = vtk_to_numpy(array).astype(float) if array and output.GetNumberOfPoints() else None
        return record

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        mismatch = (lambda t: ("Heat" in t and "Temperature" in t)
                    or re.search(r"differ|mismatch|not the same|inconsistent", t, re.I))
        check_agreed_failure(label, records, mismatch, "which arrays differ")
        for r in records:
            if "exception" in r or r["values"] is None:
                continue
            low = min(q["input_range"][0] for q in records if "input_range" in q)
            high = max(q["input_range"][1] for q in records if "input_range" in q)
            garbage = ~np.isfinite(r["values"]) | (r["values"] < low) | (r["values"] > high)
            check(not garbage.any(), "%s: rank %d outputs %d values outside the input range [%g, %g]"
                  % (label, r["rank"], int(garbage.sum()), low, high))
            check(r["rc"] == 1, "%s: rank %d failed but still outputs %d filtered values"
                  % (label, r["rank"], len(r["values"])))

    return local, judge


def array_layout_case(bad, what):
    """The active point scalars "Elevation" everywhere, but with 3 components
    (what = "components") or as unsigned char (what = "type") on the bad
    process: every process fails with the same error, none outputs values."""
    label = "array %s mismatch bad=%d np=%d" % (what, bad, PROCESSES)

    def local():
        piece = piece_mesh()
        if RANK == bad:
            values = vtk_to_numpy(piece.GetPointData().GetScalars()).astype(float)
            if what == "components":
                array = numpy_to_vtk(np.ascontiguousarray(np.stack([values] * 3, axis=1)), deep=1)
            else:
                array = numpy_to_vtk(np.round((values + 1.0) * 127.0).astype(np.uint8), deep=1,
                                     array_type=VTK_UNSIGNED_CHAR)
            array.SetName("Elevation")
            piece.GetPointData().SetScalars(array)
        record, algorithm = run("advection", piece, label)
        output = algorithm.GetOutput()
        array = output.GetPointData().GetArray("Elevation")
        record["filtered"] = bool(array is not None and output.GetNumberOfPoints() > 0)
        return record

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        about = (lambda t: re.search(r"component", t, re.I)) if what == "components" else \
            (lambda t: re.search(r"type|unsigned char|double", t, re.I))
        check_agreed_failure(label, records, about, "which property of the array differs", bad=bad,
                             one_line=True)
        check(not any(r.get("filtered") for r in records), "%s: a process output filtered values" % label)

    return local, judge


def iterations_case(bad):
    label = "SolverIterations mismatch bad=%d np=%d" % (bad, PROCESSES)

    def local():
        iterations = 30 if RANK == bad else 25
        return run("sharpen", piece_mesh(), label, configure=lambda a: a.SetSolverIterations(iterations))[0]

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check_agreed_failure(label, records, lambda t: re.search(r"iteration", t, re.I), "SolverIterations")

    return local, judge


def flow_mode_case(kind, bad):
    """The bad process recomputes the flow (Composed, 4 updates: no ring stencil, Ghost
    Levels rings), the others do not: the ring agreement before the parameter check
    must still be made by every process, then all stop with the same message."""
    label = "FlowMode mismatch %s bad=%d np=%d" % (kind, bad, PROCESSES)

    def configure(algorithm):
        if RANK == bad:
            algorithm.SetFlowModeToComposed()
            algorithm.SetNumberOfFlowUpdates(4)

    def local():
        return run(kind, piece_mesh(), label, configure=configure)[0]

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check_agreed_failure(label, records, lambda t: re.search(r"FlowMode|parameter", t, re.I), "FlowMode")

    return local, judge


def update_piece(algorithm):
    """UpdatePiece(rank, N, 0) of `algorithm` (already connected); this process's record."""
    messages.take()
    start = time.time()
    rc = algorithm.UpdatePiece(RANK, PROCESSES, 0)
    output = algorithm.GetOutputDataObject(0)
    return {"rank": RANK, "rc": rc, "errors": messages.take(), "seconds": time.time() - start,
            "points": output.GetNumberOfPoints(), "cells": output.GetNumberOfCells(),
            "executive": algorithm.GetExecutive().GetClassName()}


class FailingOn(VTKPythonAlgorithmBase):
    """A pass-through filter of `data_type` that fails (returns 0, as a VTK
    filter does on a piece it cannot handle) on process `bad`: in its
    RequestData (stage "data"), in its RequestInformation (stage
    "information", as a reader whose file is missing on one node), or in its
    RequestDataObject (stage "dataobject", as a reader that cannot tell its
    output's type there)."""

    def __init__(self, data_type, bad, stage="data"):
        VTKPythonAlgorithmBase.__init__(self, nInputPorts=1, inputType=data_type, nOutputPorts=1,
                                        outputType=data_type)
        self.bad = bad
        self.stage = stage
        # The passes it was asked for after its data object failed (a reader
        # without an output object must be asked nothing more).
        self.asked_without_output = []

    def failed_object(self, what):
        if self.stage == "dataobject" and RANK == self.bad:
            self.asked_without_output.append(what)
            return True
        return False

    def RequestDataObject(self, request, inInfo, outInfo):
        return 0 if self.stage == "dataobject" and RANK == self.bad else 1

    def RequestInformation(self, request, inInfo, outInfo):
        if self.failed_object("information"):
            return 0
        return 0 if self.stage == "information" and RANK == self.bad else 1

    def RequestUpdateExtent(self, request, inInfo, outInfo):
        return 0 if self.failed_object("update extent") else 1

    def RequestData(self, request, inInfo, outInfo):
        if self.failed_object("data") or (self.stage == "data" and RANK == self.bad):
            return 0
        self.GetOutputData(outInfo, 0).ShallowCopy(self.GetInputData(inInfo, 0, 0))
        return 1


def upstream_failure_case(kind, bad, stage="data"):
    label = "input fails upstream (%s) %s bad=%d np=%d" % (stage, kind, bad, PROCESSES)

    def pipeline(parallel):
        """The shock filter after a FailingOn filter, on this process's piece."""
        if kind == "image":
            source = vtkRTAnalyticSource()
            source.SetWholeExtent(0, 39, 0, 29, 0, 9)
            failing = FailingOn("vtkImageData", bad, stage)
            failing.SetInputConnection(source.GetOutputPort())
            algorithm = vtkImageShockAdvectionFilter()
        else:
            failing = FailingOn("vtkPolyData", bad, stage)
            failing.SetInputDataObject(0, piece_mesh())
            algorithm = FILTERS[kind]()
        algorithm.SetController(controller if parallel else None)
        algorithm.SetNumberOfThreads(1)
        algorithm.SetInputConnection(failing.GetOutputPort())
        return algorithm, failing

    def local():
        algorithm, failing = pipeline(True)
        record = update_piece(algorithm)
        # Asked again after the failing filter changed: it fails again, and so do all.
        failing.Modified()
        record["again_rc"] = algorithm.UpdatePiece(RANK, PROCESSES, 0)
        record["again_errors"] = messages.take()
        serial, _ = pipeline(False)
        record["serial_rc"] = serial.UpdatePiece(0, 1, 0)
        record["serial_errors"] = messages.take()
        # With the controller, but each process filtering its whole input (no pieces).
        whole, _ = pipeline(True)
        record["whole_rc"] = whole.UpdatePiece(0, 1, 0)
        record["whole_errors"] = messages.take()
        record["asked_without_output"] = failing.asked_without_output
        return record

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check_agreed_failure(label, records, lambda t: "input failed to update" in t,
                             "that its input failed to update", bad=bad, one_line=True)
        check(all(r.get("points") == 0 for r in records), "%s: a failed execution leaves empty outputs" % label)
        again = [dict(r, rc=r.get("again_rc"), errors=r.get("again_errors", [])) for r in records]
        check_agreed_failure(label + " (asked again)", again, lambda t: "input failed to update" in t,
                             "that its input failed to update", bad=bad, one_line=True)
        check(all(r.get("serial_rc") == (0 if r["rank"] == bad else 1) and r.get("serial_errors") == []
                  for r in records),
              "%s: serial, the filter fails only after its failed input, and adds no error: %s"
              % (label, [(r.get("serial_rc"), r.get("serial_errors")) for r in records]))
        check(all(r.get("whole_rc") == (0 if r["rank"] == bad else 1) and r.get("whole_errors") == []
                  for r in records),
              "%s: with the controller but no pieces, as in serial: %s"
              % (label, [(r.get("whole_rc"), r.get("whole_errors")) for r in records]))
        check(all(r.get("asked_without_output") == [] for r in records),
              "%s: an input without its data object is asked nothing more: %s"
              % (label, [r.get("asked_without_output") for r in records]))

    return local, judge


def paraview_executive_case(kind, bad, stage="information"):
    """The same failure in the information (or data-object) pass, through
    ParaView's executive of the shock filters: the VTK object of a proxy of
    the plugin (pvbatch --symmetric: every process holds its own)."""
    label = "input fails upstream (%s, ParaView's executive) %s bad=%d np=%d" % (stage, kind, bad, PROCESSES)

    def local():
        from paraview import simple
        simple.LoadPlugin(PLUGIN, ns=globals())  # the proxies' functions into this module
        names = globals()
        if kind == "image":
            proxy = names["ImageShockAdvection"](Input=simple.Wavelet())
            source = vtkRTAnalyticSource()
            source.SetWholeExtent(0, 39, 0, 29, 0, 9)
            failing = FailingOn("vtkImageData", bad, stage)
            failing.SetInputConnection(source.GetOutputPort())
        else:
            proxy = names["SurfaceShockSharpen"](Input=simple.Sphere())
            failing = FailingOn("vtkPolyData", bad, stage)
            failing.SetInputDataObject(0, piece_mesh())
        algorithm = proxy.GetClientSideObject()
        algorithm.SetInputConnection(failing.GetOutputPort())
        record = update_piece(algorithm)
        record["asked_without_output"] = failing.asked_without_output
        simple.Delete(proxy)
        return record

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check(all(r.get("executive") == "vtkPVShockCompositeDataPipeline" for r in records),
              "%s: the proxies' executive is vtkPVShockCompositeDataPipeline: %s"
              % (label, [r.get("executive") for r in records]))
        check_agreed_failure(label, records, lambda t: "input failed to update" in t,
                             "that its input failed to update", bad=bad, one_line=True)
        check(all(r.get("points") == 0 for r in records), "%s: a failed execution leaves empty outputs" % label)
        check(all(r.get("asked_without_output") == [] for r in records),
              "%s: an input without its data object is asked nothing more: %s"
              % (label, [r.get("asked_without_output") for r in records]))

    return local, judge


def image_filter_on(port):
    """Image Shock Advection of `port`'s pieces with the run's controller, 1 thread."""
    algorithm = vtkImageShockAdvectionFilter()
    algorithm.SetController(controller)
    algorithm.SetNumberOfThreads(1)
    algorithm.SetInputConnection(port)
    return algorithm


def image_grid_case(bad, what):
    """The image filter on vtkRTAnalyticSource's pieces, the bad process's
    image differing in its whole extent, spacing or origin (its file is
    another version on that node): the pieces do not fit together, and every
    process refuses them with the same one-line error naming what differs."""
    label = "image grid differs (%s) bad=%d np=%d" % (what, bad, PROCESSES)

    def local():
        from vtkmodules.vtkImagingCore import vtkImageChangeInformation
        source = vtkRTAnalyticSource()
        change = vtkImageChangeInformation()
        change.SetInputConnection(source.GetOutputPort())

        def set_grid(differs):
            source.SetWholeExtent(0, 49 if (differs and what.startswith("whole_extent")) else 39, 0, 29, 0, 9)
            change.SetOutputSpacing(1.0, 1.0, 1.5 if (differs and what == "spacing") else 1.0)
            change.SetOriginTranslation(0.25 if (differs and what == "origin") else 0.0, 0.0, 0.0)
            change.Modified()  # on every process, as ParaView applies a change
            source.Modified()

        set_grid(RANK == bad)
        # "whole_extent": the source itself (which reads each piece with its
        # halo); the others through a filter (the halo is exchanged).
        algorithm = image_filter_on((source if what == "whole_extent" else change).GetOutputPort())
        record = update_piece(algorithm)
        # The bad process's grid mended (a file replaced, then reloaded):
        # the same filters run, each on its own piece of the one image.
        set_grid(False)
        record["same_rc"] = algorithm.UpdatePiece(RANK, PROCESSES, 0)
        record["same_errors"] = messages.take()
        record["same_points"] = algorithm.GetOutputDataObject(0).GetNumberOfPoints()
        record["same_extent"] = list(algorithm.GetOutputDataObject(0).GetExtent())
        return record

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        word = "whole extent" if what.startswith("whole_extent") else what
        check_agreed_failure(label, records, lambda t: "image's grid" in t and word in t,
                             "that the image's %s differs" % word, bad=bad, one_line=True)
        check(all(r.get("points") == 0 for r in records), "%s: a failed execution leaves empty outputs" % label)
        check(all(r.get("same_rc") == 1 and r.get("same_errors") == [] and r.get("same_points", 0) > 0
                  for r in records),
              "%s: the grid mended, the same filters run everywhere: %s"
              % (label, [(r.get("same_rc"), r.get("same_errors"), r.get("same_points")) for r in records]))
        # Their pieces lie in the one whole extent and, by cells, tile it.
        extents = [r.get("same_extent", [0, -1] * 3) for r in records]
        cells = sum(max(0, e[1] - e[0]) * max(0, e[3] - e[2]) * max(0, e[5] - e[4]) for e in extents)
        check(all(e[0] >= 0 and e[1] <= 39 and e[3] <= 29 and e[5] <= 9 for e in extents) and cells == 39 * 29 * 9,
              "%s: the mended run's pieces tile the 40 x 30 x 10 image: %s" % (label, extents))

    return local, judge


def repeated_piece_case(bad):
    """The image filter on vtkRTAnalyticSource's pieces, the bad process asking
    for the piece of the process before it (a script's UpdatePiece(0, N, 0)
    on every process): no process would filter that piece's neighbour, and
    the halos beside it would be wrong. Every process refuses with the same
    one-line error naming the bad process; the same filters asking each for
    its own piece then run."""
    label = "image piece asked twice bad=%d np=%d" % (bad, PROCESSES)

    def pipeline():
        source = vtkRTAnalyticSource()
        source.SetWholeExtent(0, 39, 0, 29, 0, 9)
        return image_filter_on(source.GetOutputPort())

    def local():
        algorithm = pipeline()
        messages.take()
        rc = algorithm.UpdatePiece(bad - 1 if RANK == bad else RANK, PROCESSES, 0)
        output = algorithm.GetOutputDataObject(0)
        record = {"rank": RANK, "rc": rc, "errors": messages.take(), "points": output.GetNumberOfPoints(),
                  "cells": output.GetNumberOfCells(), "seconds": 0.0}
        # A new pipeline on every process (VTK re-executes a failed filter
        # only after a change, which must then be made on every process).
        own = pipeline()
        record["own_rc"] = own.UpdatePiece(RANK, PROCESSES, 0)
        record["own_errors"] = messages.take()
        record["own_points"] = own.GetOutputDataObject(0).GetNumberOfPoints()
        return record

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check_agreed_failure(label, records, lambda t: "asks for piece %d" % (bad - 1) in t,
                             "that it asks for another process's piece", bad=bad, one_line=True)
        check(all(r.get("points") == 0 for r in records), "%s: a failed execution leaves empty outputs" % label)
        check(all(r.get("own_rc") == 1 and r.get("own_errors") == [] and r.get("own_points", 0) > 0
                  for r in records),
              "%s: each asking for its own piece, all run: %s"
              % (label, [(r.get("own_rc"), r.get("own_errors"), r.get("own_points")) for r in records]))

    return local, judge


def wrong_type_case(kind, bad):
    """The bad process's input is of a type the filter does not take (a
    vtkImageData before a surface filter, a vtkPolyData before the image
    filter): VTK refuses it on that process alone, and the others waited for
    it for ever. Every process now stops with the same one-line error naming
    the type, after VTK's own errors on the bad process; without a
    controller VTK refuses it there and the others run."""
    label = "input of another type %s bad=%d np=%d" % (kind, bad, PROCESSES)
    wrong = "vtkPolyData" if kind == "image" else "vtkImageData"

    def pipeline(parallel):
        algorithm = vtkImageShockAdvectionFilter() if kind == "image" else FILTERS[kind]()
        algorithm.SetController(controller if parallel else None)
        algorithm.SetNumberOfThreads(1)
        if kind == "image" and RANK == bad:
            algorithm.SetInputDataObject(0, piece_mesh())
        elif kind == "image" or RANK == bad:
            source = vtkRTAnalyticSource()
            source.SetWholeExtent(0, 39, 0, 29, 0, 9)
            algorithm.SetInputConnection(source.GetOutputPort())
        else:
            algorithm.SetInputDataObject(0, piece_mesh())
        return algorithm

    def local():
        algorithm = pipeline(True)
        messages.take()
        rc = algorithm.UpdatePiece(RANK, PROCESSES, 0)
        output = algorithm.GetOutputDataObject(0)
        errors = messages.take()
        record = {"rank": RANK, "rc": rc, "all_errors": errors, "errors": errors[-1:], "seconds": 0.0,
                  "points": output.GetNumberOfPoints() if output else 0, "cells": 0}
        serial = pipeline(False)
        record["serial_rc"] = serial.UpdatePiece(0, 1, 0)  # each its whole input, no controller
        record["serial_errors"] = messages.take()
        return record

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        # The agreed line is every process's last error (VTK's own come before it on the bad one).
        check_agreed_failure(label, records, lambda t: wrong in t and "cannot filter its piece" in t,
                             "the input's type", bad=bad, one_line=True)
        check(all(len(r["all_errors"]) == 1 for r in records if r["rank"] != bad),
              "%s: the other processes report the agreed line only: %s" % (label, [r["all_errors"] for r in records]))
        check(all(r.get("points") == 0 for r in records), "%s: a failed execution leaves empty outputs" % label)
        check(all(r.get("serial_rc") == (0 if r["rank"] == bad else 1) for r in records)
              and all(r.get("serial_errors") == [] for r in records if r["rank"] != bad),
              "%s: without a controller VTK refuses the input on the bad process only: %s"
              % (label, [(r.get("serial_rc"), r.get("serial_errors")) for r in records]))

    return local, judge


def gradient_domain_case():
    label = "image Domain Gradients on pieces np=%d" % PROCESSES

    def local():
        # The image filter on the source's own pieces, as pvbatch runs it.
        source = vtkRTAnalyticSource()
        source.SetWholeExtent(0, 39, 0, 29, 0, 0)
        algorithm = vtkImageShockAdvectionFilter()
        algorithm.SetController(controller)
        algorithm.SetNumberOfThreads(1)
        algorithm.SetFlowTime(64)
        algorithm.SetDomainToGradients()
        algorithm.SetInputConnection(source.GetOutputPort())
        messages.take()
        start = time.time()
        rc = algorithm.UpdatePiece(RANK, PROCESSES, 0)
        output = algorithm.GetOutput()
        return {"rank": RANK, "rc": rc, "errors": messages.take(), "seconds": time.time() - start,
                "points": output.GetNumberOfPoints(), "cells": output.GetNumberOfCells()}

    def judge(records):
        print("MEASURE %-40s %s" % (label, describe(records)), flush=True)
        check_agreed_failure(label, records, lambda t: "Domain Gradients" in t and "pieces" in t,
                             "that Domain Gradients does not run on pieces", one_line=True)
        check(all(r["points"] == 0 for r in records), "%s: a failed execution leaves an empty output" % label)

    return local, judge


def abort_at_first_progress():
    """A ProgressEvent observer that sets AbortExecute at the first report from
    within RequestData (progress 0 comes before it), and the list of the
    progress it aborted at."""
    requested = []

    def abort(caller, event):
        progress = caller.GetProgress()
        if not requested and 0.0 < progress < 1.0:
            requested.append(progress)
            caller.SetAbortExecute(1)

    return requested, abort


def abort_case():
    label = "abort on rank 0 np=%d" % PROCESSES

    def local():
        requested, abort = abort_at_first_progress()
        record, algorithm = run("sharpen", piece_mesh(resolution=200), label,
                                observe=abort if RANK == 0 else None)
        controller.Barrier()
        record["returned"] = True
        record["abort_at"] = requested[0] if requested else None
        return record

    def judge(records):
        print("MEASURE %-40s %s; abort requested at progress %s" % (
            label, describe(records), records[0].get("abort_at")), flush=True)
        check(all(r.get("returned") for r in records), "%s: every process returned and reached the Barrier" % label)
        check(records[0].get("abort_at") is not None, "%s: no progress report on rank 0 to abort at" % label)

    return local, judge


def update_aborting_on_rank0(algorithm):
    """Update `algorithm`'s piece on every process, process 0 aborting at its
    first progress report, then a Barrier: (return code, progress aborted at)."""
    requested, abort = abort_at_first_progress()
    if RANK == 0:
        algorithm.AddObserver("ProgressEvent", abort)
    messages.take()
    rc = algorithm.UpdatePiece(RANK, PROCESSES, 0)
    controller.Barrier()
    return rc, requested[0] if requested else None


def image_abort_case():
    label = "image abort on rank 0 np=%d" % PROCESSES

    def local():
        # A diagonal step at a long time: the pieces' halo must grow (a second
        # attempt) unless a process aborted; rank 0 aborts during its first one.
        from vtkmodules.vtkFiltersCore import vtkArrayCalculator
        source = vtkRTAnalyticSource()
        source.SetWholeExtent(-128, 127, -128, 127, 0, 0)
        step = vtkArrayCalculator()
        step.SetInputConnection(source.GetOutputPort())
        step.AddCoordinateScalarVariable("coordsX", 0)
        step.AddCoordinateScalarVariable("coordsY", 1)
        step.SetFunction("tanh((coordsY-0.8*coordsX-5)/6)")
        step.SetResultArrayName("Step")
        algorithm = vtkImageShockAdvectionFilter()
        algorithm.SetController(controller)
        algorithm.SetNumberOfThreads(1)
        algorithm.SetFlowTime(65536)
        algorithm.SetInputArrayToProcess(0, 0, 0, 0, "Step")
        algorithm.SetInputConnection(step.GetOutputPort())
        rc, abort_at = update_aborting_on_rank0(algorithm)
        return {"rank": RANK, "rc": rc, "returned": True, "abort_at": abort_at,
                "attempts": algorithm.GetLastHaloAttempts(), "halo": algorithm.GetLastGhostLevels(),
                "errors": messages.take()}

    def judge(records):
        print("MEASURE %-40s attempts %s, halo %s; abort requested at progress %s" % (
            label, [r["attempts"] for r in records], [r["halo"] for r in records], records[0].get("abort_at")),
            flush=True)
        check(all(r.get("returned") for r in records), "%s: every process returned and reached the Barrier" % label)
        check(records[0].get("abort_at") is not None, "%s: no progress report on rank 0 to abort at" % label)
        check(all(r["attempts"] == 1 and r["halo"] == records[0]["halo"] for r in records),
              "%s: the abort is agreed: no process grows its halo and filters again (%s)"
              % (label, [(r["attempts"], r["halo"]) for r in records]))

    return local, judge


def image_abort_from_source_case(layers=False):
    """Rank 0 aborts at its first progress report: its output keeps the
    piece's own values, never an empty array. The source feeds the filter
    directly (its arrays known from a first execution): each piece is read
    with its halo, or, `layers`, the volume cut into slabs along z, read where
    it lies with its halo exchanged in layers beside it."""
    label = "image abort, %s, np=%d" % ("halo in layers" if layers else "piece read with its halo", PROCESSES)
    whole = (0, 31, 0, 23, 0, 63) if layers else (0, 63, 0, 47, 0, 31)

    def local():
        source = vtkRTAnalyticSource()
        source.SetWholeExtent(*whole)
        source.UpdatePiece(RANK, PROCESSES, 0)
        algorithm = vtkImageShockAdvectionFilter()
        algorithm.SetController(controller)
        algorithm.SetNumberOfThreads(1)
        algorithm.SetFlowTime(64)
        algorithm.SetInputConnection(source.GetOutputPort())
        rc, abort_at = update_aborting_on_rank0(algorithm)
        output = algorithm.GetOutput()
        values = output.GetPointData().GetScalars()
        reference = vtkRTAnalyticSource()
        reference.SetWholeExtent(*whole)
        reference.UpdateExtent(output.GetExtent())
        expected = reference.GetOutput().GetPointData().GetScalars()
        same = (values is not None and values.GetNumberOfTuples() == output.GetNumberOfPoints() > 0
                and np.array_equal(vtk_to_numpy(values), vtk_to_numpy(expected)))
        return {"rank": RANK, "rc": rc, "returned": True, "abort_at": abort_at,
                "from_source": algorithm.GetLastHaloFromSource(), "in_layers": algorithm.GetLastHaloInLayers(),
                "tuples": values.GetNumberOfTuples() if values else -1,
                "points": output.GetNumberOfPoints(), "unfiltered": bool(same), "errors": messages.take()}

    def judge(records):
        print("MEASURE %-40s read with the halo %s; tuples %s of points %s; abort at progress %s" % (
            label, [r["from_source"] for r in records], [r["tuples"] for r in records],
            [r["points"] for r in records], records[0].get("abort_at")), flush=True)
        check(all(r.get("returned") for r in records), "%s: every process returned and reached the Barrier" % label)
        check(records[0].get("abort_at") is not None, "%s: no progress report on rank 0 to abort at" % label)
        if layers:
            check(all(r["in_layers"] and not r["from_source"] for r in records),
                  "%s: every piece was read where it lies, its halo in layers" % label)
        else:
            check(all(r["from_source"] and not r["in_layers"] for r in records),
                  "%s: every piece was read with its halo" % label)
        check(records[0]["unfiltered"], "%s: the aborted piece keeps its own values (%d tuples for %d points)"
              % (label, records[0]["tuples"], records[0]["points"]))

    return local, judge


def all_cases():
    """(name, case) pairs; a name is dotted (e.g. bad_cell_id.sharpen.line.bad1)."""
    cases = [("replicated", replicated_case()), ("source_pieces", source_pieces_case()),
             ("noncontiguous_array", noncontiguous_array_case())]
    for bad in bad_ranks():
        for kind in ("advection", "sharpen"):
            cases.append(("nan_coordinate.%s.bad%d" % (kind, bad), nan_coordinate_case(kind, bad)))
        cases.append(("isolated_far_point.bad%d" % bad, isolated_far_point_case(bad)))
        for kind in ("advection", "sharpen"):
            for cell in ("triangle", "line", "vertex"):
                cases.append(("bad_cell_id.%s.%s.bad%d" % (kind, cell, bad), bad_cell_id_case(kind, cell, bad)))
        cases.append(("array_name.bad%d" % bad, array_name_case(bad)))
        for what in ("components", "type"):
            cases.append(("array_%s.bad%d" % (what, bad), array_layout_case(bad, what)))
    cases.append(("gradient_domain", gradient_domain_case()))
    for bad in bad_ranks():
        for what in ("whole_extent", "whole_extent_filtered", "spacing", "origin"):
            cases.append(("image_grid.%s.bad%d" % (what, bad), image_grid_case(bad, what)))
        cases.append(("repeated_piece.bad%d" % bad, repeated_piece_case(bad)))
        for kind in ("advection", "sharpen", "image"):
            cases.append(("wrong_type.%s.bad%d" % (kind, bad), wrong_type_case(kind, bad)))
    for bad in bad_ranks():
        for kind in ("advection", "sharpen", "image"):
            cases.append(("upstream_failure.%s.bad%d" % (kind, bad), upstream_failure_case(kind, bad)))
            cases.append(("upstream_information_failure.%s.bad%d" % (kind, bad),
                          upstream_failure_case(kind, bad, "information")))
            cases.append(("upstream_dataobject_failure.%s.bad%d" % (kind, bad),
                          upstream_failure_case(kind, bad, "dataobject")))
        for kind in ("sharpen", "image"):
            cases.append(("upstream_information_failure.paraview.%s.bad%d" % (kind, bad),
                          paraview_executive_case(kind, bad)))
            cases.append(("upstream_dataobject_failure.paraview.%s.bad%d" % (kind, bad),
                          paraview_executive_case(kind, bad, "dataobject")))
    # Those that may hang today last: a hang ends the whole run.
    for bad in bad_ranks():
        cases.append(("iterations.bad%d" % bad, iterations_case(bad)))
        for kind in ("advection", "sharpen"):
            cases.append(("flow_mode.%s.bad%d" % (kind, bad), flow_mode_case(kind, bad)))
    cases.append(("abort", abort_case()))
    cases.append(("image_abort", image_abort_case()))
    cases.append(("image_abort_from_source", image_abort_from_source_case()))
    cases.append(("image_abort_in_layers", image_abort_from_source_case(layers=True)))
    return cases


def selected(name):
    """Whether the optional CASES argument selects `name` (a whole name or a dotted prefix of one)."""
    return not SELECTED or any(name == s or name.startswith(s + ".") for s in SELECTED)


if RANK == 0:
    check(PROCESSES >= 2, "run with at least 2 MPI processes (got %d)" % PROCESSES)
for name, (local, judge) in all_cases():
    if not selected(name):
        continue
    try:
        record = local()
    except Exception:  # report and go on: every process must reach the gather
        record = {"rank": RANK, "exception": traceback.format_exc()}
    records = gather(record)
    if RANK == 0:
        try:
            judge(records)
        except Exception:
            check(False, "exception in the checks of %s:\n%s" % (name, traceback.format_exc()))

failed = broadcast_int(len(failures))
if RANK == 0:
    print("%d passed, %d failed" % (passed, failed), flush=True)
# On success the script just ends, so that pvbatch finalizes MPI (sys.exit(0)
# would skip that and mpirun would report an improper exit).
if failed:
    sys.exit(1)
