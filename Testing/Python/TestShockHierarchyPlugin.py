"""pvpython test of the Hierarchy Levels property of Image Shock Advection
(coarse-to-fine tracing, docs/hierarchy.md) in the real plugin.

Usage: pvpython --force-offscreen-rendering TestShockHierarchyPlugin.py PLUGIN_PATH

Checks the property's label, domain (1-16) and default (1, the class default),
that 1 gives the default output exactly, that 2 levels change it and keep the
range, and that more levels than the image holds run (they are not built).
Prints one line per failure and ends with "N passed, M failed".
"""
import sys

import numpy as np

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.numpy_interface import dataset_adapter as dsa

LoadPlugin(sys.argv[1], ns=globals())

passed = failed = 0


def check(condition, what):
    global passed, failed
    if condition:
        passed += 1
    else:
        failed += 1
        print("FAILED: " + what)


def values(proxy):
    proxy.UpdatePipeline()
    data = dsa.WrapDataObject(servermanager.Fetch(proxy))
    return np.array(data.PointData["RTData"], dtype=float)


wavelet = Wavelet(WholeExtent=[-40, 40, -40, 40, 0, 0])
default = ImageShockAdvection(Input=wavelet, FlowTime=1e4, InputArray=["POINTS", "RTData"])
check(default.HierarchyLevels == 1, "HierarchyLevels defaults to 1")
prop = default.GetProperty("HierarchyLevels")
check(default.SMProxy.GetProperty("HierarchyLevels").GetXMLLabel() == "Hierarchy Levels",
      "the label is Hierarchy Levels")
domain = prop.SMProperty.GetDomain("range")
check(domain is not None and domain.GetMinimum(0) == 1 and domain.GetMaximum(0) == 16,
      "the domain is 1-16")
check(prop.SMProperty.GetDocumentation() is not None, "the property is documented")

inputs = values(wavelet)
reference = values(default)
one = ImageShockAdvection(Input=wavelet, FlowTime=1e4, InputArray=["POINTS", "RTData"],
                          HierarchyLevels=1)
check(np.array_equal(values(one), reference), "1 level gives the default output exactly")
two = ImageShockAdvection(Input=wavelet, FlowTime=1e4, InputArray=["POINTS", "RTData"],
                          HierarchyLevels=2)
out = values(two)
check(np.abs(out - reference).max() > 1e-3 * np.ptp(inputs), "2 levels change the output")
check(out.min() >= inputs.min() and out.max() <= inputs.max(), "2 levels keep the input range")
many = ImageShockAdvection(Input=wavelet, FlowTime=1e4, InputArray=["POINTS", "RTData"],
                          HierarchyLevels=16)
out = values(many)
check(np.all(np.isfinite(out)) and out.min() >= inputs.min() and out.max() <= inputs.max(),
      "16 levels (more than the image holds) run, finite and in range")

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
