"""pvpython test of the ShockFilters ParaView plugin: all three proxies.

Usage: pvpython --force-offscreen-rendering TestShockFiltersPlugin.py PLUGIN_PATH
           [SOURCE_DIR [HELP_DIR]]

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
- with SOURCE_DIR (the folder Plugin/, whose XML files hold one flat definition per filter):
  shared properties identical in each, range domains equal to the class
  clamps;
- with HELP_DIR (the plugin's paraview_help build folder): each filter's help
  page lists every property, enumeration defaults by name, no repository
  paths.
Prints one line per failure and ends with "N passed, M failed".

The checks are in three files, run in this order in one pvpython session and
namespace (the later parts use the plugin loaded here and the pipelines of the
earlier ones): this file (the definitions, SOURCE_DIR, HELP_DIR),
TestShockFiltersPluginPipelines.py (every property on Wavelet, Sphere and
rounded-Box pipelines) and TestShockFiltersPluginInputs.py (bad values,
clamping, composite inputs); their helpers are in PluginTestSupport.py.
"""
import os
import runpy
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.modules import vtkRemotingServerManager as smcore

import PluginTestSupport
from PluginTestSupport import *  # noqa: F401,F403

PLUGIN = sys.argv[1]
SOURCE_DIR = sys.argv[2] if len(sys.argv) > 2 else None
HELP_DIR = sys.argv[3] if len(sys.argv) > 3 else None
LABELS = {
    "ImageShockAdvection": ("Image Shock Advection", "vtkImageShockAdvectionFilter"),
    "SurfaceShockAdvection": ("Surface Shock Advection", "vtkPolyDataShockAdvectionFilter"),
    "SurfaceShockSharpen": ("Surface Shock Sharpen", "vtkPolyDataShockSharpenFilter"),
}

messages = Messages()
LoadPlugin(PLUGIN, ns=globals())

# ---------------------------------------------------------------------------
# 1. Proxy definitions.
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

COMMON_NAMES = {
    "Input", "InputArray", "FlowTime", "SmoothingPasses", "FlowMode", "NumberOfFlowUpdates",
    "TracingMode", "StepFraction", "Sampling", "GenerateFlowArrays", "NumberOfThreads",
    "LastSetupSeconds", "LastFlowSeconds", "LastAdvectionSeconds", "LastTraceSteps",
    "GhostLevels"}
EXPECTED_NAMES = {"ImageShockAdvection": COMMON_NAMES | {"LastGhostLevels", "LastHaloAttempts", "LastHaloFromSource",
                                                       "LastHaloInLayers"}}
EXPECTED_NAMES["SurfaceShockAdvection"] = COMMON_NAMES | {"LastGhostLevels", "LastRingAttempts"}
EXPECTED_NAMES["SurfaceShockSharpen"] = (COMMON_NAMES - {"InputArray"}) | {
    "FeatureAngle", "CurvatureContrast", "FitTarget", "LastRepeatedTriangles", "LastDegenerateTriangles", "LastFeatureEdges",
    "NormalSmoothingPasses", "KeepUnmovedNormals", "ScreeningWeight", "AnchorWeight", "AnchorAngle", "DriftRadius", "Solver", "SolverIterations",
    "SolverTolerance",
    "MergeCoincidentPoints", "GenerateSharpenedNormals", "LastFitSetupSeconds",
    "LastFitSolveSeconds", "LastSolverIterations", "LastSolverResidual", "LastFlippedTriangles",
    "LastMaxDisplacement", "LastGhostLevels", "LastRingAttempts"}
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
# (settable, probe and class_value: PluginTestSupport.py)
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
if SOURCE_DIR:
    import glob
    import xml.etree.ElementTree as ET
    definitions = {proxy.get("name"): {prop.get("name"): prop for prop in proxy
                                       if prop.tag.endswith("Property") and prop.tag != "InputProperty"}
                   for path in sorted(glob.glob(os.path.join(SOURCE_DIR, "*.xml")))
                   for group in ET.parse(path).getroot().iter("ProxyGroup") if group.get("name") == "filters"
                   for proxy in group.iter("SourceProxy")}
    check(set(definitions) == set(LABELS), "source XML: one flat definition per filter, %s" % sorted(definitions))
    # Deliberately different texts (what is sharpened, what is measured).
    OWN_TEXT = {"FlowTime", "Sampling", "GenerateFlowArrays", "LastSetupSeconds", "LastFlowSeconds",
                "LastAdvectionSeconds", "LastTraceSteps", "GhostLevels", "LastGhostLevels", "LastRingAttempts"}

    # Deliberately different defaults: the sharpen filter's flow time (256, the
    # advection filters' 64; docs/sharpening.md, "Choosing the flow time").
    OWN_DEFAULT = {("SurfaceShockSharpen", "FlowTime")}

    def shape(prop, with_text, with_default=True):
        rows = [(prop.tag, tuple(sorted((k, v) for k, v in prop.attrib.items()
                                        if with_default or k != "default_values")))]
        for child in prop.iter():
            if child is not prop and (with_text or child.tag != "Documentation"):
                rows.append((child.tag, tuple(sorted(child.attrib.items())), " ".join((child.text or "").split())))
        return rows

    for key in sorted(set().union(*[set(d) for d in definitions.values()])):
        copies = [(name, d[key]) for name, d in definitions.items() if key in d]
        for name, prop in copies[1:]:
            with_default = (name, key) not in OWN_DEFAULT
            check(shape(prop, key not in OWN_TEXT, with_default) == shape(copies[0][1], key not in OWN_TEXT,
                                                                           with_default),
                  "%s.%s is the same as in %s" % (name, key, copies[0][0]))
    check(definitions["SurfaceShockSharpen"]["FlowTime"].get("default_values") == "256"
          and definitions["ImageShockAdvection"]["FlowTime"].get("default_values") == "64"
          and definitions["SurfaceShockAdvection"]["FlowTime"].get("default_values") == "64",
          "FlowTime defaults: 256 for the sharpen filter, 64 for the advection filters")
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
# 2.-6. The other parts, in this session and namespace, in order.
namespace = globals()
for part in ["TestShockFiltersPluginPipelines.py", "TestShockFiltersPluginInputs.py"]:
    namespace = runpy.run_path(os.path.join(os.path.dirname(os.path.abspath(__file__)), part),
                               init_globals=namespace)

print("%d passed, %d failed" % (PluginTestSupport.passed, len(failures)))
sys.exit(1 if failures else 0)
