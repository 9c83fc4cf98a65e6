"""Distributed geometry sharpening, measured: time, peak memory per process,
ghost layers and traffic per conjugate-gradient iteration.

  pvpython Benchmarks/mpi_sharpen.py prepare MESH.off LEVELS OUT.vtp
      Loop-subdivide an OFF mesh LEVELS times (each ~4x the vertices) and write it.
  mpirun -np N pvbatch --symmetric --mpi Benchmarks/mpi_sharpen.py run PLUGIN MESH.vtp [FlowTime] [GhostLevels]
      Every process: the mesh is read (by process 0) and spread by RedistributeDataSet,
      then Surface Shock Sharpen runs on the pieces. Each process prints one
      "RANK" line: seconds of the filter, its peak resident memory above the
      memory held before it (VmHWM after /proc/self/clear_refs), and the
      filter's own log line at verbosity 1 (points owned and in ghost layers, bytes per CG iteration).

docs/parallel.md has the figures and the plan derived from them.
"""
import sys
import time


def prepare(off_path, levels, out_path):
    import numpy as np
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkFiltersModeling import vtkLoopSubdivisionFilter
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    words = [line.split("#")[0].split() for line in open(off_path)]
    words = [w for w in words if w]
    assert words[0][0].upper().endswith("OFF")
    header = words[1] if len(words[0]) == 1 else words[0][1:]
    first = 2 if len(words[0]) == 1 else 1
    n_points, n_faces = int(header[0]), int(header[1])
    points = np.array(words[first:first + n_points], dtype=float)[:, :3]
    faces = [list(map(int, w[1:1 + int(w[0])])) for w in words[first + n_points:first + n_points + n_faces]]
    triangles = np.array([[f[0], f[k], f[k + 1]] for f in faces for k in range(1, len(f) - 1)], dtype=np.int64)
    mesh = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(points, deep=1))
    mesh.SetPoints(vtk_points)
    cells = vtkCellArray()
    offsets = np.arange(0, 3 * len(triangles) + 1, 3, dtype=np.int64)
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=1), numpy_to_vtkIdTypeArray(triangles.ravel(), deep=1))
    mesh.SetPolys(cells)
    loop = vtkLoopSubdivisionFilter()
    loop.SetNumberOfSubdivisions(levels)
    loop.SetInputData(mesh)
    writer = vtkXMLPolyDataWriter()
    writer.SetInputConnection(loop.GetOutputPort())
    writer.SetFileName(out_path)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.Write()
    print("wrote %s: %d vertices" % (out_path, loop.GetOutput().GetNumberOfPoints()))


def memory(field):
    for line in open("/proc/self/status"):
        if line.startswith(field + ":"):
            return int(line.split()[1]) / 1024.0  # MiB
    return 0.0


def run(plugin, mesh_path, flow_time, ghost_levels):
    from paraview.simple import LoadPlugin, XMLPolyDataReader, RedistributeDataSet
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    LoadPlugin(plugin, ns=globals())
    controller = vtkMultiProcessController.GetGlobalController()
    rank = controller.GetLocalProcessId()
    reader = XMLPolyDataReader(FileName=[mesh_path])
    pieces = RedistributeDataSet(Input=reader)
    pieces.UpdatePipeline()
    sharpen = globals()["SurfaceShockSharpen"](Input=pieces, FlowTime=flow_time, GhostLevels=ghost_levels)
    from vtkmodules.vtkCommonCore import vtkLogger
    if vtkLogger.GetCurrentVerbosityCutoff() < vtkLogger.VERBOSITY_1:
        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_1)  # the filter's piece line
    with open("/proc/self/clear_refs", "w") as handle:
        handle.write("5")  # reset VmHWM to the current resident set
    before = memory("VmRSS")
    controller.Barrier()
    start = time.perf_counter()
    sharpen.UpdatePipeline()
    controller.Barrier()
    seconds = time.perf_counter() - start
    peak = memory("VmHWM")
    print("RANK %d of %d: %.2f s, resident before %.0f MiB, peak above it %.0f MiB"
          % (rank, controller.GetNumberOfProcesses(), seconds, before, peak - before), flush=True)


if __name__ == "__main__":
    if sys.argv[1] == "prepare":
        prepare(sys.argv[2], int(sys.argv[3]), sys.argv[4])
    else:
        run(sys.argv[2], sys.argv[3], float(sys.argv[4]) if len(sys.argv) > 4 else 2048.0,
            int(sys.argv[5]) if len(sys.argv) > 5 else 16)
