"""pvpython test of the ShockFilters ParaView plugin, sections 5 to 7: bad
values (errors through vtkOutputWindow, an empty output, no crash, the session
goes on; out-of-range values clamped by the classes), composite inputs
(GroupDatasets, partitioned collections, mixed block types) and derived
arrays (a vector's Magnitude or component chosen as the filtered array).

Run by TestShockFiltersPlugin.py (CTest PluginShockFilters) in its session and
namespace, after TestShockFiltersPluginPipelines.py, whose pipelines (image,
surface, sharpen, wavelet, colour, rounded) it uses with the plugin's functions
and the helpers of PluginTestSupport.py.
"""
import numpy as np

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
    (sharpen_probe, "AnchorWeight", -1.0, 0.0),
    (sharpen_probe, "AnchorAngle", 200.0, 180.0),
    (sharpen_probe, "DriftRadius", -1.0, 0.0),
    (sharpen_probe, "DriftRadius", 5000.0, 1000.0),
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

# ---------------------------------------------------------------------------
# 7. A derived array chosen in the panel (a vector's Magnitude or one of its
# components): ParaView computes it before the filter (vtkPVPostFilter, asked
# for by the proxies' executive, vtkPVShockCompositeDataPipeline), and the
# filter sharpens it as any array.
vector = Calculator(Input=wavelet, ResultArrayName="V", Function="RTData*iHat + coordsY*jHat")
for derived in ("V_Magnitude", "V_X"):
    chosen = ImageShockAdvection(Input=vector, InputArray=["POINTS", derived])
    messages.clear()
    chosen.UpdatePipeline()
    result = fetch(chosen)
    check(not messages.errors and result.GetNumberOfPoints() == 80 * 60, "%s: filtered without error" % derived)
    vectors = point_array(fetch(vector), "V")
    given = np.linalg.norm(vectors, axis=1) if derived.endswith("Magnitude") else vectors[:, 0]
    got = point_array(result, derived)
    check(got is not None and got.shape == given.shape and not np.allclose(got, given),
          "%s: the derived array is in the output, sharpened" % derived)
    check(got is not None and got.min() >= given.min() - 1e-9 and got.max() <= given.max() + 1e-9,
          "%s: values resampled from the input's (within its range)" % derived)
    check(chosen.GetClientSideObject().GetExecutive().GetClassName() == "vtkPVShockCompositeDataPipeline",
          "%s: the proxy's executive" % derived)
    Delete(chosen)
