"""pvpython test of the ShockFilters plugin's Image Shock Advection proxy.

Usage: pvpython TestImageShockAdvectionPlugin.py PLUGIN_PATH
Loads the real plugin, runs the filter on ParaView sources with every
property set, checks arrays, ranges and counts, and checks that bad values
give errors (an empty output), not crashes.
"""
import math
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def fetch(proxy):
    return servermanager.Fetch(proxy)


def gradient_energy(image, name):
    """Mean squared x-difference of a point array (sharpness)."""
    array = image.GetPointData().GetArray(name)
    nx = image.GetDimensions()[0]
    total, count = 0.0, 0
    for i in range(array.GetNumberOfTuples() - 1):
        if (i + 1) % nx:
            d = array.GetComponent(i + 1, 0) - array.GetComponent(i, 0)
            total += d * d
            count += 1
    return total / count


LoadPlugin(sys.argv[1], ns=globals())

wavelet = Wavelet(WholeExtent=[0, 79, 0, 59, 0, 0])
source_range = wavelet.PointData["RTData"].GetRange()

# Defaults, then every property set to a non-default value.
shock = ImageShockAdvection(Input=wavelet)
shock.InputArray = ["POINTS", "RTData"]
shock.UpdatePipeline()
out = fetch(shock)
check(out.GetNumberOfPoints() == 80 * 60, "point count kept")
r = out.GetPointData().GetArray("RTData").GetRange()
check(source_range[0] - 1e-3 <= r[0] and r[1] <= source_range[1] + 1e-3, "range kept %s in %s" % (r, source_range))
check(gradient_energy(out, "RTData") > gradient_energy(fetch(wavelet), "RTData"), "sharper")

for flow_mode in ["Fixed", "Composed", "Naive"]:
    for sampling in ["Linear", "Nearest"]:
        for tracing in ["Face Crossing", "Stepped"]:
            shock.TimeStep = 300.0
            shock.SmoothingPasses = 2
            shock.FlowMode = flow_mode
            shock.NumberOfFlowUpdates = 3
            shock.Sampling = sampling
            shock.TracingMode = tracing
            shock.StepFraction = 0.2
            shock.GenerateFlowArrays = 1
            shock.NumberOfThreads = 1
            shock.UpdatePipeline()
            out = fetch(shock)
            label = "%s/%s/%s" % (flow_mode, sampling, tracing)
            values = out.GetPointData().GetArray("RTData")
            check(values is not None, label + ": array present")
            r = values.GetRange()
            check(source_range[0] - 1e-3 <= r[0] and r[1] <= source_range[1] + 1e-3, label + ": range")
            potential = out.GetPointData().GetArray("ShockPotential")
            flow = out.GetCellData().GetArray("ShockFlow")
            check(potential is not None and potential.GetNumberOfTuples() == out.GetNumberOfPoints(),
                  label + ": ShockPotential")
            check(flow is not None and flow.GetNumberOfComponents() == 3
                  and flow.GetNumberOfTuples() == out.GetNumberOfCells(), label + ": ShockFlow")
            check(all(math.isfinite(x) for x in potential.GetRange()), label + ": finite potential")

# Bad values: an error and an empty output, the session goes on.
shock.TimeStep = -5.0
shock.UpdatePipeline()
check(fetch(shock).GetNumberOfPoints() == 0, "negative time gives an empty output with an error")
shock.TimeStep = 10.0
shock.InputArray = ["POINTS", "NoSuchArray"]
shock.UpdatePipeline()
check(fetch(shock).GetNumberOfPoints() == 0, "missing array gives an empty output with an error")
shock.InputArray = ["POINTS", "RTData"]
shock.UpdatePipeline()
check(fetch(shock).GetNumberOfPoints() == 80 * 60, "recovers after errors")

# A 3D volume.
volume = ImageShockAdvection(Input=Wavelet(WholeExtent=[0, 23, 0, 19, 0, 15]), TimeStep=100.0)
volume.InputArray = ["POINTS", "RTData"]
volume.UpdatePipeline()
check(fetch(volume).GetNumberOfPoints() == 24 * 20 * 16, "volume point count")

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("all plugin checks passed")
