"""Strong and weak scaling of the three filters under MPI, as users run them.

Each figure is the median of fresh processes. One process group is started
per run (`mpirun -np N pvbatch --symmetric --mpi`, or plain `pvbatch`); inside
it the data are read and spread (RedistributeDataSet for meshes; images are
read by the pieces themselves) before the timed part, then the filter's
proxy is updated between two barriers: ghost building, global ids, every
exchange and every reduction are inside the time.

  /usr/bin/python3 Benchmarks/mpi_scaling.py prepare DIR
      Write the inputs into DIR (needs Benchmarks/get_meshes.sh's meshes):
      dragon640k.vtp, dragon2560k.vtp (the Chinese Dragon Loop-subdivided 3
      and 4 times, with a blurred scalar "Heat"), wavelet256.vti (256^3 float).
  /usr/bin/python3 Benchmarks/mpi_scaling.py strong PLUGIN DIR [RUNS]
      The strong-scaling table: every work on 1 rank x 1 thread, 2 ranks x 1
      thread, 1 rank x 2 threads (plain pvbatch) and `mpirun -np 1` x 2 threads.
  /usr/bin/python3 Benchmarks/mpi_scaling.py weak PLUGIN DIR [RUNS]
      Weak scaling on 1, 2, 4, 8 ranks (oversubscribed beyond 2): per-rank
      work, ghost fraction, bytes exchanged per CG iteration, time per owned
      sample.
  /usr/bin/python3 Benchmarks/mpi_scaling.py versus PLUGIN_BEFORE PLUGIN_AFTER DIR [RUNS]
      Two builds on the same works, interleaved round by round (2 ranks and
      1 rank, 1 thread each): before / after, with the 2 / 1 ratios.
  /usr/bin/python3 Benchmarks/mpi_scaling.py ceiling PLUGIN DIR [RUNS]
      What two processes can do on this machine without any MPI step: each
      work's two pieces (the meshes as RedistributeDataSet cuts them for 2
      ranks, without ghost rings; the volume's halves with their halo of
      Ghost Levels samples) filtered by two 1-thread processes at once, each
      by itself (the VTK class on its file, no collective step, started at a
      barrier), against one process filtering the whole and one filtering a
      piece alone. The pieces are written into DIR/pieces once.
  pvbatch [--symmetric --mpi] Benchmarks/mpi_scaling.py run PLUGIN WORK INPUT
      One run (what the two commands above start); every rank prints one
      "RANKRESULT {json}" line.

Works: sharpen (Surface Shock Sharpen, t = 2048), advect (Surface Shock
Advection of "Heat", t = 4096), image (Image Shock Advection of RTData,
t = 64). Benchmarks/RESULTS.md has the figures.
"""
import json
import os
import re
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe"]


# --- inputs ----------------------------------------------------------------

def prepare(directory):
    import numpy as np
    sys.path.insert(0, HERE)
    from mpi_sharpen import prepare as subdivide
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter, vtkXMLImageDataWriter
    from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    os.makedirs(directory, exist_ok=True)
    mesh_dir = os.environ.get("SHOCK_MESH_DIR", os.path.expanduser("~/.cache/shockfilters/meshes"))
    for levels, name in ((3, "dragon640k.vtp"), (4, "dragon2560k.vtp")):
        path = os.path.join(directory, name)
        subdivide(os.path.join(mesh_dir, "ChineseDragon-10kv.off"), levels, path)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        mesh = reader.GetOutput()
        x = vtk_to_numpy(mesh.GetPoints().GetData()).astype(float)
        size = np.ptp(x, axis=0).max()
        heat = numpy_to_vtk(np.tanh(8.0 * (x[:, 2] + 0.3 * x[:, 0] - x[:, 2].mean()) / size), deep=1)
        heat.SetName("Heat")
        mesh.GetPointData().SetScalars(heat)
        writer = vtkXMLPolyDataWriter()
        writer.SetInputData(mesh)
        writer.SetFileName(path)
        writer.SetDataModeToAppended()
        writer.EncodeAppendedDataOff()
        writer.Write()
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(0, 255, 0, 255, 0, 255)
    writer = vtkXMLImageDataWriter()
    writer.SetInputConnection(source.GetOutputPort())
    writer.SetFileName(os.path.join(directory, "wavelet256.vti"))
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.Write()
    print("inputs in", directory)


# --- one run -----------------------------------------------------------------

def memory(field):
    for line in open("/proc/self/status"):
        if line.startswith(field + ":"):
            return int(line.split()[1]) / 1024.0  # MiB
    return 0.0


def run(plugin, work, path):
    # The VTK classes' Python wrapping (when built) gives the filters' phase times.
    site = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(plugin)))),
                        "python%d.%d" % sys.version_info[:2], "site-packages")
    if os.path.isdir(os.path.join(site, "shockfilters")):
        sys.path.insert(0, site)
        try:
            import shockfilters  # noqa: F401
        except ImportError:
            pass  # a build without the package: no phase times
    from paraview import simple
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    simple.LoadPlugin(plugin, ns=globals())
    controller = vtkMultiProcessController.GetGlobalController()
    rank = controller.GetLocalProcessId() if controller else 0
    ranks = controller.GetNumberOfProcesses() if controller else 1
    if work == "image":
        source = simple.XMLImageDataReader(FileName=[path])
        source.UpdatePipelineInformation()
        filtered = globals()["ImageShockAdvection"](Input=source, FlowTime=64)
    else:
        reader = simple.XMLPolyDataReader(FileName=[path])
        source = simple.RedistributeDataSet(Input=reader) if ranks > 1 else reader
        source.UpdatePipeline()
        if work == "sharpen":
            filtered = globals()["SurfaceShockSharpen"](Input=source, FlowTime=2048)
        else:
            filtered = globals()["SurfaceShockAdvection"](Input=source, FlowTime=4096)
    # The pieces' figures (points in ghost layers, bytes per CG iteration) are
    # Surface Shock Sharpen's log lines at verbosity 1; weak() reads them.
    from vtkmodules.vtkCommonCore import vtkLogger
    if vtkLogger.GetCurrentVerbosityCutoff() < vtkLogger.VERBOSITY_1:  # -v=TRACE stays TRACE
        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_1)
    # No malloc_trim here: process 0, which read the whole mesh before
    # RedistributeDataSet spread it, reuses the free memory that left in its
    # heap, as it does when users run it (docs/parallel.md, "Scale").
    with open("/proc/self/clear_refs", "w") as handle:
        handle.write("5")  # VmHWM back to the current resident set
    before = memory("VmRSS")
    if controller:
        controller.Barrier()
    import resource
    usage = resource.getrusage(resource.RUSAGE_SELF)
    faults = usage.ru_minflt
    cpu = usage.ru_utime + usage.ru_stime
    system = usage.ru_stime
    start = time.perf_counter()
    filtered.UpdatePipeline()
    if controller:
        controller.Barrier()
    seconds = time.perf_counter() - start
    usage = resource.getrusage(resource.RUSAGE_SELF)
    faults = usage.ru_minflt - faults  # pages touched for the first time
    cpu = usage.ru_utime + usage.ru_stime - cpu  # the process's CPU time in the window (all its threads)
    system = usage.ru_stime - system  # of which in the kernel (page faults are counted here)
    peak = memory("VmHWM") - before
    data = filtered.GetClientSideObject().GetOutputDataObject(0)
    ghosts = data.GetPointData().GetArray("vtkGhostType") if work != "image" else None
    points = data.GetNumberOfPoints()
    owned = points
    if work == "image" and points > 0:
        # The piece's halo: the samples it used on each side (Last Ghost Levels;
        # Ghost Levels before it was sized from the flow lines), within the whole extent.
        from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
        whole = source.GetClientSideObject().GetOutputInformation(0).Get(
            vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT())
        extent = data.GetExtent()
        used = getattr(filtered.GetClientSideObject(), "GetLastGhostLevels", None)
        halo = used() if used and ranks > 1 else (filtered.GhostLevels if ranks > 1 else 0)
        grown = 1
        for a in range(3):
            low = max(whole[2 * a], extent[2 * a] - halo)
            high = min(whole[2 * a + 1], extent[2 * a + 1] + halo)
            grown *= high - low + 1
        points = grown  # the samples filtered: the piece and its halo
    if ghosts is not None:
        from vtkmodules.util.numpy_support import vtk_to_numpy
        owned = int((vtk_to_numpy(ghosts) == 0).sum())
    phases = {}
    algorithm = filtered.GetClientSideObject()
    for phase in ("Setup", "Flow", "Advection", "FitSetup", "FitSolve"):
        getter = getattr(algorithm, "GetLast%sSeconds" % phase, None)
        if getter:
            phases[re.sub(r"(?<!^)(?=[A-Z])", "_", phase).lower()] = getter()
    print("RANKRESULT " + json.dumps(dict(rank=rank, ranks=ranks, seconds=seconds, peak_mib=peak,
                                          points=points, owned=owned, page_faults=faults, cpu=cpu, system=system, **phases)), flush=True)


# --- drivers -----------------------------------------------------------------

def launch(plugin, work, path, ranks, threads, mpi=True, keep_log=False):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    script = [os.path.abspath(__file__), "run", plugin, work, path]
    if mpi:
        command = MPIRUN + ["-np", str(ranks), "pvbatch", "--symmetric", "--mpi"] + script
    else:
        command = ["pvbatch"] + script
    out = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         universal_newlines=True, timeout=1800)
    # Ranks print concurrently: lines may run together.
    results = [json.loads(m) for m in re.findall(r"RANKRESULT (\{[^}]*\})", out.stdout)]
    if out.returncode != 0 or len(results) != ranks:
        sys.stderr.write(out.stdout[-3000:])
        raise SystemExit("run failed: %s" % " ".join(command))
    return (results, out.stdout) if keep_log else results


def medians(plugin, work, path, ranks, threads, mpi, runs):
    times, peaks, per_point, cpu = [], [], [], []
    for _ in range(runs):
        results = launch(plugin, work, path, ranks, threads, mpi)
        times.append(max(r["seconds"] for r in results))
        cpu.append(sum(r["cpu"] for r in results))
        peaks.append(max(r["peak_mib"] for r in results))
        per_point.append(max(1024.0 * 1024.0 * r["peak_mib"] / max(r["owned"], 1) for r in results))
    return (statistics.median(times), min(times), max(times), statistics.median(peaks), statistics.median(per_point),
            statistics.median(cpu))


WORKS = [("sharpen", "dragon640k.vtp"), ("advect", "dragon640k.vtp"), ("sharpen", "dragon2560k.vtp"),
         ("image", "wavelet256.vti")]
if os.environ.get("SHOCK_SCALING_WORKS"):  # e.g. "sharpen:dragon640k.vtp,image:wavelet256.vti"
    WORKS = [tuple(w.split(":")) for w in os.environ["SHOCK_SCALING_WORKS"].split(",")]


def strong(plugin, directory, runs):
    """The strong-scaling table. The machine is shared and its speed drifts, so
    besides the medians of each configuration it gives the median of the
    per-run ratios (run i of 2 ranks against run i of 1 rank, started one after
    the other) and the CPU time summed over the ranks: what distribution adds
    in work, whatever the wall clock did (Open MPI spins while a rank waits in
    a collective step, so waiting for the slower rank counts too)."""
    configs = [("1 rank x 1 thread", 1, 1, True), ("2 ranks x 1 thread", 2, 1, True),
               ("pvbatch x 2 threads", 1, 2, False), ("mpirun -np 1 x 2 threads", 1, 2, True)]
    print("| work | " + " | ".join(c[0] for c in configs) +
          " | 2 ranks / 1 rank | the same, median of per-run ratios | CPU, 2 ranks (sum) / 1 rank | np 1 / pvbatch |")
    print("|---" * (len(configs) + 5) + "|")
    for work, name in WORKS:
        path = os.path.join(directory, name)
        row = {}
        cells = []
        # Interleaved: each run of each configuration in turn, so that a noisy period hits all.
        samples = {c[0]: [] for c in configs}
        for _ in range(runs):
            for label, ranks, threads, mpi in configs:
                samples[label].append(medians(plugin, work, path, ranks, threads, mpi, 1))
        for label, _, _, _ in configs:
            times = [s[0] for s in samples[label]]
            row[label] = statistics.median(times)
            per_point = statistics.median(s[4] for s in samples[label])
            cells.append("%.3f s (%.3f-%.3f), %.0f B/owned point" % (row[label], min(times), max(times), per_point))
        one, two = samples[configs[0][0]], samples[configs[1][0]]
        pair_ratio = statistics.median(b[0] / a[0] for a, b in zip(one, two))
        cpu_ratio = statistics.median(b[5] for b in two) / statistics.median(a[5] for a in one)
        print("| %s %s | %s | %.2f | %.2f | %.2f | %.2f |" % (work, name, " | ".join(cells),
                                                            row[configs[1][0]] / row[configs[0][0]], pair_ratio,
                                                            cpu_ratio, row[configs[3][0]] / row[configs[2][0]]),
              flush=True)


def versus(before, after, directory, runs):
    """Two builds of the plugin on the same works, interleaved: each round runs
    `after` and `before` on 2 ranks and on 1 rank (1 thread each), so that a
    noisy period hits both; medians, the 2 / 1 ratios and the per-round
    after / before ratio on 2 ranks."""
    print("| work | build | 2 ranks | 1 rank | 2 / 1 | the same, median of per-run ratios |")
    print("|---|---|---|---|---|---|")
    for work, name in WORKS:
        path = os.path.join(directory, name)
        times = {(b, r): [] for b in ("before", "after") for r in (1, 2)}
        for _ in range(runs):
            for label, plugin in (("after", after), ("before", before)):
                for ranks in (2, 1):
                    times[(label, ranks)].append(medians(plugin, work, path, ranks, 1, True, 1)[0])
        for label in ("before", "after"):
            two, one = times[(label, 2)], times[(label, 1)]
            print("| %s %s | %s | %.3f s (%.3f-%.3f) | %.3f s (%.3f-%.3f) | %.2f | %.2f |" % (
                work, name, label, statistics.median(two), min(two), max(two), statistics.median(one), min(one),
                max(one), statistics.median(two) / statistics.median(one),
                statistics.median(b / a for a, b in zip(one, two))), flush=True)
        rounds = statistics.median(b / a for a, b in zip(times[("before", 2)], times[("after", 2)]))
        print("| %s %s | after / before, 2 ranks, median per round | %.2f | | | |" % (work, name, rounds), flush=True)


def weak(plugin, directory, runs):
    """Per-rank figures on 1 to 8 ranks (more ranks than the 2 cores: oversubscribed,
    so the wall time is not the figure; the time per owned sample is scaled by the
    share of a core each rank had)."""
    print("| work | ranks | wall time (s) | owned samples per rank (largest) | samples filtered per rank "
          "(with ghosts/halo, largest) | ghost fraction (all ranks) | bytes per CG iteration per rank, sent + "
          "received (largest) | time per owned sample x core share (us) |")
    print("|---|---|---|---|---|---|---|---|")
    for work, name in [w for w in WORKS if w[1] != "dragon2560k.vtp"]:
        path = os.path.join(directory, name)
        for ranks in (1, 2, 4, 8):
            times, results, traffic = [], None, 0
            rings = {}
            for _ in range(runs):
                results, log = launch(plugin, work, path, ranks, 1, keep_log=True)
                times.append(max(r["seconds"] for r in results))
                for sent, received in re.findall(r"per CG iteration (\d+) bytes sent and (\d+) received", log):
                    traffic = max(traffic, int(sent) + int(received))
                # Surface Shock Sharpen logs each piece's points in its ghost rings.
                for rank, total, in_rings in re.findall(
                        r"piece (\d+) of \d+: (\d+) points \(\d+ owned, (\d+) in ghost layers\)", log):
                    rings[int(rank)] = (int(total), int(in_rings))
            seconds = statistics.median(times)
            owned = max(r["owned"] for r in results)
            local = max(r["points"] for r in results)
            ghost = sum(r["points"] - r["owned"] for r in results) / max(sum(r["owned"] for r in results), 1)
            if rings:
                local = max(total for total, _ in rings.values())
                ghost = sum(g for _, g in rings.values()) / max(sum(r["owned"] for r in results), 1)
            share = min(1.0, 2.0 / ranks)  # 2 cores
            print("| %s %s | %d | %.3f | %d | %d | %.3f | %s | %.3f |" % (
                work, name, ranks, seconds, owned, local, ghost, traffic if work == "sharpen" else "-",
                1e6 * seconds * share / max(owned, 1)), flush=True)


def split(path, outdir):
    """Under `mpirun -np 2 pvbatch --symmetric --mpi`: write each rank's piece of
    the mesh `path` as RedistributeDataSet gives it (a surface, no ghost cells)."""
    from paraview import simple
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    controller = vtkMultiProcessController.GetGlobalController()
    rank = controller.GetLocalProcessId()
    spread = simple.RedistributeDataSet(Input=simple.XMLPolyDataReader(FileName=[path]))
    spread.UpdatePipeline()
    surface = vtkGeometryFilter()
    surface.SetInputData(spread.GetClientSideObject().GetOutputDataObject(0))
    surface.Update()
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(surface.GetOutput())
    write_raw(writer, piece_path(outdir, os.path.basename(path), rank))


def write_raw(writer, path):
    """Write with `writer` (an XML writer with its input set) into `path`, appended raw data."""
    writer.SetFileName(path)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.Write()


def piece_path(outdir, name, rank):
    stem, extension = os.path.splitext(name)
    return os.path.join(outdir, "%s.piece%d%s" % (stem, rank, extension))


def split_image(path, outdir, layers=16):
    """The two pieces of a volume as ParaView's extent translator cuts them for
    2 ranks, each grown by `layers` samples (the filter's default Ghost Levels)
    within the whole extent: what each rank of the MPI run filters."""
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter
    from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
    from vtkmodules.vtkImagingCore import vtkExtractVOI
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    whole = reader.GetOutput().GetExtent()
    for rank in range(2):
        translator = vtkExtentTranslator()
        translator.SetWholeExtent(whole)
        translator.SetNumberOfPieces(2)
        translator.SetPiece(rank)
        translator.SetGhostLevel(0)
        translator.PieceToExtent()
        extent = list(translator.GetExtent())
        for a in range(3):
            extent[2 * a] = max(whole[2 * a], extent[2 * a] - layers)
            extent[2 * a + 1] = min(whole[2 * a + 1], extent[2 * a + 1] + layers)
        voi = vtkExtractVOI()
        voi.SetInputConnection(reader.GetOutputPort())
        voi.SetVOI(extent)
        writer = vtkXMLImageDataWriter()
        writer.SetInputConnection(voi.GetOutputPort())
        write_raw(writer, piece_path(outdir, os.path.basename(path), rank))


def alone(plugin, work, pattern):
    """Under `mpirun -np N pvbatch --symmetric --mpi`: every rank filters the file
    `pattern % rank` by itself (the VTK class, one piece: no collective step),
    all starting at one barrier; every rank prints its RANKRESULT."""
    site = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(plugin)))),
                        "python%d.%d" % sys.version_info[:2], "site-packages")
    sys.path.insert(0, site)
    import shockfilters
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader
    controller = vtkMultiProcessController.GetGlobalController()
    rank = controller.GetLocalProcessId()
    reader = vtkXMLImageDataReader() if work == "image" else vtkXMLPolyDataReader()
    reader.SetFileName(pattern % rank if "%d" in pattern else pattern)
    reader.Update()
    if work == "image":
        filtered, time_ = shockfilters.vtkImageShockAdvectionFilter(), 64
    elif work == "sharpen":
        filtered, time_ = shockfilters.vtkPolyDataShockSharpenFilter(), 2048
    else:
        filtered, time_ = shockfilters.vtkPolyDataShockAdvectionFilter(), 4096
    filtered.SetFlowTime(time_)
    filtered.SetInputConnection(reader.GetOutputPort())
    controller.Barrier()
    start = time.perf_counter()
    filtered.Update()
    seconds = time.perf_counter() - start
    controller.Barrier()
    print("RANKRESULT " + json.dumps(dict(rank=rank, seconds=seconds)), flush=True)


def concurrent(plugin, work, pattern, processes):
    """`processes` 1-thread ranks filtering `pattern % rank` each by itself; their RANKRESULTs."""
    command = MPIRUN + ["-np", str(processes), "pvbatch", "--symmetric", "--mpi", os.path.abspath(__file__),
                        "alone", plugin, work, pattern]
    out = subprocess.run(command, env=dict(os.environ, OMP_NUM_THREADS="1"), stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, universal_newlines=True, timeout=1800)
    results = [json.loads(m) for m in re.findall(r"RANKRESULT (\{[^}]*\})", out.stdout)]
    if out.returncode != 0 or len(results) != processes:
        sys.stderr.write(out.stdout[-3000:])
        raise SystemExit("run failed: %s" % " ".join(command))
    return results


def ceiling(plugin, directory, runs):
    """Two processes without MPI against one: this machine's ceiling for the strong-scaling ratio."""
    pieces = os.path.join(directory, "pieces")
    os.makedirs(pieces, exist_ok=True)
    print("| work | 1 process, whole | 1 process, piece 0 alone | 2 processes at once, pieces 0 and 1 "
          "(the slower) | at once / alone | at once / whole |")
    print("|---|---|---|---|---|---|")
    for work, name in WORKS:
        path = os.path.join(directory, name)
        parts = [piece_path(pieces, name, rank) for rank in range(2)]
        if not all(os.path.exists(p) for p in parts):
            if work == "image":
                split_image(path, pieces)
            else:
                subprocess.run(MPIRUN + ["-np", "2", "pvbatch", "--symmetric", "--mpi", os.path.abspath(__file__),
                                         "split", path, pieces], check=True, stdout=subprocess.DEVNULL,
                               timeout=1800)
        whole, alone, together = [], [], []
        for _ in range(runs):  # interleaved, so that a noisy period hits all three
            pattern = piece_path(pieces, name, 0).replace(".piece0", ".piece%d")
            whole.append(concurrent(plugin, work, path, 1)[0]["seconds"])
            alone.append(concurrent(plugin, work, pattern, 1)[0]["seconds"])
            together.append(max(r["seconds"] for r in concurrent(plugin, work, pattern, 2)))
        w, a, t = (statistics.median(x) for x in (whole, alone, together))
        cell = lambda xs: "%.3f s (%.3f-%.3f)" % (statistics.median(xs), min(xs), max(xs))
        print("| %s %s | %s | %s | %s | %.2f | **%.2f** |" % (work, name, cell(whole), cell(alone), cell(together),
                                                              t / a, t / w), flush=True)


if __name__ == "__main__":
    command = sys.argv[1]
    if command == "prepare":
        prepare(sys.argv[2])
    elif command == "run":
        run(sys.argv[2], sys.argv[3], sys.argv[4])
    elif command == "strong":
        strong(sys.argv[2], sys.argv[3], int(sys.argv[4]) if len(sys.argv) > 4 else 5)
    elif command == "ceiling":
        ceiling(sys.argv[2], sys.argv[3], int(sys.argv[4]) if len(sys.argv) > 4 else 3)
    elif command == "alone":
        alone(sys.argv[2], sys.argv[3], sys.argv[4])
    elif command == "split":
        split(sys.argv[2], sys.argv[3])
    elif command == "versus":
        versus(sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]) if len(sys.argv) > 5 else 7)
    elif command == "weak":
        weak(sys.argv[2], sys.argv[3], int(sys.argv[4]) if len(sys.argv) > 4 else 3)
    else:
        raise SystemExit(__doc__)
