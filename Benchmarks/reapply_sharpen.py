"""Re-Apply of Surface Shock Sharpen in pvpython: the time of the first Apply and
of each Apply after changing one parameter, as a ParaView user does it.

    pvpython Benchmarks/reapply_sharpen.py PLUGIN MESH [REPEATS]

PLUGIN: build/lib/paraview-5.11/plugins/ShockFilters/ShockFilters.so; MESH: any
surface ParaView reads (e.g. the 640K dragon written by `meshbench sharpen
--levels 3 --dump PREFIX`). Each step changes one parameter and updates the
pipeline (what Apply does); steps marked "flow" change only a flow parameter,
which must not prepare the mesh or assemble the fit again. Markdown on stdout:
median (and range) over REPEATS rounds of the steps, in one process: the wall
time of UpdatePipeline, the CPU time of the process during it (all threads;
less sensitive to other processes), and the filter's own LastSetupSeconds (the
mesh preparation: ~0 when the prepared mesh is kept). The counts of preparations
and assemblies are checked by Testing/Cxx/TestPolyDataSharpenCache.cxx.
"""
import statistics
import sys
import time

from paraview.simple import LoadPlugin, OpenDataFile

STEPS = [  # (label, kind, property, value)
    ("first Apply, FlowTime 2048", "first", None, None),
    ("FlowTime 1024", "flow", "FlowTime", 1024.0),
    ("FlowTime 4096", "flow", "FlowTime", 4096.0),
    ("SolverIterations 40", "flow", "SolverIterations", 40),
    ("FeatureAngle 40", "normals", "FeatureAngle", 40.0),
    ("ScreeningWeight 2", "fit matrix", "ScreeningWeight", 2.0),
]


def main():
    plugin, mesh = sys.argv[1], sys.argv[2]
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    LoadPlugin(plugin, ns=globals())
    reader = OpenDataFile(mesh)
    reader.UpdatePipeline()
    seconds = {label: [] for label, _, _, _ in STEPS}
    cpu = {label: [] for label, _, _, _ in STEPS}
    setup = {label: [] for label, _, _, _ in STEPS}
    for _ in range(repeats):
        sharpen = globals()["SurfaceShockSharpen"](Input=reader, FlowTime=2048.0)
        for label, kind, prop, value in STEPS:
            if prop:
                setattr(sharpen, prop, value)
            start, cpuStart = time.perf_counter(), time.process_time()
            sharpen.UpdatePipeline()
            seconds[label].append(time.perf_counter() - start)
            cpu[label].append(time.process_time() - cpuStart)
            sharpen.UpdatePropertyInformation()
            setup[label].append(sharpen.GetPropertyValue("LastSetupSeconds"))
        from paraview.simple import Delete
        Delete(sharpen)
    points = reader.GetDataInformation().GetNumberOfPoints()
    print("| step (%d points, %d rounds) | changes | wall s, median (range) | CPU s, median | LastSetupSeconds, median |"
          % (points, repeats))
    print("|---|---|---:|---:|---:|")
    for label, kind, _, _ in STEPS:
        values = seconds[label]
        print("| %s | %s | %.3f (%.3f-%.3f) | %.3f | %.3f |"
              % (label, kind, statistics.median(values), min(values), max(values),
                 statistics.median(cpu[label]), statistics.median(setup[label])))


if __name__ == "__main__":
    main()
