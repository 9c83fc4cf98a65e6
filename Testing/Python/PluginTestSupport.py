"""Helpers shared by the parts of the pvpython test of the ShockFilters plugin
(TestShockFiltersPlugin.py, which runs TestShockFiltersPluginPipelines.py and
TestShockFiltersPluginInputs.py in its session and namespace): check() and its
counts, the errors and warnings of vtkOutputWindow, numpy views of fetched data,
and the probe proxies' reads of the VTK classes' getters.
"""
import numpy as np

from paraview import servermanager
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkOutputWindow

passed = 0
failures = []


def check(condition, message):
    global passed
    if condition:
        passed += 1
    else:
        failures.append(message)
        print("FAIL:", message)
    return condition


class Messages:
    """Collects the errors and warnings that reach vtkOutputWindow."""

    def __init__(self):
        self.errors, self.warnings = [], []
        window = vtkOutputWindow.GetInstance()
        window.AddObserver("ErrorEvent", self._error)
        window.AddObserver("WarningEvent", self._warning)

    @calldata_type(VTK_STRING)
    def _error(self, caller, event, text):
        self.errors.append(text)

    @calldata_type(VTK_STRING)
    def _warning(self, caller, event, text):
        self.warnings.append(text)

    def clear(self):
        del self.errors[:]
        del self.warnings[:]

    def error_with(self, text):
        return any(text in e for e in self.errors)


def fetch(proxy):
    return servermanager.Fetch(proxy)


def point_array(data, name):
    return np.asarray(dsa.WrapDataObject(data).PointData[name])


def cell_array(data, name):
    return np.asarray(dsa.WrapDataObject(data).CellData[name])


def points(data):
    return np.asarray(dsa.WrapDataObject(data).Points)


def within(values, low, high, tol=1e-6):
    return values.min() >= low - tol and values.max() <= high + tol


pxm = servermanager.ProxyManager()


# The properties of a proxy that set a value of its VTK object: (key, what) for
# Set<what>(); the probe proxies of TestShockFiltersPlugin.py read them back.
def settable(proto):
    keys = []
    iterator = proto.NewPropertyIterator()
    iterator.Begin()
    while not iterator.IsAtEnd():
        prop = iterator.GetProperty()
        command = prop.GetCommand() or ""
        if not prop.GetInformationOnly() and command.startswith("Set") and command != "SetInputArrayToProcess" \
                and iterator.GetKey() != "Input":
            keys.append((iterator.GetKey(), command[3:]))
        iterator.Next()
    return keys


def probe(name, kind="Probe"):
    return servermanager._getPyProxy(pxm.SMProxyManager.NewProxy("shock_filters_probes", name + kind))


def class_value(proxy, key):
    proxy.SMProxy.UpdatePropertyInformation()
    return proxy.SMProxy.GetProperty("Class" + key).GetElement(0)
