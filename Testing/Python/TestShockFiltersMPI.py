"""Parallel test of the ShockFilters plugin: pieces with ghost layers against the serial result.

Usage: mpirun -np 2 pvbatch --mpi TestShockFiltersMPI.py PLUGIN_PATH OUTPUT_DIR

The script runs on process 0 (pvbatch's usual mode); the other processes
execute the same pipelines on their pieces. Each parallel result is written
with SaveData (.pvti/.pvtp: one piece per process) and read back on process 0,
where the serial reference is computed in the same process with the same VTK
classes on the whole data set (one piece). docs/parallel.md explains the
bounds and records the fractions printed here ("MEASURE" lines).

- Image Shock Advection: 2D and 3D wavelets and a 2D blurred step, point and
  cell data; an image from a reader that cannot cut pieces stays whole. Outside a band of W samples around the piece boundary the
  parallel result must equal the serial one (1e-12 of the data range); the
  fraction of samples that differ at all must stay below a bound.
- Surface Shock Advection: a sphere with a blurred scalar, split into pieces,
  with and without Ghost Cells Generator; per-point agreement.
- Surface Shock Sharpen: refused on pieces (error message, empty output);
  accepted on a mesh aggregated onto one process, where it matches the serial
  result.

Prints one line per failure and ends with "N passed, M failed"; the exit code
is 1 on any failure (mpirun then stops the other processes). An exception in
a case is reported as a failure and the remaining cases still run.
"""
import os
import re
import sys
import traceback

import numpy as np

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkOutputWindow
from vtkmodules.vtkFiltersCore import vtkArrayCalculator
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOXML import vtkXMLPImageDataReader, vtkXMLPPolyDataReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController

PLUGIN, OUTPUT = sys.argv[1], sys.argv[2]
os.makedirs(OUTPUT, exist_ok=True)
LoadPlugin(PLUGIN, ns=globals())

passed = 0
failures = []


def check(condition, message):
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


messages = Messages()
controller = vtkMultiProcessController.GetGlobalController()
PROCESSES = controller.GetNumberOfProcesses() if controller else 1
check(PROCESSES >= 2, "run with at least 2 MPI processes (got %d)" % PROCESSES)


def serial_filter(proxy_name, vtk_input, **properties):
    """The VTK object of a fresh proxy, rewired (on this process only) to a
    plain VTK input and updated as one piece: the serial reference."""
    dummy = Sphere(ThetaResolution=3, PhiResolution=3) if "Surface" in proxy_name else Wavelet(WholeExtent=[0, 1, 0, 1, 0, 0])
    proxy = globals()[proxy_name](Input=dummy, **properties)
    algorithm = proxy.GetClientSideObject()
    algorithm.SetInputConnection(vtk_input.GetOutputPort())
    algorithm.UpdatePiece(0, 1, 0)
    output = algorithm.GetOutputDataObject(0).NewInstance()
    output.DeepCopy(algorithm.GetOutputDataObject(0))
    Delete(proxy)
    Delete(dummy)
    return output


def wavelet(extent, expression=None):
    """vtkRTAnalyticSource (like the Wavelet source), optionally with a calculator array 'Step'."""
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(*extent)
    if not expression:
        return source, [source]
    calculator = vtkArrayCalculator()
    calculator.SetInputConnection(source.GetOutputPort())
    for axis, name in enumerate(("coordsX", "coordsY", "coordsZ")):
        calculator.AddCoordinateScalarVariable(name, axis)
    calculator.SetFunction(expression)
    calculator.SetResultArrayName("Step")
    calculator.SetResultArrayType(11)  # double, as ParaView's Calculator
    return calculator, [source, calculator]


def piece_extents(path):
    with open(path) as handle:
        return [list(map(int, e.split())) for e in re.findall(r'<Piece Extent="([^"]*)"', handle.read())]


def image_case(label, extent, flow_time, ghost_levels, band, bound, expression=None, cells=False):
    """Filter in parallel and serially; equality outside `band` samples of the
    piece boundaries, and at most `bound` of the samples differing."""
    name = "Step" if expression else "RTData"
    association = "CELLS" if cells else "POINTS"
    # Serial reference.
    reference_input, keep = wavelet(extent, expression)
    last = reference_input
    if cells:
        from vtkmodules.vtkFiltersCore import vtkPointDataToCellData
        to_cells = vtkPointDataToCellData()
        to_cells.SetInputConnection(reference_input.GetOutputPort())
        keep.append(to_cells)
        last = to_cells
    serial = serial_filter("ImageShockAdvection", last, InputArray=[association, name], FlowTime=flow_time)
    # Parallel run (fresh proxies: a source keeps the ghost layers of an earlier request).
    proxies = [Wavelet(WholeExtent=extent)]
    if expression:
        proxies.append(Calculator(Input=proxies[-1], Function=expression, ResultArrayName="Step"))
    if cells:
        proxies.append(PointDatatoCellData(Input=proxies[-1]))
    filtered = ImageShockAdvection(Input=proxies[-1], InputArray=[association, name], FlowTime=flow_time,
                                   GhostLevels=ghost_levels)
    path = os.path.join(OUTPUT, "image_%s.pvti" % label)
    SaveData(path, proxy=filtered)
    for proxy in [filtered] + proxies[::-1]:
        Delete(proxy)

    reader = vtkXMLPImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    pieces = piece_extents(path)
    check(len(pieces) == PROCESSES, "%s: %d pieces written" % (label, len(pieces)))
    check(list(image.GetExtent()) == list(extent), "%s: gathered extent %s" % (label, image.GetExtent()))
    # The pieces tile the image: neighbours share their boundary layer of points, no more.
    for a in range(len(pieces)):
        for b in range(a + 1, len(pieces)):
            overlap = [min(pieces[a][2 * i + 1], pieces[b][2 * i + 1]) - max(pieces[a][2 * i], pieces[b][2 * i])
                       for i in range(3)]
            spans = [extent[2 * i + 1] > extent[2 * i] for i in range(3)]
            check(min(o for o, s in zip(overlap, spans) if s) <= 0,
                  "%s: pieces %s and %s overlap by more than a layer" % (label, pieces[a], pieces[b]))
    data = image.GetCellData() if cells else image.GetPointData()
    reference = serial.GetCellData() if cells else serial.GetPointData()
    parallel = vtk_to_numpy(data.GetArray(name)).astype(float)
    expected = vtk_to_numpy(reference.GetArray(name)).astype(float)
    if not check(parallel.shape == expected.shape, "%s: %s vs %s samples" % (label, parallel.shape, expected.shape)):
        return
    # Distance (in samples) of every sample to the nearest boundary between pieces.
    dims = [extent[2 * i + 1] - extent[2 * i] + (0 if cells and extent[2 * i + 1] > extent[2 * i] else 1)
            for i in range(3)]
    index = np.indices(dims[::-1])
    distance = np.full(parallel.shape, np.inf)
    for piece in pieces:
        for axis in range(3):
            for side, limit in ((0, extent[2 * axis]), (1, extent[2 * axis + 1])):
                boundary = piece[2 * axis + side]
                if boundary == limit:
                    continue  # a side of the whole image, not a piece boundary
                position = index[2 - axis].ravel() + extent[2 * axis] + (0.5 if cells else 0.0)
                distance = np.minimum(distance, np.abs(position - boundary))
    scale = max(np.ptp(expected), 1e-300)
    differ = np.abs(parallel - expected) > 1e-12 * scale
    fraction = differ.mean()
    outside = differ & (distance > band)
    widest = distance[differ].max() if differ.any() else 0
    print("MEASURE image %-24s T=%-6g GhostLevels=%-3d differing=%.4f%% max|diff|/range=%.2g "
          "farthest differing sample %s from a piece boundary" % (
              label, flow_time, ghost_levels, 100 * fraction, np.abs(parallel - expected).max() / scale, widest),
          flush=True)
    check(not outside.any(), "%s: %d samples differ farther than %d samples from a piece boundary"
          % (label, outside.sum(), band))
    check(fraction <= bound, "%s: %.4f%% of the samples differ (bound %.4f%%)" % (label, 100 * fraction, 100 * bound))


def unsplit_image_case():
    """A reader that cannot cut pieces (legacy .vtk) gives the whole image to
    process 0: the filter must keep it whole (no crop) and match the serial result."""
    from vtkmodules.vtkIOLegacy import vtkStructuredPointsWriter
    source, keep = wavelet([0, 63, 0, 63, 0, 0])
    path = os.path.join(OUTPUT, "unsplit.vtk")
    writer = vtkStructuredPointsWriter()
    writer.SetInputConnection(source.GetOutputPort())
    writer.SetFileName(path)
    writer.SetFileTypeToBinary()
    writer.Write()
    from vtkmodules.vtkIOLegacy import vtkStructuredPointsReader
    file_reader = vtkStructuredPointsReader()
    file_reader.SetFileName(path)
    serial = serial_filter("ImageShockAdvection", file_reader, InputArray=["POINTS", "RTData"], FlowTime=64)
    reader_proxy = LegacyVTKReader(FileNames=[path])
    filtered = ImageShockAdvection(Input=reader_proxy, InputArray=["POINTS", "RTData"], FlowTime=64)
    out = os.path.join(OUTPUT, "image_unsplit.pvti")
    SaveData(out, proxy=filtered)
    Delete(filtered)
    Delete(reader_proxy)
    reader = vtkXMLPImageDataReader()
    reader.SetFileName(out)
    reader.Update()
    image = reader.GetOutput()
    check(image.GetNumberOfPoints() == 64 * 64, "unsplit reader: %d points kept" % image.GetNumberOfPoints())
    parallel = vtk_to_numpy(image.GetPointData().GetArray("RTData"))
    expected = vtk_to_numpy(serial.GetPointData().GetArray("RTData"))
    check(parallel.shape == expected.shape and np.array_equal(parallel, expected),
          "unsplit reader: equals the serial result")


def sphere_input(resolution, expression):
    source = vtkSphereSource()
    source.SetThetaResolution(resolution)
    source.SetPhiResolution(resolution)
    calculator = vtkArrayCalculator()
    calculator.SetInputConnection(source.GetOutputPort())
    for axis, name in enumerate(("coordsX", "coordsY", "coordsZ")):
        calculator.AddCoordinateScalarVariable(name, axis)
    calculator.SetFunction(expression)
    calculator.SetResultArrayName("Heat")
    calculator.SetResultArrayType(11)
    return calculator, [source, calculator]


def point_key(points):
    return [tuple(p) for p in np.round(np.asarray(points, dtype=float), 9)]


def surface_case(label, resolution, flow_time, ghost_levels, ghosts, max_bound, fraction_bound):
    """Per-point agreement of Surface Shock Advection on sphere pieces."""
    expression = "tanh((coordsZ+0.3*coordsX)*12)"
    reference_input, keep = sphere_input(resolution, expression)
    serial = serial_filter("SurfaceShockAdvection", reference_input, InputArray=["POINTS", "Heat"],
                           FlowTime=flow_time)
    expected = dict(zip(point_key(vtk_to_numpy(serial.GetPoints().GetData())),
                        vtk_to_numpy(serial.GetPointData().GetArray("Heat"))))
    proxies = [Sphere(ThetaResolution=resolution, PhiResolution=resolution)]
    proxies.append(Calculator(Input=proxies[-1], Function=expression, ResultArrayName="Heat"))
    if ghosts:
        proxies.append(GhostCellsGenerator(Input=proxies[-1]))
    filtered = SurfaceShockAdvection(Input=proxies[-1], InputArray=["POINTS", "Heat"], FlowTime=flow_time,
                                     GhostLevels=ghost_levels)
    path = os.path.join(OUTPUT, "surface_%s.pvtp" % label)
    SaveData(path, proxy=filtered)
    for proxy in [filtered] + proxies[::-1]:
        Delete(proxy)
    reader = vtkXMLPPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    mesh = reader.GetOutput()
    values = vtk_to_numpy(mesh.GetPointData().GetArray("Heat"))
    ghost_array = mesh.GetPointData().GetArray("vtkGhostType")
    owned = vtk_to_numpy(ghost_array) == 0 if ghost_array else np.ones(len(values), bool)
    keys = point_key(vtk_to_numpy(mesh.GetPoints().GetData()))
    if ghosts:
        check(ghost_array is not None and (~owned).any(), "%s: the output keeps the ghost points" % label)
    missing = sum(1 for k in keys if k not in expected)
    if not check(missing == 0, "%s: %d points not in the serial mesh" % (label, missing)):
        return
    difference = np.array([abs(v - expected[k]) for k, v, o in zip(keys, values, owned) if o])
    scale = np.ptp(np.array(list(expected.values())))
    print("MEASURE surface %-22s T=%-6g GhostLevels=%-3d ghost cells=%-3s points differing: %.2f%% (>1e-12), "
          "%.3f%% (>1e-3 of the range); max|diff|/range=%.2g" % (
              label, flow_time, ghost_levels, "yes" if ghosts else "no", 100 * np.mean(difference > 1e-12 * scale),
              100 * np.mean(difference > 1e-3 * scale), difference.max() / scale), flush=True)
    check(difference.max() <= max_bound * scale, "%s: max difference %.3g of the range (bound %g)"
          % (label, difference.max() / scale, max_bound))
    check(np.mean(difference > 1e-3 * scale) <= fraction_bound,
          "%s: %.3f%% of the points differ by more than 1e-3 of the range (bound %g%%)"
          % (label, 100 * np.mean(difference > 1e-3 * scale), 100 * fraction_bound))


def sharpen_cases():
    # Refused on pieces of a distributed mesh.
    del messages.errors[:]
    sphere = Sphere(ThetaResolution=32, PhiResolution=32)
    sharpen = SurfaceShockSharpen(Input=sphere, FlowTime=256)
    sharpen.UpdatePipeline()
    info = sharpen.GetDataInformation()
    check(info.GetNumberOfPoints() == 0, "sharpen on pieces: empty output (%d points)" % info.GetNumberOfPoints())
    refused = [e for e in messages.errors if "cannot run on one piece of a distributed mesh" in e]
    check(len(refused) >= 1, "sharpen on pieces: the refusal message (errors: %s)" % messages.errors)
    if refused:
        print("MEASURE sharpen refusal message:", refused[0].strip().splitlines()[-1], flush=True)
    check(any("Aggregate Dataset" in e for e in refused), "sharpen refusal says what to do")
    Delete(sharpen)

    # Accepted on a mesh gathered onto one process; compared with the serial result
    # through the original coordinates carried as a point array.
    del messages.errors[:]
    calculator = Calculator(Input=sphere, Function="coords", ResultArrayName="Original")
    aggregate = AggregateDataset(Input=calculator, NumberOfTargetProcesses=1)
    # The Sphere source computes the points its pieces share separately, so the
    # copies differ in the last bits: Clean merges them (MergeCoincidentPoints
    # only merges exact copies), else the seam would act as a boundary.
    clean = Clean(Input=aggregate, Tolerance=1e-6)
    sharpen = SurfaceShockSharpen(Input=clean, FlowTime=256, Solver="Exact")
    path = os.path.join(OUTPUT, "sharpen_aggregated.pvtp")
    SaveData(path, proxy=sharpen)
    check(not messages.errors, "sharpen on an aggregated mesh: no error (%s)" % messages.errors)
    for proxy in (sharpen, clean, aggregate, calculator, sphere):
        Delete(proxy)
    reader = vtkXMLPPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    mesh = reader.GetOutput()

    source = vtkSphereSource()
    source.SetThetaResolution(32)
    source.SetPhiResolution(32)
    serial = serial_filter("SurfaceShockSharpen", source, FlowTime=256, Solver="Exact")
    expected = dict(zip(point_key(vtk_to_numpy(source.GetOutput().GetPoints().GetData())),
                        vtk_to_numpy(serial.GetPoints().GetData())))
    original = point_key(vtk_to_numpy(mesh.GetPointData().GetArray("Original")))
    moved = vtk_to_numpy(mesh.GetPoints().GetData())
    if not check(mesh.GetNumberOfPoints() > 0 and all(k in expected for k in original),
                 "sharpen on an aggregated mesh: every point found in the serial mesh"):
        return
    error = max(np.linalg.norm(m - expected[k]) for k, m in zip(original, moved))
    print("MEASURE sharpen aggregated onto one process (Aggregate Dataset + Clean): "
          "max |position - serial| = %.2g (sphere radius 0.5)" % error, flush=True)
    check(error < 1e-6, "sharpen on an aggregated mesh matches the serial fit (%.3g)" % error)


cases = [
    # label, extent, FlowTime, GhostLevels, band W, bound on the differing fraction
    lambda: image_case("wavelet2d", [0, 255, 0, 255, 0, 0], 64, 16, 16, 0.005),
    lambda: image_case("wavelet2d_g0", [0, 255, 0, 255, 0, 0], 64, 0, 8, 0.05),
    lambda: image_case("step2d_t4096_g4", [-128, 127, -128, 127, 0, 0], 4096, 4, 8, 0.01,
                       expression="tanh((coordsY-12+0.1*coordsX)/6)"),
    lambda: image_case("step2d_t4096", [-128, 127, -128, 127, 0, 0], 4096, 16, 16, 0.005,
                       expression="tanh((coordsY-12+0.1*coordsX)/6)"),
    lambda: image_case("wavelet2d_cells", [0, 255, 0, 255, 0, 0], 64, 16, 16, 0.005, cells=True),
    lambda: image_case("wavelet3d", [0, 95, 0, 95, 0, 95], 256, 16, 16, 0.005),
    unsplit_image_case,
    # With ghost cells and the default Ghost Levels the pieces equal the serial
    # result (global range and mean edge length); with 2 levels, nearly.
    lambda: surface_case("sphere_ghosts", 128, 64, 16, True, 1e-12, 0.0),
    lambda: surface_case("sphere_ghosts_t1024", 128, 1024, 16, True, 1e-12, 0.0),
    lambda: surface_case("sphere_ghosts_g2_t1024", 128, 1024, 2, True, 1e-5, 0.0),
    lambda: surface_case("sphere_no_ghosts", 128, 64, 16, False, 0.05, 0.02),
    sharpen_cases,
]
for case in cases:
    try:
        case()
    except Exception:  # report and go on: every process must reach the end
        check(False, "exception:\n" + traceback.format_exc())

print("%d passed, %d failed" % (passed, len(failures)), flush=True)
# On success the script just ends, so that pvbatch finalizes MPI and releases
# the other processes (sys.exit(0) would skip that and mpirun would report an
# improper exit). On failure a non-zero exit makes mpirun stop them all.
if failures:
    sys.exit(1)
