"""Re-Apply time of Surface Shock Advection in pvpython: what a ParaView user
waits for after changing only the Flow Time and pressing Apply again.

Usage (one fresh process per measurement):
  pvpython Benchmarks/reapply_bench.py PLUGIN MESH.ply [--threads N] [--reps R]
PLUGIN: the built plugin (build/lib/paraview-5.11/plugins/ShockFilters/ShockFilters.so);
MESH: a PLY with vertex colours, e.g. the armadillo of
`meshbench colors --flows none --dump /tmp/arma` (/tmp/arma-input.ply).

Prints one JSON object: the first Apply (reading excluded: the reader is
updated first) and each re-Apply with a new Flow Time: wall time of
UpdatePipeline and the filter's own phase timers (Last Setup/Flow/Advection
Seconds), and the re-Applies' medians.
"""
import json
import statistics
import sys
import time

from paraview.simple import *  # noqa: F401,F403  (pvpython's API)

args = sys.argv[1:]
plugin, mesh = args[0], args[1]
threads = int(args[args.index("--threads") + 1]) if "--threads" in args else 0
reps = int(args[args.index("--reps") + 1]) if "--reps" in args else 5

LoadPlugin(plugin, ns=globals())
reader = OpenDataFile(mesh)
reader.UpdatePipeline()
arrays = reader.PointData.keys()
colours = "RGB" if "RGB" in arrays else arrays[0]

shock = SurfaceShockAdvection(Input=reader)
shock.InputArray = ["POINTS", colours]
shock.NumberOfThreads = threads
shock.FlowTime = 4096


def apply():
    start = time.perf_counter()
    shock.UpdatePipeline()
    wall = time.perf_counter() - start
    shock.UpdatePipelineInformation()
    phases = {k: shock.GetProperty("Last%sSeconds" % k.capitalize()).GetData()
              for k in ("setup", "flow", "advection")}
    return dict(wall=wall, **phases)


first = apply()
again = []
for k in range(reps):
    shock.FlowTime = 4096 - 256 * (k + 1)  # only the flow time changes
    again.append(apply())
print(json.dumps({
    "mesh": mesh, "threads": threads, "points": reader.GetDataInformation().GetNumberOfPoints(),
    "first": first, "reapply": again,
    "reapply_wall_median": statistics.median(r["wall"] for r in again),
    "reapply_setup_median": statistics.median(r["setup"] for r in again),
}))
