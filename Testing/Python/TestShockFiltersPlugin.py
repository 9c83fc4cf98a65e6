"""pvpython test of the ShockFilters ParaView plugin: all three proxies.

Usage: pvpython --force-offscreen-rendering TestShockFiltersPlugin.py PLUGIN_PATH
           [SOURCE_XML [HELP_DIR]]

Loads the real plugin into the real pvpython and checks, for
"Image Shock Advection", "Surface Shock Advection" and "Surface Shock Sharpen":
- the proxy definitions: labels, classes, menu, every property documented,
  with a domain and a default equal to the VTK class default; panel order;
- every property set and applied on ParaView sources, output arrays, ranges
  and point counts (servermanager.Fetch + numpy);
- bad values: errors reported through vtkOutputWindow (captured here), an
  empty output, no crash, and the session goes on; out-of-range values are
  clamped by the classes;
- composite inputs (GroupDatasets, partitioned collections): block by block,
  identical to filtering each block alone; in mixed composites the matching
  blocks are filtered (each with its own array) and the others pass through;
- the read-only measurement properties;
- with SOURCE_XML (Plugin/ShockFilters.xml): one flat definition per filter,
  shared properties identical in each, range domains equal to the class
  clamps;
- with HELP_DIR (the plugin's paraview_help build folder): each filter's help
  page lists every property, enumeration defaults by name, no repository
  paths.
Prints one line per failure and ends with "N passed, M failed".
"""
import math
import sys

import numpy as np

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.modules import vtkRemotingServerManager as smcore
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkOutputWindow

PLUGIN = sys.argv[1]
SOURCE_XML = sys.argv[2] if len(sys.argv) > 2 else None
HELP_DIR = sys.argv[3] if len(sys.argv) > 3 else None
LABELS = {
    "ImageShockAdvection": ("Image Shock Advection", "vtkImageShockAdvectionFilter"),
    "SurfaceShockAdvection": ("Surface Shock Advection", "vtkPolyDataShockAdvectionFilter"),
    "SurfaceShockSharpen": ("Surface Shock Sharpen", "vtkPolyDataShockSharpenFilter"),
}

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


messages = Messages()
LoadPlugin(PLUGIN, ns=globals())

# ---------------------------------------------------------------------------
# 1. Proxy definitions.
pxm = servermanager.ProxyManager()
for name, (label, cls) in LABELS.items():
    proto = pxm.GetPrototypeProxy("filters", name)
    if not check(proto is not None, name + ": proxy in the filters group"):
        continue
    check(proto.GetXMLLabel() == label, name + ": label " + str(proto.GetXMLLabel()))
    check(proto.GetVTKClassName() == cls, name + ": class " + str(proto.GetVTKClassName()))
    check(label.replace(" ", "") in globals(), name + ": pvpython function " + label.replace(" ", ""))
    hints = proto.GetHints()
    menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
    check(menu is not None and menu.GetAttribute("category") == "Shock Filters",
          name + ": ShowInMenu category Shock Filters")
for abstract in ["ShockFilterBase", "ShockAdvectionBase"]:
    check(pxm.GetPrototypeProxy("filters", abstract) is None, abstract + " is not a filter")
    check(abstract not in globals(), abstract + " is not a pvpython function")

EXPECTED_NAMES = {
    "ImageShockAdvection": {
        "Input", "InputArray", "FlowTime", "SmoothingPasses", "FlowMode", "NumberOfFlowUpdates",
        "TracingMode", "StepFraction", "Sampling", "GenerateFlowArrays", "NumberOfThreads",
        "LastSetupSeconds", "LastFlowSeconds", "LastAdvectionSeconds", "LastTraceSteps",
        "GhostLevels"},
}
EXPECTED_NAMES["SurfaceShockAdvection"] = set(EXPECTED_NAMES["ImageShockAdvection"])
EXPECTED_NAMES["SurfaceShockSharpen"] = (EXPECTED_NAMES["ImageShockAdvection"] - {"InputArray"}) | {
    "FeatureAngle", "FitTarget", "LastRepeatedTriangles", "LastDegenerateTriangles", "LastFeatureEdges",
    "NormalSmoothingPasses", "ScreeningWeight", "Solver", "SolverIterations", "SolverTolerance",
    "MergeCoincidentPoints", "GenerateSharpenedNormals", "LastFitSetupSeconds",
    "LastFitSolveSeconds", "LastSolverIterations", "LastSolverResidual", "LastFlippedTriangles",
    "LastMaxDisplacement"}
# The image filter alone offers the PDE baseline.
EXPECTED_NAMES["ImageShockAdvection"] = EXPECTED_NAMES["ImageShockAdvection"] | {
    "Method", "Domain", "GradientScreening", "HierarchyLevels", "CourantNumber", "MaximumIterations",
    "LastIterations", "LastReachedTime"}

# The panel order, computed as pqProxyWidget::createPropertyWidgets does it:
# XML order, properties of groups with the same label placed together.
EXPECTED_PANEL = {
    "ImageShockAdvection": ["Input", "Flow", "Tracing", "Output", "Performance", "Parallel",
                            "Measurements"],
    "SurfaceShockAdvection": ["Input", "Flow", "Tracing", "Output", "Performance", "Parallel",
                              "Measurements"],
    "SurfaceShockSharpen": ["Input", "Flow", "Tracing", "Fitting", "Output", "Performance", "Parallel",
                            "Measurements"],
}


def panel_order(proxy):
    """Group labels and property keys in panel order (the algorithm of
    pqProxyWidget::createPropertyWidgets: XML order, except that properties of
    groups with the same label follow the first property of that label)."""
    smproxy = proxy.SMProxy
    group_of = {}
    for g in range(smproxy.GetNumberOfPropertyGroups()):
        group = smproxy.GetPropertyGroup(g)
        for p in range(group.GetNumberOfProperties()):
            group_of[group.GetProperty(p).GetXMLName()] = group.GetXMLLabel()
    iterator = smcore.vtkSMOrderedPropertyIterator()
    iterator.SetProxy(smproxy)
    iterator.Begin()
    ordered, group_end = [], {}
    while not iterator.IsAtEnd():
        key = iterator.GetKey()
        label = group_of.get(key)
        check(label is not None, "%s: property %s is in a group" % (proxy.GetXMLName(), key))
        position = group_end[label] + 1 if label in group_end else len(ordered)
        ordered.insert(position, (key, label))
        for other in group_end:
            if group_end[other] >= position:
                group_end[other] += 1
        group_end[label] = position
        iterator.Next()
    order = []
    for key, label in ordered:
        if label not in order:
            order.append(label)
    return order, [key for key, label in ordered]


# The VTK classes have no Python wrapping in pvpython, so their getters are read
# through probe proxies with one information-only property "Class<X>" per
# property <X>, calling Get<X>() on the VTK object: "<name>Defaults" has only
# those (nothing is pushed to its VTK object, so it shows the class defaults);
# "<name>Probe" inherits the real proxy as well (to set values and read back).
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


probe_xml = ["<ServerManagerConfiguration><ProxyGroup name=\"shock_filters_probes\">"]
for name in LABELS:
    getters = "".join('<DoubleVectorProperty name="Class%s" command="Get%s" information_only="1">'
                      "<SimpleDoubleInformationHelper/></DoubleVectorProperty>" % (key, what)
                      for key, what in settable(pxm.GetPrototypeProxy("filters", name)))
    probe_xml.append('<SourceProxy name="%sDefaults" class="%s">%s</SourceProxy>'
                     % (name, LABELS[name][1], getters))
    probe_xml.append('<SourceProxy name="%sProbe" class="%s" base_proxygroup="filters" base_proxyname="%s">'
                     "%s</SourceProxy>" % (name, LABELS[name][1], name, getters))
probe_xml.append("</ProxyGroup></ServerManagerConfiguration>")
check(pxm.SMProxyManager.GetProxyDefinitionManager().LoadConfigurationXMLFromString("".join(probe_xml)),
      "probe proxies loaded")


def probe(name, kind="Probe"):
    return servermanager._getPyProxy(pxm.SMProxyManager.NewProxy("shock_filters_probes", name + kind))


def class_value(proxy, key):
    proxy.SMProxy.UpdatePropertyInformation()
    return proxy.SMProxy.GetProperty("Class" + key).GetElement(0)


for name in LABELS:
    wrapped = servermanager._getPyProxy(pxm.SMProxyManager.NewProxy("filters", name))
    names = set(wrapped.ListProperties())
    check(names == EXPECTED_NAMES[name], "%s: pvpython names %s" % (name, sorted(names)))
    order, keys = panel_order(wrapped)
    check(order == EXPECTED_PANEL[name], "%s: panel groups %s" % (name, order))
    if name != "SurfaceShockSharpen":
        check(keys[:3] == ["Input", "SelectInputArray", "FlowTime"], name + ": Input Array first, %s" % keys[:3])
    for key in keys:
        prop = wrapped.GetProperty(key)
        doc = prop.GetDocumentation()
        check(doc is not None and len(doc.GetDescription().split()) >= 8,
              "%s.%s: documented" % (name, key))
        if prop.GetInformationOnly():
            check(prop.GetPanelVisibility() == "advanced", "%s.%s: information in advanced" % (name, key))
            continue
        domains = prop.NewDomainIterator()
        domains.Begin()
        check(not domains.IsAtEnd(), "%s.%s: has a domain" % (name, key))
    # Defaults: the XML default values (a new proxy holds them) against a VTK
    # object that received no value.
    defaults = probe(name, "Defaults")
    defaults.SMProxy.UpdateVTKObjects()
    for key, what in settable(wrapped.SMProxy):
        default = wrapped.SMProxy.GetProperty(key).GetElement(0)
        actual = class_value(defaults, key)
        check(abs(float(default) - float(actual)) <= 1e-12 * max(1.0, abs(float(actual))),
              "%s.%s: XML default %s == class default %s" % (name, key, default, actual))


# The XML as written: shared properties agree across the filters, and every
# range domain is the class's clamp (set below and above, read back).
if SOURCE_XML:
    import xml.etree.ElementTree as ET
    definitions = {proxy.get("name"): {prop.get("name"): prop for prop in proxy
                                       if prop.tag.endswith("Property") and prop.tag != "InputProperty"}
                   for proxy in ET.parse(SOURCE_XML).getroot().iter("SourceProxy")}
    check(set(definitions) == set(LABELS), "source XML: one flat definition per filter, %s" % sorted(definitions))
    # Deliberately different texts (what is sharpened, what is measured).
    OWN_TEXT = {"FlowTime", "Sampling", "GenerateFlowArrays", "LastSetupSeconds", "LastFlowSeconds",
                "LastAdvectionSeconds", "LastTraceSteps", "GhostLevels"}

    def shape(prop, with_text):
        rows = [(prop.tag, tuple(sorted(prop.attrib.items())))]
        for child in prop.iter():
            if child is not prop and (with_text or child.tag != "Documentation"):
                rows.append((child.tag, tuple(sorted(child.attrib.items())), " ".join((child.text or "").split())))
        return rows

    for key in sorted(set().union(*[set(d) for d in definitions.values()])):
        copies = [(name, d[key]) for name, d in definitions.items() if key in d]
        for name, prop in copies[1:]:
            check(shape(prop, key not in OWN_TEXT) == shape(copies[0][1], key not in OWN_TEXT),
                  "%s.%s is the same as in %s" % (name, key, copies[0][0]))
    for name, props in definitions.items():
        clamp_probe = probe(name)
        for key, prop in props.items():
            rng = prop.find("IntRangeDomain")
            rng = rng if rng is not None else prop.find("DoubleRangeDomain")
            # FlowTime is validated, not clamped: a negative time is an error.
            if rng is None or key == "FlowTime" or key not in dict(settable(clamp_probe.SMProxy)):
                continue
            check(rng.get("max") is not None, "%s.%s: the domain has a max (the class clamps)" % (name, key))
            for bound, outside in (("min", -1e12), ("max", 1e12)):
                if rng.get(bound) is None:
                    continue
                value = int(outside) if prop.tag == "IntVectorProperty" else outside
                if prop.tag == "IntVectorProperty":
                    value = max(-2 ** 31, min(2 ** 31 - 1, value))
                clamp_probe.SMProxy.GetProperty(key).SetElement(0, value)
                clamp_probe.SMProxy.UpdateVTKObjects()
                got = class_value(clamp_probe, key)
                check(got == float(rng.get(bound)), "%s.%s: XML %s %s == class clamp %s"
                      % (name, key, bound, rng.get(bound), got))

if HELP_DIR:
    import html
    import os
    import re
    for name in LABELS:
        page = os.path.join(HELP_DIR, "filters.%s.html" % name)
        if check(os.path.isfile(page), "help page " + page):
            with open(page) as handle:
                text = html.unescape(re.sub(r"<[^>]+>", " ", handle.read()))
            proxy = servermanager._getPyProxy(pxm.SMProxyManager.NewProxy("filters", name))
            flat = " ".join(text.split())
            stale = []
            for key in panel_order(proxy)[1]:
                label = proxy.SMProxy.GetProperty(key).GetXMLLabel()
                check(label in text, "%s help lists %s" % (name, label))
                doc = proxy.SMProxy.GetProperty(key).GetDocumentation()
                if doc is not None and " ".join(doc.GetDescription().split())[:60] not in flat:
                    stale.append(key)
            # ParaView 5.11 does not rebuild the help pages when the XML changes.
            check(not stale, "%s help pages older than the XML (%s): rm %s/* and build again"
                  % (name, ", ".join(stale), HELP_DIR))
            check("docs/" not in text and ".md" not in text, "%s help names no repository file" % name)
            if name == "ImageShockAdvection":
                check("Default: 'Fixed'" in text and "Default: 'Face Crossing'" in text,
                      "image help: enumeration defaults by name")
                check("An array of scalars is required" not in text, "image help: no scalars-only restriction")


# ---------------------------------------------------------------------------
# 2. Image Shock Advection on Wavelet.


def x_energy(image, values):
    nx = image.GetDimensions()[0]
    grid = values.reshape(-1, nx)
    return float(np.mean(np.diff(grid, axis=1) ** 2))


# The filter is created before its input has run, as a newcomer writes it.
wavelet = Wavelet(WholeExtent=[0, 79, 0, 59, 0, 0])
image = ImageShockAdvection(Input=wavelet)
check(list(image.InputArray) == ["POINTS", "RTData"], "image: default input array RTData, got %s" % image.InputArray)
source = fetch(wavelet)
rt = point_array(source, "RTData")
lo, hi = float(rt.min()), float(rt.max())
image.UpdatePipeline()
out = fetch(image)
values = point_array(out, "RTData")
check(out.GetNumberOfPoints() == 80 * 60, "image: point count kept")
check(within(values, lo, hi, 1e-3), "image: range kept")
check(x_energy(out, values) > x_energy(source, rt), "image: sharper")
check(out.GetPointData().GetArray("ShockPotential") is None, "image: no flow arrays by default")
image.UpdatePropertyInformation()
check(image.LastFlowSeconds >= 0 and image.LastAdvectionSeconds >= 0, "image: measurement seconds")
check(image.LastTraceSteps > 0, "image: LastTraceSteps %s" % image.LastTraceSteps)
check(image.LastSetupSeconds == 0.0, "image: no setup for images")

image.FlowTime = 0.0
image.UpdatePipeline()
check(np.array_equal(point_array(fetch(image), "RTData"), rt), "image: time 0 returns the input")

for flow_mode in ["Fixed", "Composed", "Naive"]:
    for sampling in ["Linear", "Nearest"]:
        for tracing in ["Face Crossing", "Stepped"]:
            image.FlowTime = 300.0
            image.SmoothingPasses = 2
            image.FlowMode = flow_mode
            image.NumberOfFlowUpdates = 3
            image.Sampling = sampling
            image.TracingMode = tracing
            image.StepFraction = 0.2
            image.GenerateFlowArrays = 1
            image.NumberOfThreads = 1
            image.UpdatePipeline()
            out = fetch(image)
            label = "image %s/%s/%s" % (flow_mode, sampling, tracing)
            values = point_array(out, "RTData")
            check(within(values, lo, hi, 1e-3), label + ": range")
            potential = point_array(out, "ShockPotential")
            flow = cell_array(out, "ShockFlow")
            check(potential.shape == (out.GetNumberOfPoints(),), label + ": ShockPotential")
            check(flow.shape == (out.GetNumberOfCells(), 3), label + ": ShockFlow")
            check(np.isfinite(potential).all() and potential.min() >= 0, label + ": potential finite >= 0")

# A blurred oblique step: the blurred band shrinks.
step = Calculator(Input=wavelet, ResultArrayName="Step", Function="tanh((coordsX - 0.75*coordsY) / 2.5)")
step_shock = ImageShockAdvection(Input=step, FlowTime=1024.0)
step_shock.InputArray = ["POINTS", "Step"]
step_shock.UpdatePipeline()
s_in = point_array(fetch(step), "Step")
s_out = point_array(fetch(step_shock), "Step")
band = lambda v: float(np.mean(np.abs(v) < 0.8))  # noqa: E731
check(within(s_out, s_in.min(), s_in.max()), "image step: range kept")
check(band(s_out) < 0.5 * band(s_in), "image step: band %.3f -> %.3f" % (band(s_in), band(s_out)))

# Threads do not change the result.
image.FlowMode = "Fixed"
image.Sampling = "Linear"
image.TracingMode = "Face Crossing"
image.NumberOfThreads = 1
image.UpdatePipeline()
one_thread = point_array(fetch(image), "RTData")
image.NumberOfThreads = 2
image.UpdatePipeline()
check(np.array_equal(one_thread, point_array(fetch(image), "RTData")), "image: same result on 1 and 2 threads")

# Method PDE: the Osher-Rudin baseline, with the same parameters.
check(image.Method == "Advection", "image: Advection is the default method")
pde = ImageShockAdvection(Input=step, FlowTime=1024.0, Method="PDE")
pde.InputArray = ["POINTS", "Step"]
pde.UpdatePipeline()
pde.UpdatePropertyInformation()
p_out = point_array(fetch(pde), "Step")
check(within(p_out, s_in.min(), s_in.max(), 1e-9), "image pde: range kept")
check(band(p_out) < 0.5 * band(s_in), "image pde: band %.3f -> %.3f" % (band(s_in), band(p_out)))
check(float(np.mean(np.abs(p_out - s_out))) < 0.05 * float(s_in.max() - s_in.min()),
      "image pde: close to the advection, mean difference %.4f" % float(np.mean(np.abs(p_out - s_out))))
check(pde.LastIterations > 1 and pde.LastReachedTime == 1024.0 and pde.LastTraceSteps == 0,
      "image pde: measurements %s %s" % (pde.LastIterations, pde.LastReachedTime))
pde.MaximumIterations = 2
pde.CourantNumber = 0.25
pde.UpdatePipeline()
pde.UpdatePropertyInformation()
check(pde.LastIterations == 2 and 0.0 < pde.LastReachedTime < 1024.0,
      "image pde: stops at MaximumIterations, reached %s" % pde.LastReachedTime)
Delete(pde)

# Domain Gradients (beyond the paper): the differences carried along the same
# flow and integrated back; an edge sharpens, the values stay near the input's.
check(image.Domain == "Values", "image: Values is the default domain")
gradients = ImageShockAdvection(Input=step, FlowTime=1024.0, Domain="Gradients")
gradients.InputArray = ["POINTS", "Step"]
g_out = point_array(fetch(gradients), "Step")
check(band(g_out) < 0.75 * band(s_in), "image gradients: band %.3f -> %.3f" % (band(s_in), band(g_out)))
check(not np.array_equal(g_out, s_out), "image gradients: not the value advection's result")
span = float(s_in.max() - s_in.min())
check(within(g_out, s_in.min(), s_in.max(), 0.1 * span), "image gradients: within 10 %% of the input's range")
gradients.GradientScreening = 1e6  # the input's structure everywhere: back to the input
g_close = point_array(fetch(gradients), "Step")
check(float(np.max(np.abs(g_close - s_in))) < 1e-3 * span,
      "image gradients: a huge screening keeps the input, max change %.2g" % float(np.max(np.abs(g_close - s_in))))
Delete(gradients)

# Cell data on the grid of cell centres.
cells = PointDatatoCellData(Input=wavelet)
cell_shock = ImageShockAdvection(Input=cells, FlowTime=200.0, GenerateFlowArrays=1)
cell_shock.InputArray = ["CELLS", "RTData"]
cell_shock.UpdatePipeline()
out = fetch(cell_shock)
cin = cell_array(fetch(cells), "RTData")
cout = cell_array(out, "RTData")
check(cout.shape == cin.shape and not np.array_equal(cout, cin), "image cells: filtered")
check(within(cout, cin.min(), cin.max(), 1e-3), "image cells: range kept")
check(out.GetCellData().GetArray("ShockPotential") is not None, "image cells: ShockPotential on cells")

# A 3D volume.
volume = ImageShockAdvection(Input=Wavelet(WholeExtent=[0, 23, 0, 19, 0, 15]), FlowTime=100.0)
volume.InputArray = ["POINTS", "RTData"]
volume.UpdatePipeline()
check(fetch(volume).GetNumberOfPoints() == 24 * 20 * 16, "volume: point count")

# ---------------------------------------------------------------------------
# 3. Surface Shock Advection: a blurred colour pattern on a fine sphere.
sphere = Sphere(ThetaResolution=96, PhiResolution=48)
colour = Calculator(Input=sphere, ResultArrayName="Colour",
                    Function="(0.5+0.5*tanh(30*coordsX))*iHat + (0.5+0.5*tanh(30*coordsY))*jHat"
                             " + (0.5+0.5*tanh(30*coordsZ))*kHat")
surface = SurfaceShockAdvection(Input=colour)  # before its input has run
check(list(surface.InputArray) == ["POINTS", "Colour"], "surface: default input array, got %s" % surface.InputArray)
mesh_in = fetch(colour)
c_in = point_array(mesh_in, "Colour")


def blurred(values):
    """Fraction of values far from both ends of [0, 1] (the blurred band)."""
    return float(np.mean(np.abs(values - 0.5) < 0.35))


surface.FlowTime = 2048.0
surface.UpdatePipeline()
out = fetch(surface)
c_out = point_array(out, "Colour")
check(out.GetNumberOfPoints() == mesh_in.GetNumberOfPoints(), "surface: point count kept")
check(out.GetNumberOfCells() == mesh_in.GetNumberOfCells(), "surface: cell count kept")
check(np.array_equal(points(out), points(mesh_in)), "surface: geometry untouched")
check(c_out.shape == c_in.shape, "surface: 3 components kept")
check(within(c_out, c_in.min(), c_in.max()), "surface: range kept")
check(blurred(c_out) < 0.6 * blurred(c_in), "surface: sharper (%.3f -> %.3f)" % (blurred(c_in), blurred(c_out)))
check(np.array_equal(point_array(out, "Normals"), point_array(mesh_in, "Normals")),
      "surface: other arrays pass through")
surface.UpdatePropertyInformation()
check(surface.LastSetupSeconds > 0 and surface.LastTraceSteps > 0, "surface: measurements")

for flow_mode in ["Fixed", "Composed", "Naive"]:
    for sampling in ["Linear", "Nearest"]:
        for tracing in ["Face Crossing", "Stepped"]:
            surface.FlowTime = 512.0
            surface.SmoothingPasses = 2
            surface.FlowMode = flow_mode
            surface.NumberOfFlowUpdates = 2
            surface.Sampling = sampling
            surface.TracingMode = tracing
            surface.StepFraction = 0.25
            surface.GenerateFlowArrays = 1
            surface.NumberOfThreads = 2
            surface.UpdatePipeline()
            out = fetch(surface)
            label = "surface %s/%s/%s" % (flow_mode, sampling, tracing)
            c_out = point_array(out, "Colour")
            check(within(c_out, c_in.min(), c_in.max()), label + ": range")
            check(point_array(out, "ShockPotential").shape == (out.GetNumberOfPoints(),),
                  label + ": ShockPotential")
            check(cell_array(out, "ShockFlow").shape == (out.GetNumberOfCells(), 3), label + ": ShockFlow")

# Cell data (triangles) and a scalar point array.
elevation = Elevation(Input=sphere, LowPoint=[0, 0, -0.5], HighPoint=[0, 0, 0.5])
to_cells = PointDatatoCellData(Input=elevation)
surface_cells = SurfaceShockAdvection(Input=to_cells, FlowTime=256.0, Sampling="Nearest")
surface_cells.InputArray = ["CELLS", "Elevation"]
surface_cells.UpdatePipeline()
e_in = cell_array(fetch(to_cells), "Elevation")
e_out = cell_array(fetch(surface_cells), "Elevation")
check(e_out.shape == e_in.shape and within(e_out, e_in.min(), e_in.max()), "surface cells: range and count")
check(np.isin(e_out, e_in).all(), "surface cells: nearest reads triangle values")

# ---------------------------------------------------------------------------
# 4. Surface Shock Sharpen: a box with rounded edges and corners.
box = Box()
welded = Clean(Input=box)
triangles = Triangulate(Input=welded)
fine = Subdivide(Input=triangles, NumberofSubdivisions=4)
rounded = Smooth(Input=fine, NumberofIterations=40)
rounded.UpdatePipeline()
box_in = fetch(rounded)


def axis_aligned(proxy):
    """Fraction of triangles whose normal is within 5 degrees of an axis."""
    normals = GenerateSurfaceNormals(Input=proxy, ComputeCellNormals=1, Splitting=0)
    n = cell_array(fetch(normals), "Normals")
    Delete(normals)
    return float(np.mean(np.abs(n).max(axis=1) > math.cos(math.radians(5))))


# Smooth leaves the creases' own edges sharper than 60 degrees (it bends the faces
# next to them): the default Feature Angle would keep them, the paper's 180 flattens
# the faces (docs/sharpening.md).
sharpen = SurfaceShockSharpen(Input=rounded, FeatureAngle=180)
sharpen.UpdatePipeline()
out = fetch(sharpen)
check(out.GetNumberOfPoints() == box_in.GetNumberOfPoints(), "sharpen: point count kept")
check(out.GetNumberOfCells() == box_in.GetNumberOfCells(), "sharpen: cell count kept")
check(axis_aligned(sharpen) > axis_aligned(rounded) + 0.1,
      "sharpen: faces flatter (%.3f -> %.3f)" % (axis_aligned(rounded), axis_aligned(sharpen)))
for field in ["ShockSolverIterations", "ShockSolverResidual", "ShockFlippedTriangles", "ShockMaxDisplacement"]:
    check(out.GetFieldData().GetArray(field) is not None, "sharpen: field data " + field)
sharpen.UpdatePropertyInformation()
check(sharpen.LastSolverIterations == 25, "sharpen: 25 CG iterations, got %s" % sharpen.LastSolverIterations)
check(sharpen.LastFlippedTriangles == 0, "sharpen: no flipped triangles")
check(0 < sharpen.LastMaxDisplacement < 0.2, "sharpen: small displacement %s" % sharpen.LastMaxDisplacement)
check(sharpen.LastFitSolveSeconds >= 0 and sharpen.LastTraceSteps > 0, "sharpen: measurements")
check(abs(out.GetFieldData().GetArray("ShockMaxDisplacement").GetValue(0) - sharpen.LastMaxDisplacement) < 1e-12,
      "sharpen: field data and measurement agree")

for solver in ["Conjugate Gradient", "Conjugate Gradient Tolerance", "Exact"]:
    for sampling in ["Linear", "Nearest"]:
        sharpen.FlowTime = 128.0
        sharpen.SmoothingPasses = 2
        sharpen.FlowMode = "Composed"
        sharpen.NumberOfFlowUpdates = 2
        sharpen.TracingMode = "Stepped"
        sharpen.StepFraction = 0.2
        sharpen.Sampling = sampling
        sharpen.NormalSmoothingPasses = 2
        sharpen.ScreeningWeight = 2.0
        sharpen.Solver = solver
        sharpen.SolverIterations = 60
        sharpen.SolverTolerance = 1e-5
        sharpen.MergeCoincidentPoints = 1
        sharpen.GenerateFlowArrays = 1
        sharpen.GenerateSharpenedNormals = 1
        sharpen.NumberOfThreads = 2
        sharpen.UpdatePipeline()
        out = fetch(sharpen)
        label = "sharpen %s/%s" % (solver, sampling)
        p = points(out)
        check(p.shape == points(box_in).shape and np.isfinite(p).all(), label + ": points")
        normals = cell_array(out, "ShockNormals")
        check(normals.shape == (out.GetNumberOfCells(), 3)
              and np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-4), label + ": unit ShockNormals")
        check(point_array(out, "ShockPotential").shape == (out.GetNumberOfPoints(),), label + ": ShockPotential")
        check(cell_array(out, "ShockFlow").shape == (out.GetNumberOfCells(), 3), label + ": ShockFlow")
        sharpen.UpdatePropertyInformation()
        if solver == "Conjugate Gradient":
            check(sharpen.LastSolverIterations == 60, label + ": iterations %s" % sharpen.LastSolverIterations)
        elif solver == "Conjugate Gradient Tolerance":
            check(sharpen.LastSolverResidual <= 1e-5 or sharpen.LastSolverIterations == 60,
                  label + ": tolerance reached")
        check(sharpen.LastFlippedTriangles == 0, label + ": no flipped triangles")

# Time 0, Nearest sampling, Exact solver: the input comes back (class documentation).
identity = SurfaceShockSharpen(Input=rounded, FlowTime=0.0, Sampling="Nearest", Solver="Exact")
identity.UpdatePipeline()
check(np.allclose(points(fetch(identity)), points(box_in), atol=1e-6), "sharpen: time 0 + nearest + exact = input")

# The Box source has duplicate points on its seams: merged by default.
seams = SurfaceShockSharpen(Input=Subdivide(Input=Triangulate(Input=box), NumberofSubdivisions=3), FlowTime=64.0)
seams.UpdatePipeline()
seams_out = fetch(seams)
check(seams_out.GetNumberOfPoints() == 6 * 81 and np.isfinite(points(seams_out)).all(), "sharpen: seams kept")
seams.MergeCoincidentPoints = 0
seams.UpdatePipeline()
check(np.isfinite(points(fetch(seams))).all(), "sharpen: unmerged seams")

# ---------------------------------------------------------------------------
# 5. Bad values: an error through vtkOutputWindow and an empty output, no crash.


def expect_error(proxy, text, label):
    messages.clear()
    proxy.UpdatePipeline()
    data = fetch(proxy)
    check(messages.error_with(text), "%s: error containing %r, got %s" % (label, text, messages.errors[:1]))
    check(data.GetNumberOfPoints() == 0, label + ": empty output")


image.FlowTime = -5.0
expect_error(image, "FlowTime must be a finite number >= 0", "image negative time")
image.FlowTime = float("nan")
expect_error(image, "FlowTime must be a finite number >= 0", "image NaN time")
image.FlowTime = float("inf")
expect_error(image, "FlowTime must be a finite number >= 0", "image infinite time")
image.FlowTime = 10.0
image.InputArray = ["POINTS", "NoSuchArray"]
expect_error(image, "NoSuchArray", "image missing array")
image.InputArray = ["POINTS", "RTData"]
messages.clear()
image.UpdatePipeline()
check(fetch(image).GetNumberOfPoints() == 80 * 60 and not messages.errors, "image: recovers after errors")

surface.FlowTime = -1.0
expect_error(surface, "FlowTime must be a finite number >= 0", "surface negative time")
surface.FlowTime = 16.0
surface.InputArray = ["CELLS", "NoSuchArray"]
expect_error(surface, "NoSuchArray", "surface missing array")
sharpen.FlowTime = -2.0
expect_error(sharpen, "FlowTime must be a finite number >= 0", "sharpen negative time")
sharpen.FlowTime = 16.0
messages.clear()
sharpen.UpdatePipeline()
check(fetch(sharpen).GetNumberOfPoints() > 0 and not messages.errors, "sharpen: recovers after errors")

# Cell data on quads must be triangulated first.
quads = PointDatatoCellData(Input=Elevation(Input=Plane(XResolution=8, YResolution=8)))
quad_shock = SurfaceShockAdvection(Input=quads)
quad_shock.InputArray = ["CELLS", "Elevation"]
expect_error(quad_shock, "Triangulate the mesh first", "surface cell data on quads")
# Point data on quads is fine (triangulated internally, cells kept).
quad_points = SurfaceShockAdvection(Input=Elevation(Input=Plane(XResolution=8, YResolution=8)), FlowTime=32.0)
quad_points.InputArray = ["POINTS", "Elevation"]
quad_points.UpdatePipeline()
check(fetch(quad_points).GetNumberOfCells() == 64, "surface point data on quads: cells kept")

# A mesh without polygons passes through with a warning.
messages.clear()
lines = SurfaceShockSharpen(Input=Line(Resolution=10))
lines.UpdatePipeline()
check(fetch(lines).GetNumberOfPoints() == 11 and not messages.errors and messages.warnings,
      "sharpen: lines pass through with a warning")


# Out-of-range values are clamped by the classes (raw values bypass the
# enumeration names); read back through the probes.
image_probe, sharpen_probe = probe("ImageShockAdvection"), probe("SurfaceShockSharpen")
clamps = [
    (image_probe, "SmoothingPasses", -3, 0),
    (image_probe, "StepFraction", 5.0, 1.0),
    (image_probe, "StepFraction", 0.0, 0.001),
    (image_probe, "NumberOfFlowUpdates", 0, 1),
    (image_probe, "NumberOfThreads", -4, 0),
    (image_probe, "FlowMode", 7, 2),
    (image_probe, "Sampling", -1, 0),
    (image_probe, "TracingMode", 9, 1),
    (image_probe, "GhostLevels", -1, 0),
    (sharpen_probe, "ScreeningWeight", 0.0, 1e-6),
    (sharpen_probe, "SolverTolerance", 2.0, 1.0),
    (sharpen_probe, "SolverTolerance", -1.0, 0.0),
    (sharpen_probe, "SolverIterations", -5, 0),
    (sharpen_probe, "Solver", 3, 2),
]
for proxy, key, value, expected in clamps:
    proxy.SMProxy.GetProperty(key).SetElement(0, value)
    proxy.SMProxy.UpdateVTKObjects()
    got = class_value(proxy, key)
    check(got == expected, "clamp %s=%s -> %s, got %s" % (key, value, expected, got))
# The plugin proxy runs after clamped values.
for key, value in [("SmoothingPasses", -3), ("StepFraction", 5.0), ("NumberOfFlowUpdates", 0),
                   ("NumberOfThreads", -4), ("FlowMode", 7), ("Sampling", -1), ("TracingMode", 9)]:
    image.SMProxy.GetProperty(key).SetElement(0, value)
messages.clear()
image.UpdatePipeline()
check(fetch(image).GetNumberOfPoints() == 80 * 60 and not messages.errors, "image: runs with clamped values")
image.SmoothingPasses = 1
image.StepFraction = 0.1
image.NumberOfFlowUpdates = 8
image.NumberOfThreads = 0
image.FlowMode = "Fixed"
image.Sampling = "Linear"
image.TracingMode = "Face Crossing"

# ---------------------------------------------------------------------------
# 6. Composite inputs.


def blocks(data):
    iterator = data.NewIterator()
    iterator.UnRegister(None)
    iterator.InitTraversal()
    result = []
    while not iterator.IsDoneWithTraversal():
        result.append(iterator.GetCurrentDataObject())
        iterator.GoToNextItem()
    return result


def in_input_domain(proxy, source):
    source.UpdatePipeline()  # the domain reads the source's data information
    domain = proxy.GetProperty("Input").FindDomain("vtkSMDataTypeDomain")
    return bool(domain.IsInDomain(source.SMProxy, 0))


# Images: each block filtered as if alone (own data range).
small = Wavelet(WholeExtent=[0, 39, 0, 29, 0, 0], Maximum=100.0)
group_images = GroupDatasets(Input=[wavelet, small])
composite_image = ImageShockAdvection(Input=group_images, FlowTime=200.0)
composite_image.InputArray = ["POINTS", "RTData"]
check(in_input_domain(composite_image, group_images), "composite images: accepted by the input domain")
messages.clear()
composite_image.UpdatePipeline()
parts = blocks(fetch(composite_image))
check(fetch(composite_image).IsA("vtkMultiBlockDataSet") and len(parts) == 2, "composite images: 2 blocks")
for part, alone_source in zip(parts, [wavelet, small]):
    alone = ImageShockAdvection(Input=alone_source, FlowTime=200.0)
    alone.InputArray = ["POINTS", "RTData"]
    alone.UpdatePipeline()
    check(np.array_equal(point_array(part, "RTData"), point_array(fetch(alone), "RTData")),
          "composite images: block %d == block alone" % parts.index(part))
check(not messages.errors, "composite images: no error")

# Surfaces: GroupDatasets of two Spheres with colours.
sphere2 = Sphere(Center=[2, 0, 0], Radius=0.7, ThetaResolution=48, PhiResolution=24)
colour2 = Calculator(Input=sphere2, ResultArrayName="Colour",
                     Function="(0.5+0.5*tanh(20*(coordsX-2)))*iHat + 0.2*jHat + (0.5+0.5*tanh(20*coordsZ))*kHat")
group_spheres = GroupDatasets(Input=[colour, colour2])
composite_surface = SurfaceShockAdvection(Input=group_spheres, FlowTime=512.0, GenerateFlowArrays=1)
composite_surface.InputArray = ["POINTS", "Colour"]
check(in_input_domain(composite_surface, group_spheres), "composite surfaces: accepted by the input domain")
composite_surface.UpdatePipeline()
parts = blocks(fetch(composite_surface))
check(len(parts) == 2, "composite surfaces: 2 blocks")
for index, (part, alone_source) in enumerate(zip(parts, [colour, colour2])):
    alone = SurfaceShockAdvection(Input=alone_source, FlowTime=512.0)
    alone.InputArray = ["POINTS", "Colour"]
    alone.UpdatePipeline()
    check(np.array_equal(point_array(part, "Colour"), point_array(fetch(alone), "Colour")),
          "composite surfaces: block %d == block alone" % index)
    check(part.GetPointData().GetArray("ShockPotential") is not None, "composite surfaces: flow arrays per block")

# Sharpen: two rounded boxes, one moved.
moved = Transform(Input=rounded)
moved.Transform.Translate = [3, 0, 0]
group_boxes = GroupDatasets(Input=[rounded, moved])
composite_sharpen = SurfaceShockSharpen(Input=group_boxes, FlowTime=64.0)
composite_sharpen.UpdatePipeline()
parts = blocks(fetch(composite_sharpen))
alone = SurfaceShockSharpen(Input=rounded, FlowTime=64.0)
alone.UpdatePipeline()
check(len(parts) == 2, "composite sharpen: 2 blocks")
check(np.allclose(points(parts[0]), points(fetch(alone))), "composite sharpen: block 0 == alone")
check(np.allclose(points(parts[1]) - [3, 0, 0], points(fetch(alone)), atol=1e-5),
      "composite sharpen: block 1 == alone, translated")
check(parts[1].GetFieldData().GetArray("ShockSolverIterations") is not None, "composite sharpen: field data per block")

# Partitioned dataset collections (the newer composite type).
partitioned = ConvertToPartitionedDataSetCollection(Input=group_spheres)
composite_partitioned = SurfaceShockAdvection(Input=partitioned, FlowTime=512.0)
composite_partitioned.InputArray = ["POINTS", "Colour"]
composite_partitioned.UpdatePipeline()
# servermanager.Fetch turns a partitioned collection into a broken multiblock in
# ParaView 5.11; in this builtin session the VTK output itself can be read.
result = composite_partitioned.GetClientSideObject().GetOutputDataObject(0)
parts = blocks(result)
check(result.IsA("vtkPartitionedDataSetCollection") and len(parts) == 2, "partitioned: 2 partitions, %s" % result.GetClassName())
check(len(parts) == 2 and np.array_equal(point_array(parts[0], "Colour"),
                                         point_array(fetch(composite_surface).GetBlock(0), "Colour")),
      "partitioned: same result as the multiblock")

# Mixed block types (the input domain accepts a composite with any matching
# block): the matching blocks are filtered as if alone, each with the array it
# has (ParaView names one array for all blocks: a block without it takes its
# own active scalars), the other blocks pass through unchanged; no error.
heat = Elevation(Input=Sphere(ThetaResolution=48, PhiResolution=24), LowPoint=[0, 0, -0.1], HighPoint=[0, 0, 0.1])
group_mixed = GroupDatasets(Input=[wavelet, heat])
mixed = ImageShockAdvection(Input=group_mixed)  # defaults, as a user writes it
check(in_input_domain(mixed, group_mixed), "mixed blocks: in the image input domain")
mixed_surface = SurfaceShockAdvection(Input=group_mixed, FlowTime=512.0)
messages.clear()
mixed.UpdatePipeline()
mixed_surface.UpdatePipeline()
check(not messages.errors, "mixed blocks: no error, got %s" % messages.errors)
image_alone = ImageShockAdvection(Input=wavelet)
image_alone.InputArray = ["POINTS", "RTData"]
image_alone.UpdatePipeline()
surface_alone = SurfaceShockAdvection(Input=heat, FlowTime=512.0)
surface_alone.UpdatePipeline()
parts = blocks(mixed.GetClientSideObject().GetOutputDataObject(0))
check(len(parts) == 2 and parts[0].IsA("vtkImageData") and parts[1].IsA("vtkPolyData"), "mixed blocks: types kept")
check(np.array_equal(point_array(parts[0], "RTData"), point_array(fetch(image_alone), "RTData")),
      "mixed blocks: the image block filtered as alone (its RTData)")
check(not np.array_equal(point_array(parts[0], "RTData"), point_array(fetch(wavelet), "RTData")),
      "mixed blocks: the image block changed")
check(np.array_equal(point_array(parts[1], "Elevation"), point_array(fetch(heat), "Elevation")) and
      np.array_equal(points(parts[1]), points(fetch(heat))), "mixed blocks: the mesh block unchanged by the image filter")
parts = blocks(mixed_surface.GetClientSideObject().GetOutputDataObject(0))
check(len(parts) == 2 and np.array_equal(point_array(parts[1], "Elevation"), point_array(fetch(surface_alone), "Elevation")),
      "mixed blocks: the mesh block filtered as alone by the surface filter")
check(not np.array_equal(point_array(parts[1], "Elevation"), point_array(fetch(heat), "Elevation")),
      "mixed blocks: the mesh block changed")
check(np.array_equal(point_array(parts[0], "RTData"), point_array(fetch(wavelet), "RTData")),
      "mixed blocks: the image block unchanged by the surface filter")

print("%d passed, %d failed" % (passed, len(failures)))
sys.exit(1 if failures else 0)
