"""Re-Apply time in pvpython: change FlowTime alone and update again.

    pvpython Benchmarks/reapply.py --plugin PATH/ShockFilters.so --filter colours|sharpen
        --input MESH --time T --second-time T2 [--threads N]

Loads the plugin, opens MESH, applies Surface Shock Advection (colours: the
reader's colour array, the filter's default) or Surface Shock Sharpen with
FlowTime T, updates, sets FlowTime T2 (nothing else) and updates again.
Prints {"first": s, "second": s, "points": n} (wall seconds of each
UpdatePipeline) as one JSON line. Minimal version written for
Benchmarks/userbench.sh (rows reapply-colours, reapply-sharpen).
"""
import argparse
import json
import time

from paraview import simple

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", required=True)
parser.add_argument("--filter", choices=["colours", "sharpen"], required=True)
parser.add_argument("--input", required=True)
parser.add_argument("--time", type=float, required=True)
parser.add_argument("--second-time", type=float, required=True)
parser.add_argument("--threads", type=int, default=0)
arguments = parser.parse_args()

simple.LoadPlugin(arguments.plugin, remote=False)
reader = simple.OpenDataFile(arguments.input)
reader.UpdatePipeline()  # reading is not part of either Apply
if arguments.filter == "colours":
    shock = simple.SurfaceShockAdvection(Input=reader)
else:
    shock = simple.SurfaceShockSharpen(Input=reader)
shock.FlowTime = arguments.time
shock.NumberOfThreads = arguments.threads

start = time.perf_counter()
shock.UpdatePipeline()
first = time.perf_counter() - start

shock.FlowTime = arguments.second_time
start = time.perf_counter()
shock.UpdatePipeline()
second = time.perf_counter() - start

points = shock.GetDataInformation().GetNumberOfPoints()
print(json.dumps({"first": first, "second": second, "points": points}))
