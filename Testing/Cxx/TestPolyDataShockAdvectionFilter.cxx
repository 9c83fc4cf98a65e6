// Tests of vtkPolyDataShockAdvectionFilter in real VTK pipelines: mesh and array
// handling, array types, pass-through, flow arrays, invariances (the flow
// modes, errors, mesh defects, NaN values, progress and abort:
// TestPolyDataShockAdvectionModes.cxx).
#include "TestPolyDataAdvection.h"

namespace
{

// ---------------------------------------------------------------------------
// A pipeline, structure and basic properties

TEST(PolyDataShockAdvectionFilter, ElevationOnASphereInAPipelineKeepsTheMesh)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(96);
  sphere->SetPhiResolution(96);
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(sphere->GetOutputPort());
  elevation->SetLowPoint(0.0, 0.0, -0.5);
  elevation->SetHighPoint(0.0, 0.0, 0.5);
  vtkNew<Filter> filter;
  filter->SetInputConnection(elevation->GetOutputPort());
  filter->SetFlowTime(RampSharpeningTime);
  MessageLog log(filter);
  ASSERT_TRUE(UpdateSucceeds(filter));
  EXPECT_TRUE(log.Errors.empty()) << log.Errors;
  EXPECT_TRUE(log.Warnings.empty()) << log.Warnings;

  vtkPolyData* in = elevation->GetPolyDataOutput();
  vtkPolyData* out = filter->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), in->GetNumberOfPoints());
  ASSERT_EQ(out->GetNumberOfCells(), in->GetNumberOfCells());
  ASSERT_EQ(out->GetNumberOfPolys(), in->GetNumberOfPolys());
  for (vtkIdType p = 0; p < in->GetNumberOfPoints(); ++p)
  {
    double a[3], b[3];
    in->GetPoint(p, a);
    out->GetPoint(p, b);
    ASSERT_TRUE(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) << p;
  }
  for (vtkIdType cell = 0; cell < in->GetNumberOfCells(); ++cell)
  {
    vtkNew<vtkIdList> a, b;
    in->GetCellPoints(cell, a);
    out->GetCellPoints(cell, b);
    ASSERT_EQ(a->GetNumberOfIds(), b->GetNumberOfIds());
    for (vtkIdType k = 0; k < a->GetNumberOfIds(); ++k)
    {
      ASSERT_EQ(a->GetId(k), b->GetId(k));
    }
  }

  vtkDataArray* inScalars = in->GetPointData()->GetScalars();
  vtkDataArray* outScalars = out->GetPointData()->GetScalars();
  ASSERT_NE(inScalars, nullptr);
  ASSERT_NE(outScalars, nullptr); // the filtered array is still the active scalars
  EXPECT_STREQ(outScalars->GetName(), "Elevation");
  EXPECT_EQ(outScalars->GetDataType(), inScalars->GetDataType());
  EXPECT_EQ(outScalars->GetNumberOfComponents(), 1);
  EXPECT_NE(out->GetPointData()->GetArray("Normals"), nullptr);
  EXPECT_TRUE(FiniteAndInRange(outScalars, inScalars));
  // The linear ramp on a sphere is steepest along the equator: it sharpens there.
  const Range r = RangeOf(inScalars);
  EXPECT_LT(BandCount(outScalars, r), 0.8 * BandCount(inScalars, r));
  EXPECT_GT(filter->GetLastTraceSteps(), 0u);
}

TEST(PolyDataShockAdvectionFilter, BlurredStepGetsSharper)
{
  auto mesh = StepSphere();
  vtkDataArray* in = mesh->GetPointData()->GetScalars();
  const Range r = RangeOf(in);
  auto out = FilterMesh(mesh, SharpeningTime);
  vtkDataArray* result = out->GetPointData()->GetArray("Step");
  ASSERT_TRUE(FiniteAndInRange(result, in));
  const vtkIdType before = BandCount(in, r);
  const vtkIdType after = BandCount(result, r);
  EXPECT_LT(after, before / 2) << before << " -> " << after;
  // Each side of the edge keeps its value: the far plateaus are not touched.
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    const double d = Dot(x, StepDirection());
    if (std::abs(d) > 0.2)
    {
      ASSERT_NEAR(result->GetComponent(p, 0), in->GetComponent(p, 0), 1e-12) << p;
    }
  }
  // And the transition does not move: it stays centred on the step.
  double meanIn = 0.0, meanOut = 0.0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    meanIn += in->GetComponent(p, 0);
    meanOut += result->GetComponent(p, 0);
  }
  EXPECT_NEAR(meanOut / mesh->GetNumberOfPoints(), meanIn / mesh->GetNumberOfPoints(), 0.01);
}

TEST(PolyDataShockAdvectionFilter, TimeZeroIsExactlyTheInput)
{
  auto mesh = StepSphere();
  mesh->GetPointData()->AddArray(PointArray<vtkFloatArray>(
    mesh, "FloatStep", [](const double x[3], int c) { return 3.0 * BlurredStep(x) + c; }, 2));
  EXPECT_EQ(Values(FilterMesh(mesh, 0.0)->GetPointData()->GetArray("Step")),
    Values(mesh->GetPointData()->GetArray("Step")));
  EXPECT_EQ(Values(FilterMesh(mesh, 0.0, PointArrayNamed("FloatStep"))->GetPointData()->GetArray("FloatStep")),
    Values(mesh->GetPointData()->GetArray("FloatStep")));
  // Not a tautology: a positive time changes the same data.
  EXPECT_NE(Values(FilterMesh(mesh, 10.0)->GetPointData()->GetArray("Step")),
    Values(mesh->GetPointData()->GetArray("Step")));
}

TEST(PolyDataShockAdvectionFilter, IsolatedExtremaKeepTheirValues)
{
  auto mesh = Sphere();
  // A bump and a pit centred on two mesh vertices.
  auto nearest = [&mesh](double x, double y, double z) {
    const double d[3] = { x, y, z };
    vtkIdType best = 0;
    double score = -1e300;
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      double q[3];
      mesh->GetPoint(p, q);
      if (Dot(q, d) > score)
      {
        score = Dot(q, d);
        best = p;
      }
    }
    return best;
  };
  const vtkIdType top = nearest(0.3, -0.7, 0.5);
  const vtkIdType bottom = nearest(-0.6, 0.2, -0.4);
  double ct[3], cb[3];
  mesh->GetPoint(top, ct);
  mesh->GetPoint(bottom, cb);
  auto field = [&](const double x[3], int) {
    auto g = [x](const double c[3]) {
      const double d2 = (x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) +
        (x[2] - c[2]) * (x[2] - c[2]);
      return std::exp(-d2 / (0.1 * 0.1));
    };
    return 0.5 + 0.4 * g(ct) - 0.4 * g(cb);
  };
  mesh->GetPointData()->SetScalars(PointArray(mesh, "Bumps", field));
  vtkDataArray* in = mesh->GetPointData()->GetScalars();
  const Range r = RangeOf(in);
  ASSERT_NEAR(r.high, 0.9, 1e-9);
  ASSERT_NEAR(r.low, 0.1, 1e-9);
  auto out = FilterMesh(mesh, SharpeningTime);
  vtkDataArray* result = out->GetPointData()->GetArray("Bumps");
  ASSERT_TRUE(FiniteAndInRange(result, in));
  EXPECT_NEAR(result->GetComponent(top, 0), 0.9, 0.005 * r.Width());
  EXPECT_NEAR(result->GetComponent(bottom, 0), 0.1, 0.005 * r.Width());
  // The flanks did sharpen (the filter did something).
  EXPECT_GT(MaxAbsDifference(Values(result), Values(in)), 0.05 * r.Width());
}

// ---------------------------------------------------------------------------
// Array types and components

TEST(PolyDataShockAdvectionFilter, EveryNumericTypeKeepsItsTypeAndMatchesDouble)
{
  auto mesh = Sphere();
  const Field field = [](const double x[3], int) { return -50.0 + 200.0 * BlurredStep(x); };
  mesh->GetPointData()->SetScalars(PointArray(mesh, "Values", field));
  const auto expected = Values(FilterMesh(mesh, SharpeningTime)->GetPointData()->GetScalars());
  const auto input = Values(mesh->GetPointData()->GetScalars());
  ASSERT_EQ(expected.size(), input.size());
  ASSERT_GT(MaxAbsDifference(expected, input), 20.0);

  std::vector<vtkSmartPointer<vtkDataArray>> arrays = { PointArray<vtkFloatArray>(mesh, "Values", field),
    PointArray<vtkShortArray>(mesh, "Values", field), PointArray<vtkIntArray>(mesh, "Values", field) };
  for (auto& array : arrays)
  {
    auto typed = vtkSmartPointer<vtkPolyData>::New();
    typed->ShallowCopy(mesh);
    typed->GetPointData()->SetScalars(array);
    vtkSmartPointer<vtkDataArray> result = FilterMesh(typed, SharpeningTime)->GetPointData()->GetScalars();
    ASSERT_NE(result, nullptr);
    EXPECT_EQ(result->GetDataType(), array->GetDataType()) << array->GetClassName();
    EXPECT_STREQ(result->GetName(), "Values");
    EXPECT_TRUE(FiniteAndInRange(result, array)) << array->GetClassName();
    const auto values = Values(result);
    ASSERT_EQ(values.size(), expected.size());
    double mean = 0.0;
    for (size_t i = 0; i < values.size(); ++i)
    {
      if (array->GetDataType() != VTK_FLOAT)
      {
        ASSERT_EQ(values[i], std::round(values[i]));
      }
      mean += std::abs(values[i] - expected[i]);
    }
    EXPECT_LT(mean / static_cast<double>(values.size()), 1.0) << array->GetClassName();
  }
}

TEST(PolyDataShockAdvectionFilter, RgbColoursMoveTogetherAlongTheEdge)
{
  auto mesh = Sphere();
  const double a[3] = { 220.0, 40.0, 30.0 };
  const double b[3] = { 30.0, 160.0, 240.0 };
  auto colours = PointArray<vtkUnsignedCharArray>(
    mesh, "Colors", [&](const double x[3], int c) { return std::round(a[c] + BlurredStep(x) * (b[c] - a[c])); }, 3);
  mesh->GetPointData()->SetScalars(colours);
  auto out = FilterMesh(mesh, SharpeningTime);
  vtkDataArray* result = out->GetPointData()->GetScalars();
  ASSERT_NE(result, nullptr);
  EXPECT_EQ(result->GetDataType(), VTK_UNSIGNED_CHAR);
  EXPECT_EQ(result->GetNumberOfComponents(), 3);
  EXPECT_STREQ(result->GetName(), "Colors");
  EXPECT_TRUE(FiniteAndInRange(result, colours));

  // Every output colour lies on the segment a-b, within the rounding of input and output.
  const double ab[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  vtkIdType bandBefore = 0, bandAfter = 0;
  double worst = 0.0;
  auto parameter = [&](const double* rgb) {
    const double v[3] = { rgb[0] - a[0], rgb[1] - a[1], rgb[2] - a[2] };
    return Dot(v, ab) / Dot(ab, ab);
  };
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const double* c = result->GetTuple3(p);
    const double s = std::min(1.0, std::max(0.0, parameter(c)));
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      d2 += (c[k] - a[k] - s * ab[k]) * (c[k] - a[k] - s * ab[k]);
    }
    worst = std::max(worst, std::sqrt(d2));
    bandAfter += (s > 0.1 && s < 0.9) ? 1 : 0;
    const double sIn = parameter(colours->GetTuple3(p));
    bandBefore += (sIn > 0.1 && sIn < 0.9) ? 1 : 0;
  }
  EXPECT_LE(worst, 0.5 * std::sqrt(3.0) * 2.0 + 1e-9);
  EXPECT_LT(bandAfter, bandBefore / 2) << bandBefore << " -> " << bandAfter;
}

TEST(PolyDataShockAdvectionFilter, AnyNumberOfComponentsShareOneFlow)
{
  auto mesh = StepSphere();
  const auto single = Values(FilterMesh(mesh, SharpeningTime)->GetPointData()->GetScalars());
  ASSERT_EQ(single.size(), static_cast<size_t>(mesh->GetNumberOfPoints()));

  // A constant channel inside the range adds no gradient: channel 0 matches the
  // single-channel result and the constant stays constant.
  auto pair = PointArray(mesh, "Pair", [](const double x[3], int c) { return c == 0 ? BlurredStep(x) : 0.375; }, 2);
  mesh->GetPointData()->AddArray(pair);
  vtkSmartPointer<vtkDataArray> pairOut = FilterMesh(mesh, SharpeningTime, PointArrayNamed("Pair"))->GetPointData()->GetArray("Pair");
  ASSERT_NE(pairOut, nullptr);
  ASSERT_EQ(pairOut->GetNumberOfComponents(), 2);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    ASSERT_NEAR(pairOut->GetComponent(p, 0), single[static_cast<size_t>(p)], 1e-12) << p;
    ASSERT_NEAR(pairOut->GetComponent(p, 1), 0.375, 1e-12) << p;
  }

  // One flow for all channels: a slow ramp along the step direction, filtered
  // alone, hardly moves in this time; next to the step as a second channel it is
  // carried along by the step's flow and jumps where the step does.
  auto ramp = [](const double x[3]) { return 0.5 + 0.5 * Dot(x, StepDirection()); };
  auto rampOnly = PointArray(mesh, "Ramp", [&](const double x[3], int) { return ramp(x); });
  auto coupled = PointArray(mesh, "Coupled", [&](const double x[3], int c) { return c == 0 ? BlurredStep(x) : ramp(x); }, 2);
  mesh->GetPointData()->AddArray(rampOnly);
  mesh->GetPointData()->AddArray(coupled);
  vtkSmartPointer<vtkDataArray> rampOut = FilterMesh(mesh, SharpeningTime, PointArrayNamed("Ramp"))->GetPointData()->GetArray("Ramp");
  vtkSmartPointer<vtkDataArray> coupledOut = FilterMesh(mesh, SharpeningTime, PointArrayNamed("Coupled"))->GetPointData()->GetArray("Coupled");
  ASSERT_NE(rampOut, nullptr);
  ASSERT_NE(coupledOut, nullptr);
  double alone = 0.0, together = 0.0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    alone = std::max(alone, std::abs(rampOut->GetComponent(p, 0) - rampOnly->GetComponent(p, 0)));
    together = std::max(together, std::abs(coupledOut->GetComponent(p, 1) - coupled->GetComponent(p, 1)));
  }
  EXPECT_LT(alone, 0.005);
  EXPECT_GT(together, 0.02);

  // Five colour-like channels (one value range shared by all, as the range that
  // normalises the intensities is taken over all channels): each stays within its
  // own range and all sharpen together.
  auto five = PointArray(mesh, "Five",
    [](const double x[3], int c) {
      static const double from[5] = { 0.0, 1.0, 0.2, 0.9, 0.3 };
      static const double to[5] = { 1.0, 0.0, 0.8, 0.4, 0.7 };
      return from[c] + BlurredStep(x) * (to[c] - from[c]);
    },
    5);
  mesh->GetPointData()->AddArray(five);
  vtkSmartPointer<vtkDataArray> fiveOut = FilterMesh(mesh, SharpeningTime, PointArrayNamed("Five"))->GetPointData()->GetArray("Five");
  ASSERT_NE(fiveOut, nullptr);
  ASSERT_EQ(fiveOut->GetNumberOfComponents(), 5);
  EXPECT_TRUE(FiniteAndInRange(fiveOut, five));
  for (int c = 0; c < 5; ++c)
  {
    const Range r = RangeOf(five, c);
    vtkIdType before = 0, after = 0;
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      const double sIn = (five->GetComponent(p, c) - r.low) / r.Width();
      const double sOut = (fiveOut->GetComponent(p, c) - r.low) / r.Width();
      before += (sIn > 0.1 && sIn < 0.9) ? 1 : 0;
      after += (sOut > 0.1 && sOut < 0.9) ? 1 : 0;
    }
    EXPECT_LT(after, before / 2) << "component " << c;
  }
}

// ---------------------------------------------------------------------------
// Cell data, quads, strips

TEST(PolyDataShockAdvectionFilter, CellDataOnTrianglesIsFiltered)
{
  auto mesh = Sphere();
  auto cells = CellArray(mesh, "CellStep", [](const double x[3], int) { return BlurredStep(x); });
  mesh->GetCellData()->SetScalars(cells);
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->SetFlowTime(SharpeningTime);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "CellStep");
  MessageLog log(filter);
  ASSERT_TRUE(UpdateSucceeds(filter));
  EXPECT_TRUE(log.Errors.empty()) << log.Errors;
  vtkDataArray* result = filter->GetOutput()->GetCellData()->GetScalars();
  ASSERT_NE(result, nullptr);
  EXPECT_STREQ(result->GetName(), "CellStep");
  EXPECT_NE(result, cells.GetPointer());
  EXPECT_TRUE(FiniteAndInRange(result, cells));
  const Range r = RangeOf(cells);
  EXPECT_LT(BandCount(result, r), BandCount(cells, r) / 2)
    << BandCount(cells, r) << " -> " << BandCount(result, r);
}

TEST(PolyDataShockAdvectionFilter, QuadsAndStripsKeepTheirCells)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(60, 60);
  plane->SetOrigin(-0.5, -0.5, 0.0);
  plane->SetPoint1(0.5, -0.5, 0.0);
  plane->SetPoint2(-0.5, 0.5, 0.0);
  plane->Update();
  auto quads = vtkSmartPointer<vtkPolyData>::New();
  quads->ShallowCopy(plane->GetOutput());
  ASSERT_EQ(quads->GetCellType(0), VTK_QUAD);
  auto ramp = [](const double x[3], int) { return SmoothStep(x[0] + 0.3 * x[1], 0.08); };
  quads->GetPointData()->SetScalars(PointArray(quads, "PointStep", ramp));
  quads->GetCellData()->AddArray(CellArray(quads, "CellStep", ramp));

  // Cell data on quads: refused, with a hint.
  {
    vtkNew<Filter> filter;
    filter->SetInputData(quads);
    filter->SetFlowTime(SharpeningTime);
    filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "CellStep");
    MessageLog log(filter);
    EXPECT_FALSE(UpdateSucceeds(filter));
    EXPECT_NE(log.Errors.find("Triangulate"), std::string::npos) << log.Errors;
  }

  // Point data on quads: filtered, the quads are kept.
  {
    vtkNew<Filter> filter;
    filter->SetInputData(quads);
    filter->SetFlowTime(SharpeningTime);
    MessageLog log(filter);
    ASSERT_TRUE(UpdateSucceeds(filter));
    EXPECT_TRUE(log.Errors.empty()) << log.Errors;
    vtkPolyData* out = filter->GetOutput();
    ASSERT_EQ(out->GetNumberOfCells(), quads->GetNumberOfCells());
    for (vtkIdType cell = 0; cell < out->GetNumberOfCells(); ++cell)
    {
      ASSERT_EQ(out->GetCellType(cell), VTK_QUAD);
    }
    vtkDataArray* in = quads->GetPointData()->GetScalars();
    vtkDataArray* result = out->GetPointData()->GetScalars();
    ASSERT_TRUE(FiniteAndInRange(result, in));
    const Range r = RangeOf(in);
    EXPECT_LT(BandCount(result, r), BandCount(in, r) / 2) << BandCount(in, r) << " -> " << BandCount(result, r);
  }

  // Triangle strips (vtkStripper) with point data: filtered, the strips are kept,
  // and the result matches the same triangles given as polygons.
  auto sphere = StepSphere();
  vtkNew<vtkStripper> stripper;
  stripper->SetInputData(sphere);
  vtkNew<Filter> filter;
  filter->SetInputConnection(stripper->GetOutputPort());
  filter->SetFlowTime(SharpeningTime);
  MessageLog log(filter);
  ASSERT_TRUE(UpdateSucceeds(filter));
  EXPECT_TRUE(log.Errors.empty()) << log.Errors;
  vtkPolyData* strips = stripper->GetOutput();
  vtkPolyData* out = filter->GetOutput();
  ASSERT_GT(strips->GetNumberOfStrips(), 0);
  EXPECT_EQ(out->GetNumberOfStrips(), strips->GetNumberOfStrips());
  EXPECT_EQ(out->GetNumberOfPolys(), strips->GetNumberOfPolys());
  EXPECT_EQ(out->GetNumberOfCells(), strips->GetNumberOfCells());
  vtkDataArray* in = strips->GetPointData()->GetScalars();
  vtkDataArray* result = out->GetPointData()->GetScalars();
  ASSERT_TRUE(FiniteAndInRange(result, in));
  const auto viaTriangles = Values(FilterMesh(sphere, SharpeningTime)->GetPointData()->GetScalars());
  const auto viaStrips = Values(result);
  ASSERT_EQ(viaStrips.size(), viaTriangles.size());
  size_t close = 0;
  double meanDifference = 0.0;
  for (size_t i = 0; i < viaStrips.size(); ++i)
  {
    close += std::abs(viaStrips[i] - viaTriangles[i]) < 1e-9 ? 1 : 0;
    meanDifference += std::abs(viaStrips[i] - viaTriangles[i]) / static_cast<double>(viaStrips.size());
  }
  EXPECT_GT(close, viaStrips.size() * 99 / 100);
  EXPECT_LT(meanDifference, 1e-3);

  // Cell data on strips is refused like on quads.
  strips->GetCellData()->SetScalars(CellArray(strips, "StripCells", ramp));
  vtkNew<Filter> cellFilter;
  cellFilter->SetInputData(strips);
  cellFilter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "StripCells");
  MessageLog cellLog(cellFilter);
  EXPECT_FALSE(UpdateSucceeds(cellFilter));
  EXPECT_NE(cellLog.Errors.find("Triangulate"), std::string::npos) << cellLog.Errors;
}

TEST(PolyDataShockAdvectionFilter, VerticesAndLinesPassThrough)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(64);
  vtkNew<vtkLineSource> line;
  line->SetPoint1(0.8, 0.0, -0.4);
  line->SetPoint2(1.2, 0.0, 0.4);
  line->SetResolution(20);
  vtkNew<vtkPointSource> cloud;
  cloud->SetNumberOfPoints(25);
  cloud->SetCenter(0.0, 0.0, 0.8);
  cloud->SetRadius(0.3);
  vtkNew<vtkAppendPolyData> append;
  append->AddInputConnection(sphere->GetOutputPort());
  append->AddInputConnection(line->GetOutputPort());
  append->AddInputConnection(cloud->GetOutputPort());
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(append->GetOutputPort());
  elevation->SetLowPoint(0.0, 0.0, -0.5);
  elevation->SetHighPoint(0.0, 0.0, 0.5);
  vtkNew<Filter> filter;
  filter->SetInputConnection(elevation->GetOutputPort());
  filter->SetFlowTime(RampSharpeningTime);
  filter->GenerateFlowArraysOn();
  MessageLog log(filter);
  ASSERT_TRUE(UpdateSucceeds(filter));
  EXPECT_TRUE(log.Errors.empty()) << log.Errors;

  vtkPolyData* in = elevation->GetPolyDataOutput();
  vtkPolyData* out = filter->GetOutput();
  const vtkIdType spherePoints = sphere->GetOutput()->GetNumberOfPoints();
  ASSERT_EQ(in->GetNumberOfPoints(), spherePoints + 21 + 25);
  ASSERT_GT(in->GetNumberOfVerts(), 0);
  ASSERT_GT(in->GetNumberOfLines(), 0);
  EXPECT_EQ(out->GetNumberOfVerts(), in->GetNumberOfVerts());
  EXPECT_EQ(out->GetNumberOfLines(), in->GetNumberOfLines());
  EXPECT_EQ(out->GetNumberOfPolys(), in->GetNumberOfPolys());
  vtkDataArray* before = in->GetPointData()->GetScalars();
  vtkDataArray* after = out->GetPointData()->GetScalars();
  ASSERT_NE(after, nullptr);
  // Line and vertex points keep their values exactly, and they do vary.
  const Range lineRange = [&] {
    Range r;
    for (vtkIdType p = spherePoints; p < in->GetNumberOfPoints(); ++p)
    {
      r.low = std::min(r.low, before->GetComponent(p, 0));
      r.high = std::max(r.high, before->GetComponent(p, 0));
      EXPECT_EQ(after->GetComponent(p, 0), before->GetComponent(p, 0)) << p;
    }
    return r;
  }();
  EXPECT_GT(lineRange.Width(), 0.5);
  // The sphere part is filtered.
  double change = 0.0;
  for (vtkIdType p = 0; p < spherePoints; ++p)
  {
    change = std::max(change, std::abs(after->GetComponent(p, 0) - before->GetComponent(p, 0)));
  }
  EXPECT_GT(change, 0.05);
  // The flow is zero on vertex and line cells, non-zero on triangles.
  vtkDataArray* flow = out->GetCellData()->GetArray("ShockFlow");
  ASSERT_NE(flow, nullptr);
  ASSERT_EQ(flow->GetNumberOfTuples(), out->GetNumberOfCells());
  const vtkIdType firstPolygon = out->GetNumberOfVerts() + out->GetNumberOfLines();
  double polygonFlow = 0.0;
  for (vtkIdType cell = 0; cell < out->GetNumberOfCells(); ++cell)
  {
    const double* u = flow->GetTuple3(cell);
    const double norm = std::sqrt(Dot(u, u));
    if (cell < firstPolygon)
    {
      ASSERT_EQ(norm, 0.0) << cell;
    }
    else
    {
      polygonFlow = std::max(polygonFlow, norm);
    }
  }
  EXPECT_GT(polygonFlow, 0.0);
}

// ---------------------------------------------------------------------------
// Pass-through and input integrity

TEST(PolyDataShockAdvectionFilter, OtherArraysPassThroughAndTheInputIsUntouched)
{
  auto mesh = StepSphere();
  vtkDataArray* step = mesh->GetPointData()->GetScalars();
  auto second = PointArray(mesh, "Second", [](const double x[3], int) { return 1.0 - BlurredStep(x); });
  mesh->GetPointData()->AddArray(second);
  auto ids = CellArray<vtkIntArray>(mesh, "CellLabel", [](const double x[3], int) { return x[2] > 0 ? 7 : 3; });
  mesh->GetCellData()->SetScalars(ids);
  vtkNew<vtkDoubleArray> meta;
  meta->SetName("Meta");
  meta->InsertNextValue(42.0);
  meta->InsertNextValue(-1.5);
  mesh->GetFieldData()->AddArray(meta);

  struct Snapshot
  {
    std::string name;
    std::vector<double> values;
    vtkMTimeType mtime;
  };
  auto snapshot = [](vtkDataArray* a) { return Snapshot{ a->GetName(), Values(a), a->GetMTime() }; };
  const std::vector<vtkDataArray*> inputs = { step, second, mesh->GetPointData()->GetArray("Normals"), ids, meta };
  std::vector<Snapshot> before;
  for (vtkDataArray* a : inputs)
  {
    ASSERT_NE(a, nullptr);
    before.push_back(snapshot(a));
  }
  std::vector<double> coordinates(static_cast<size_t>(3 * mesh->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    mesh->GetPoint(p, &coordinates[static_cast<size_t>(3 * p)]);
  }

  for (const char* selected : { "Step", "Second" })
  {
    vtkNew<Filter> filter;
    filter->SetInputData(mesh);
    filter->SetFlowTime(SharpeningTime);
    filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, selected);
    filter->Update();
    vtkPolyData* out = filter->GetOutput();

    // The input is unchanged, including the filtered array.
    for (size_t k = 0; k < inputs.size(); ++k)
    {
      EXPECT_EQ(Values(inputs[k]), before[k].values) << before[k].name;
      EXPECT_EQ(inputs[k]->GetMTime(), before[k].mtime) << before[k].name;
    }
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      double x[3];
      mesh->GetPoint(p, x);
      ASSERT_TRUE(x[0] == coordinates[3 * p] && x[1] == coordinates[3 * p + 1] && x[2] == coordinates[3 * p + 2]);
    }
    EXPECT_EQ(mesh->GetPointData()->GetScalars(), step);

    // Output: the selected array is filtered, every other array is the input's.
    vtkPointData* pd = out->GetPointData();
    ASSERT_EQ(pd->GetNumberOfArrays(), mesh->GetPointData()->GetNumberOfArrays());
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
    {
      EXPECT_STREQ(pd->GetArrayName(i), mesh->GetPointData()->GetArrayName(i)); // same order
    }
    ASSERT_NE(pd->GetScalars(), nullptr);
    EXPECT_STREQ(pd->GetScalars()->GetName(), "Step"); // the active scalars stay active
    ASSERT_NE(pd->GetNormals(), nullptr);
    EXPECT_STREQ(pd->GetNormals()->GetName(), "Normals");
    EXPECT_EQ(Values(pd->GetArray("Normals")), before[2].values);
    ASSERT_NE(out->GetCellData()->GetScalars(), nullptr);
    EXPECT_EQ(Values(out->GetCellData()->GetScalars()), before[3].values);
    EXPECT_STREQ(out->GetCellData()->GetScalars()->GetName(), "CellLabel");
    ASSERT_NE(out->GetFieldData()->GetArray("Meta"), nullptr);
    EXPECT_EQ(Values(out->GetFieldData()->GetArray("Meta")), before[4].values);
    EXPECT_EQ(pd->GetArray("ShockPotential"), nullptr); // not asked for
    EXPECT_EQ(out->GetCellData()->GetArray("ShockFlow"), nullptr);
    const bool stepSelected = std::string(selected) == "Step";
    EXPECT_EQ(Values(pd->GetArray("Step")) == before[0].values, !stepSelected) << selected;
    EXPECT_EQ(Values(pd->GetArray("Second")) == before[1].values, stepSelected) << selected;
    ASSERT_NE(pd->GetArray("Second"), nullptr);
    EXPECT_EQ(pd->GetArray("Second")->GetDataType(), VTK_DOUBLE);
  }
}

// ---------------------------------------------------------------------------
// Flow arrays

TEST(PolyDataShockAdvectionFilter, FlowArraysAreTangentToTheSurface)
{
  auto mesh = StepSphere();
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->SetFlowTime(100.0);
  filter->GenerateFlowArraysOn();
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  vtkDataArray* potential = out->GetPointData()->GetArray(Filter::PotentialArrayName());
  vtkDataArray* flow = out->GetCellData()->GetArray(Filter::FlowArrayName());
  ASSERT_NE(potential, nullptr);
  ASSERT_NE(flow, nullptr);
  EXPECT_STREQ(Filter::PotentialArrayName(), "ShockPotential");
  EXPECT_STREQ(Filter::FlowArrayName(), "ShockFlow");
  ASSERT_EQ(potential->GetNumberOfTuples(), mesh->GetNumberOfPoints());
  ASSERT_EQ(potential->GetNumberOfComponents(), 1);
  ASSERT_EQ(flow->GetNumberOfTuples(), mesh->GetNumberOfCells());
  ASSERT_EQ(flow->GetNumberOfComponents(), 3);
  // The filtered array is still the active scalars, not the potential.
  ASSERT_NE(out->GetPointData()->GetScalars(), nullptr);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "Step");

  // The potential is >= 0, finite, and concentrated on the edge.
  double inBand = 0.0, offBand = 0.0;
  vtkIdType nIn = 0, nOff = 0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const double v = potential->GetComponent(p, 0);
    ASSERT_TRUE(std::isfinite(v) && v >= 0.0) << p << ": " << v;
    double x[3];
    mesh->GetPoint(p, x);
    const double d = std::abs(Dot(x, StepDirection()));
    if (d < 0.04)
    {
      inBand += v;
      ++nIn;
    }
    else if (d > 0.15)
    {
      offBand += v;
      ++nOff;
    }
  }
  ASSERT_GT(nIn, 0);
  ASSERT_GT(nOff, 0);
  EXPECT_GT(inBand / nIn, 10.0 * (offBand / nOff + 1e-300));

  // The flow lies in each triangle's plane (and so is tangent to the sphere), and
  // it points towards the edge from both sides.
  double maxNorm = 0.0, maxNormal = 0.0, maxRadial = 0.0;
  double towardsBelow = 0.0, towardsAbove = 0.0;
  for (vtkIdType cell = 0; cell < mesh->GetNumberOfCells(); ++cell)
  {
    const double* u = flow->GetTuple3(cell);
    ASSERT_TRUE(std::isfinite(u[0]) && std::isfinite(u[1]) && std::isfinite(u[2])) << cell;
    const double norm = std::sqrt(Dot(u, u));
    vtkNew<vtkIdList> ids;
    mesh->GetCellPoints(cell, ids);
    ASSERT_EQ(ids->GetNumberOfIds(), 3);
    double x[3][3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids->GetId(k), x[k]);
    }
    const double e1[3] = { x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2] };
    const double e2[3] = { x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2] };
    double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
    const double nn = std::sqrt(Dot(n, n));
    double c[3];
    CellCentre(mesh, cell, c);
    const double cn = std::sqrt(Dot(c, c));
    if (norm > 0.0 && nn > 0.0)
    {
      maxNormal = std::max(maxNormal, std::abs(Dot(u, n)) / (nn * norm));
      maxRadial = std::max(maxRadial, std::abs(Dot(u, c)) / (cn * norm));
    }
    maxNorm = std::max(maxNorm, norm);
    const double d = Dot(c, StepDirection());
    if (d > -0.1 && d < -0.03)
    {
      towardsBelow += Dot(u, StepDirection());
    }
    else if (d > 0.03 && d < 0.1)
    {
      towardsAbove += Dot(u, StepDirection());
    }
  }
  EXPECT_GT(maxNorm, 0.0);
  EXPECT_LT(maxNormal, 1e-9);
  EXPECT_LT(maxRadial, 0.05); // a fine sphere: triangle normals are nearly radial
  EXPECT_GT(towardsBelow, 0.0);
  EXPECT_LT(towardsAbove, 0.0);
}

// ---------------------------------------------------------------------------
// Invariances and determinism

TEST(PolyDataShockAdvectionFilter, ScalingAndTranslatingMeshAndValuesChangeNothing)
{
  auto mesh = StepSphere(64);
  const auto reference = Values(FilterMesh(mesh, 1500.0)->GetPointData()->GetScalars());
  ASSERT_GT(MaxAbsDifference(reference, Values(mesh->GetPointData()->GetScalars())), 0.05);

  // Mesh scaled by 3.5 and moved.
  vtkNew<vtkTransform> transform;
  transform->Translate(4.0, -2.5, 1.25);
  transform->Scale(3.5, 3.5, 3.5);
  vtkNew<vtkTransformFilter> move;
  move->SetTransform(transform);
  move->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  move->SetInputData(mesh);
  move->Update();
  vtkPolyData* moved = vtkPolyData::SafeDownCast(move->GetOutput());
  ASSERT_NE(moved, nullptr);
  double x[3];
  moved->GetPoint(0, x);
  double y[3];
  mesh->GetPoint(0, y);
  ASSERT_NEAR(x[0], 4.0 + 3.5 * y[0], 1e-12);
  const auto geometry = Values(FilterMesh(moved, 1500.0)->GetPointData()->GetArray("Step"));

  // Values times 255.
  auto scaled = vtkSmartPointer<vtkPolyData>::New();
  scaled->ShallowCopy(mesh);
  scaled->GetPointData()->SetScalars(
    PointArray(mesh, "Step", [](const double p[3], int) { return 255.0 * BlurredStep(p); }));
  auto intensity = Values(FilterMesh(scaled, 1500.0)->GetPointData()->GetScalars());
  for (double& v : intensity)
  {
    v /= 255.0;
  }

  ASSERT_EQ(geometry.size(), reference.size());
  ASSERT_EQ(intensity.size(), reference.size());
  size_t geometryOff = 0, intensityOff = 0;
  for (size_t i = 0; i < reference.size(); ++i)
  {
    geometryOff += std::abs(geometry[i] - reference[i]) > 1e-9 ? 1 : 0;
    intensityOff += std::abs(intensity[i] - reference[i]) > 1e-9 ? 1 : 0;
  }
  EXPECT_EQ(geometryOff, 0u) << "max difference " << MaxAbsDifference(geometry, reference);
  EXPECT_EQ(intensityOff, 0u) << "max difference " << MaxAbsDifference(intensity, reference);
}

} // namespace
