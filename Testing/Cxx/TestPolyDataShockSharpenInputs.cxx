// Tests of vtkPolyDataShockSharpenFilter on the inputs users bring: cell
// types, coincident points, noise and mesh defects, errors and degenerate
// inputs, pipelines, progress, abort and PrintSelf (the sharpening itself,
// arrays and solvers: TestPolyDataShockSharpenFilter.cxx).
#include "TestPolyDataSharpen.h"

namespace
{

// ---------------------------------------------------------------------------
// Coincident points

TEST(PolyDataShockSharpenFilter, MergingCoincidentPointsClosesSeams)
{
  const shocktest::MeshData welded = shocktest::RoundedBox(16, 2.0, 0.35);
  const shocktest::MeshData split = shocktest::WithDuplicatePoints(welded);
  const vtkIdType n = static_cast<vtkIdType>(welded.NumberOfPoints());
  ASSERT_GT(split.NumberOfPoints(), welded.NumberOfPoints());
  auto weldedMesh = shocktest::ToPolyData(welded);
  auto splitMesh = shocktest::ToPolyData(split);

  // The copy of each seam point (copies are appended in the order of the originals).
  std::vector<std::pair<vtkIdType, vtkIdType>> copies;
  for (vtkIdType q = n, p = 0; q < splitMesh->GetNumberOfPoints(); ++q)
  {
    while (Distance(splitMesh, p, splitMesh, q) != 0.0)
    {
      ++p;
      ASSERT_LT(p, n);
    }
    copies.emplace_back(p, q);
  }
  ASSERT_GT(copies.size(), 16u);

  const auto reference = Sharpen(weldedMesh, 2048.0, Exact);
  const auto merged = Sharpen(splitMesh, 2048.0, Exact);
  double gap = 0.0;
  for (const auto& [p, q] : copies)
  {
    gap = std::max(gap, Distance(merged, p, merged, q));
  }
  EXPECT_EQ(gap, 0.0); // every copy at exactly the same place: the seam stays closed
  // ... and the result is that of the welded mesh.
  std::vector<double> originals = Coordinates(merged);
  originals.resize(static_cast<size_t>(3 * n));
  EXPECT_LT(MaxDifference(originals, Coordinates(reference)), 1e-12);

  // Without merging, the seam is a boundary on both sides: the result is finite
  // but the two sides move independently and the seam opens.
  const auto unmerged = Sharpen(splitMesh, 2048.0, [](Filter* f) {
    f->SetSolverToExact();
    f->MergeCoincidentPointsOff();
  });
  ASSERT_TRUE(AllFinite(Coordinates(unmerged)));
  double openGap = 0.0;
  for (const auto& [p, q] : copies)
  {
    openGap = std::max(openGap, Distance(unmerged, p, unmerged, q));
  }
  std::cout << "seam gap without merging: " << openGap << " (box of side 2)\n";
  ::testing::Test::RecordProperty("UnmergedSeamGap", std::to_string(openGap));
  EXPECT_GT(openGap, 1e-6);
}

TEST(PolyDataShockSharpenFilter, CubeSourceCornersStayTogether)
{
  // vtkCubeSource: 6 quads on 24 points, every corner three times (one per face, for the normals).
  vtkNew<vtkCubeSource> cube;
  cube->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  cube->Update();
  vtkPolyData* input = cube->GetOutput();
  ASSERT_EQ(input->GetNumberOfPoints(), 24);
  auto cornerGap = [input](vtkPolyData* out) {
    double gap = 0.0;
    for (vtkIdType p = 0; p < 24; ++p)
    {
      for (vtkIdType q = p + 1; q < 24; ++q)
      {
        if (Distance(input, p, input, q) == 0.0)
        {
          gap = std::max(gap, Distance(out, p, out, q));
        }
      }
    }
    return gap;
  };
  for (int sampling : { Filter::LINEAR, Filter::NEAREST })
  {
    for (vtkTypeBool merge : { 1, 0 })
    {
      const std::string what = std::string(sampling == Filter::LINEAR ? "linear" : "nearest") +
        (merge ? ", merged" : ", not merged");
      // The paper's settings (no feature angle, projection, every triangle sampled).
      auto out = Sharpen(input, 256.0, [merge, sampling](Filter* f) {
        f->SetSolverToExact();
        f->SetSampling(sampling);
        f->SetMergeCoincidentPoints(merge);
        f->SetFeatureAngle(180.0);
        f->SetFitTargetToProjection();
        f->KeepUnmovedNormalsOff();
        f->SetNormalSmoothingPasses(0);
      });
      ExpectSameCells(out, input, what);
      ASSERT_TRUE(AllFinite(Coordinates(out))) << what;
      const double gap = cornerGap(out);
      const double moved = MaxDifference(Coordinates(out), Coordinates(input));
      std::cout << "vtkCubeSource, " << what << ": corner gap " << gap << ", largest coordinate change "
                << moved << "\n";
      if (merge)
      {
        EXPECT_EQ(gap, 0.0) << what; // the copies of a corner move as one
      }
      if (!merge || sampling == Filter::NEAREST)
      {
        // Unmerged: six separate flat squares, nothing to sharpen. Merged with
        // nearest sampling: the cube, already sharp, is a fixed point. (Merged with
        // linear sampling, the paper's per-point normals, the 12 targets are
        // interpolated from corner normals 55 degrees off the faces and the unit
        // cube is visibly deformed: coordinates change by about 0.09 at t = 256.)
        EXPECT_LT(moved, 1e-9) << what;
      }
      else
      {
        EXPECT_GT(moved, 0.05) << what;
      }
      // The default feature angle keeps the cube's creases: nothing moves.
      auto kept = Sharpen(input, 256.0, [merge, sampling](Filter* f) {
        f->SetSolverToExact();
        f->SetSampling(sampling);
        f->SetMergeCoincidentPoints(merge);
      });
      EXPECT_LT(MaxDifference(Coordinates(kept), Coordinates(input)), 1e-9) << what << ", default feature angle";
    }
  }
}

// ---------------------------------------------------------------------------
// Noise and defects

TEST(PolyDataShockSharpenFilter, NormalSmoothingCalmsNoise)
{
  auto noisy = shocktest::ToPolyData(shocktest::Noisy(shocktest::Icosphere(4), 0.01, 3));
  const double inputNoise = MeanRadialNormalError(noisy);
  double noise[2];
  for (int passes : { 0, 5 })
  {
    // Noise the flow leaves alone is calmed only with the smoothed normals as
    // targets everywhere (KeepUnmovedNormals off, as docs/sharpening.md says for noisy scans).
    auto out = Sharpen(noisy, 64.0, [passes](Filter* f) {
      f->SetNormalSmoothingPasses(passes);
      f->KeepUnmovedNormalsOff();
      f->SetSolverToExact();
    });
    noise[passes > 0] = MeanRadialNormalError(out);
  }
  std::cout << "normal noise: input " << inputNoise << ", 0 passes " << noise[0] << ", 5 passes " << noise[1]
            << "\n";
  EXPECT_LT(noise[1], 0.7 * noise[0]);
  EXPECT_LT(noise[1], inputNoise);
}

TEST(PolyDataShockSharpenFilter, MeshDefectsGiveFiniteResultsWithoutErrors)
{
  struct Defect
  {
    const char* what;
    shocktest::MeshData mesh;
    std::vector<vtkIdType> fixed; // points that must keep their coordinates exactly
  };
  const shocktest::MeshData sphere = shocktest::Icosphere(3);
  const vtkIdType n = static_cast<vtkIdType>(sphere.NumberOfPoints());
  const std::vector<Defect> defects = {
    { "open patch with holes",
      shocktest::WithHoles(shocktest::RoundedBox(10, 2.0, 0.4), { { { 0.0, 0.0, 1.0 }, 0.5 }, { { 1.0, 0.0, 0.0 }, 0.4 } }),
      {} },
    { "non-manifold", shocktest::NonManifoldFan(), {} },
    // m (id n) is used only by the collinear triangle (b, m, c).
    { "degenerate triangles", shocktest::WithDegenerateTriangles(sphere), { n } },
    { "isolated points", shocktest::WithIsolatedPoints(sphere, 4), { n, n + 1, n + 2, n + 3 } },
    { "two components", shocktest::TwoComponents(3), {} },
    { "open tube", shocktest::Cylinder(32, 12, 1.0, 2.0), {} },
  };
  for (const Defect& defect : defects)
  {
    auto mesh = shocktest::ToPolyData(defect.mesh);
    for (int solver : { Filter::CONJUGATE_GRADIENT, Filter::EXACT })
    {
      const std::string what = std::string(defect.what) + (solver == Filter::EXACT ? " (exact)" : " (cg)");
      std::string warnings;
      auto out = Sharpen(mesh, 1e6, [solver](Filter* f) { f->SetSolver(solver); }, &warnings);
      if (!warnings.empty())
      {
        std::cout << what << ": " << warnings;
      }
      ASSERT_EQ(out->GetNumberOfPoints(), mesh->GetNumberOfPoints()) << what;
      ASSERT_TRUE(AllFinite(Coordinates(out))) << what;
      EXPECT_TRUE(std::isfinite(FieldValue(out, "ShockSolverResidual"))) << what;
      ExpectSameCells(out, mesh, what);
      for (vtkIdType p : defect.fixed)
      {
        double x[3], y[3];
        out->GetPoint(p, x);
        mesh->GetPoint(p, y);
        EXPECT_TRUE(x[0] == y[0] && x[1] == y[1] && x[2] == y[2]) << what << " point " << p;
      }
      if (std::string(defect.what) == "two components")
      {
        // Two identical spheres side by side come out identical up to the shift.
        const vtkIdType half = mesh->GetNumberOfPoints() / 2;
        double worst = 0.0, moved = 0.0;
        for (vtkIdType p = 0; p < half; ++p)
        {
          double x[3], y[3];
          out->GetPoint(p, x);
          out->GetPoint(p + half, y);
          worst = std::max({ worst, std::abs(y[0] - x[0] - 4.0), std::abs(y[1] - x[1]), std::abs(y[2] - x[2]) });
          moved = std::max(moved, Distance(out, p, mesh, p));
        }
        EXPECT_LT(worst, 1e-6) << what;
        EXPECT_GT(moved, 0.0) << what;
      }
    }
  }
}

TEST(PolyDataShockSharpenFilter, MeshesWithoutAreaPassThroughUnchanged)
{
  // Only collinear triangles (zero area everywhere), and two triangles on one point.
  auto collinear = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> line;
  vtkNew<vtkCellArray> slivers;
  for (vtkIdType i = 0; i < 6; ++i)
  {
    line->InsertNextPoint(static_cast<double>(i), 2.0 * static_cast<double>(i), 0.5);
  }
  for (vtkIdType i = 0; i + 2 < 6; ++i)
  {
    const vtkIdType ids[3] = { i, i + 1, i + 2 };
    slivers->InsertNextCell(3, ids);
  }
  collinear->SetPoints(line);
  collinear->SetPolys(slivers);
  auto point = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> same;
  vtkNew<vtkCellArray> pair;
  for (int i = 0; i < 4; ++i)
  {
    same->InsertNextPoint(1.0, 1.0, 1.0);
  }
  const vtkIdType first[3] = { 0, 1, 2 }, second[3] = { 1, 3, 2 };
  pair->InsertNextCell(3, first);
  pair->InsertNextCell(3, second);
  point->SetPoints(same);
  point->SetPolys(pair);
  for (vtkPolyData* mesh : { collinear.Get(), point.Get() })
  {
    for (vtkTypeBool merge : { 0, 1 })
    {
      for (int solver : { Filter::CONJUGATE_GRADIENT, Filter::CONJUGATE_GRADIENT_TOLERANCE, Filter::EXACT })
      {
        auto out = Sharpen(mesh, 1e3, [merge, solver](Filter* f) {
          f->SetSolver(solver);
          f->SetMergeCoincidentPoints(merge);
          f->GenerateSharpenedNormalsOn();
          f->GenerateFlowArraysOn();
        });
        EXPECT_EQ(Coordinates(out), Coordinates(mesh)) << solver << " " << merge;
        ExpectSameCells(out, mesh);
        EXPECT_EQ(FieldValue(out, "ShockMaxDisplacement"), 0.0);
        EXPECT_TRUE(AllFinite(Values(out->GetPointData()->GetArray(Filter::PotentialArrayName()))));
        EXPECT_TRUE(AllFinite(Values(out->GetCellData()->GetArray(Filter::FlowArrayName()))));
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Errors and degenerate inputs

TEST(PolyDataShockSharpenFilter, BadInputsFailWithAClearError)
{
  auto box = RoundedCube(8);
  struct Case
  {
    const char* what;
    double time;
  };
  for (const Case& c : { Case{ "negative", -1.0 }, Case{ "NaN", std::numeric_limits<double>::quiet_NaN() },
         Case{ "infinite", std::numeric_limits<double>::infinity() } })
  {
    vtkNew<Filter> filter;
    MessageLog log(filter);
    filter->SetInputData(box);
    // A good run first: the measurements of a failed run must not be the old ones.
    filter->SetFlowTime(64.0);
    ASSERT_TRUE(UpdateSucceeds(filter)) << log.Errors;
    ASSERT_EQ(filter->GetLastSolverIterations(), 25);
    filter->SetFlowTime(c.time);
    EXPECT_FALSE(UpdateSucceeds(filter)) << c.what;
    EXPECT_NE(log.Errors.find("FlowTime"), std::string::npos) << c.what << ": " << log.Errors;
    EXPECT_EQ(filter->GetLastSolverIterations(), 0) << c.what;
    EXPECT_EQ(filter->GetLastMaxDisplacement(), 0.0) << c.what;
  }

  // A NaN point coordinate.
  auto broken = DeepCopy(box);
  broken->GetPoints()->SetPoint(10, 0.1, std::numeric_limits<double>::quiet_NaN(), 0.2);
  {
    vtkNew<Filter> filter;
    MessageLog log(filter);
    filter->SetInputData(broken);
    EXPECT_FALSE(UpdateSucceeds(filter));
    EXPECT_NE(log.Errors.find("not finite"), std::string::npos) << log.Errors;
  }

  // A polygon referring to a point that does not exist.
  auto dangling = DeepCopy(box);
  const vtkIdType bad[3] = { 0, 1, dangling->GetNumberOfPoints() + 5 };
  dangling->GetPolys()->InsertNextCell(3, bad);
  {
    vtkNew<Filter> filter;
    MessageLog log(filter);
    filter->SetInputData(dangling);
    EXPECT_FALSE(UpdateSucceeds(filter));
    EXPECT_NE(log.Errors.find("outside"), std::string::npos) << log.Errors;
  }
}

TEST(PolyDataShockSharpenFilter, EmptyAndPolygonFreeInputsPassThroughWithAWarning)
{
  {
    auto empty = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<Filter> filter;
    MessageLog log(filter);
    filter->SetInputData(empty);
    EXPECT_TRUE(UpdateSucceeds(filter));
    EXPECT_TRUE(log.Errors.empty()) << log.Errors;
    EXPECT_NE(log.Warnings.find("empty"), std::string::npos) << log.Warnings;
    EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);
  }

  vtkNew<vtkLineSource> line;
  line->SetPoint1(0.0, 0.0, 0.0);
  line->SetPoint2(1.0, 2.0, 0.5);
  line->SetResolution(30);
  vtkNew<vtkPointSource> cloud;
  cloud->SetNumberOfPoints(50);
  for (vtkPolyDataAlgorithm* source : std::vector<vtkPolyDataAlgorithm*>{ line, cloud })
  {
    vtkNew<Filter> filter;
    MessageLog log(filter);
    filter->SetInputConnection(source->GetOutputPort());
    filter->SetFlowTime(1000.0);
    EXPECT_TRUE(UpdateSucceeds(filter)) << source->GetClassName();
    EXPECT_TRUE(log.Errors.empty()) << log.Errors;
    EXPECT_NE(log.Warnings.find("no polygons"), std::string::npos) << source->GetClassName() << log.Warnings;
    vtkPolyData* in = source->GetOutput();
    vtkPolyData* out = filter->GetOutput();
    EXPECT_EQ(Coordinates(out), Coordinates(in)) << source->GetClassName();
    ExpectSameCells(out, in, source->GetClassName());
  }
}

// ---------------------------------------------------------------------------
// Pipelines, progress, abort, PrintSelf

TEST(PolyDataShockSharpenFilter, ChainedInAPipelineAndReExecutedOnChange)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(40);
  vtkNew<Filter> first;
  first->SetInputConnection(sphere->GetOutputPort());
  first->SetFlowTime(128.0);
  vtkNew<Filter> second;
  second->SetInputConnection(first->GetOutputPort());
  second->SetFlowTime(128.0);
  second->SetSolverIterations(7);
  MessageLog log(second);
  ASSERT_TRUE(UpdateSucceeds(second)) << log.Errors;
  // The measurement arrays of the first pass are replaced, not duplicated.
  vtkFieldData* field = second->GetOutput()->GetFieldData();
  int count = 0;
  for (int k = 0; k < field->GetNumberOfArrays(); ++k)
  {
    count += std::string(field->GetArrayName(k)) == "ShockSolverIterations" ? 1 : 0;
  }
  EXPECT_EQ(count, 1);
  EXPECT_EQ(FieldValue(second->GetOutput(), "ShockSolverIterations"), 7.0);
  EXPECT_EQ(FieldValue(first->GetOutput(), "ShockSolverIterations"), 25.0);

  // A parameter change re-executes.
  const std::vector<double> before = Coordinates(second->GetOutput());
  second->SetScreeningWeight(50.0);
  ASSERT_TRUE(UpdateSucceeds(second)) << log.Errors;
  EXPECT_GT(MaxDifference(before, Coordinates(second->GetOutput())), 0.0);
}

TEST(PolyDataShockSharpenFilter, ReportsProgressAndHonoursAbort)
{
  auto box = RoundedCube(24);
  vtkNew<Filter> filter;
  filter->SetInputData(box);
  filter->SetFlowTime(512.0);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&progress);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* data) {
    static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(data));
  });
  filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
  filter->Update();
  ASSERT_GE(progress.size(), 3u);
  EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
  EXPECT_EQ(progress.back(), 1.0);
  EXPECT_TRUE(std::any_of(progress.begin(), progress.end(), [](double f) { return f > 0.0 && f < 1.0; }));
  ASSERT_GT(MaxDifference(Coordinates(filter->GetOutput()), Coordinates(box)), 1e-3);

  // Abort at the first report from inside the run: the output holds the input.
  struct AbortState
  {
    int callsAfterAbort = 0;
    bool aborted = false;
  } state;
  vtkNew<Filter> aborting;
  aborting->SetInputData(box);
  aborting->SetFlowTime(512.0);
  vtkNew<vtkCallbackCommand> onAbort;
  onAbort->SetClientData(&state);
  onAbort->SetCallback([](vtkObject* caller, unsigned long, void* client, void* data) {
    auto* s = static_cast<AbortState*>(client);
    const double fraction = *static_cast<double*>(data);
    s->callsAfterAbort += (s->aborted && fraction < 1.0) ? 1 : 0;
    if (fraction > 0.0 && fraction < 1.0 && !s->aborted)
    {
      s->aborted = true;
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    }
  });
  aborting->AddObserver(vtkCommand::ProgressEvent, onAbort);
  MessageLog log(aborting);
  aborting->Update();
  ASSERT_TRUE(state.aborted);
  EXPECT_EQ(state.callsAfterAbort, 0);
  EXPECT_TRUE(log.Errors.empty()) << log.Errors;
  vtkPolyData* out = aborting->GetOutput();
  EXPECT_EQ(Coordinates(out), Coordinates(box));
  ExpectSameCells(out, box);
  EXPECT_EQ(aborting->GetLastSolverIterations(), 0);
  EXPECT_EQ(out->GetFieldData()->GetArray("ShockSolverIterations"), nullptr);

  // The flag stays set after the run (this VTK no longer clears it in the executive:
  // without the reset below, the next Update would abort again at the first report
  // and pass the input through). Cleared, the filter sharpens as a fresh one does.
  EXPECT_TRUE(aborting->GetAbortExecute());
  aborting->RemoveObserver(onAbort);
  aborting->SetAbortExecute(0);
  aborting->Modified();
  ASSERT_TRUE(UpdateSucceeds(aborting)) << log.Errors;
  EXPECT_EQ(aborting->GetLastSolverIterations(), 25);
  EXPECT_EQ(MaxDifference(Coordinates(aborting->GetOutput()), Coordinates(filter->GetOutput())), 0.0);
}

TEST(PolyDataShockSharpenFilter, DefaultsClampingAndPrintSelf)
{
  vtkNew<Filter> filter;
  EXPECT_EQ(filter->GetNormalSmoothingPasses(), 0);
  EXPECT_TRUE(filter->GetKeepUnmovedNormals());
  EXPECT_EQ(filter->GetScreeningWeight(), 1.0);
  EXPECT_EQ(filter->GetSolver(), Filter::CONJUGATE_GRADIENT);
  EXPECT_EQ(filter->GetSolverIterations(), 25);
  EXPECT_EQ(filter->GetSolverTolerance(), 1e-6);
  EXPECT_TRUE(filter->GetMergeCoincidentPoints());
  EXPECT_FALSE(filter->GetGenerateSharpenedNormals());
  EXPECT_EQ(filter->GetSampling(), Filter::LINEAR);
  EXPECT_EQ(filter->GetFeatureAngle(), 30.0);
  EXPECT_EQ(filter->GetCurvatureContrast(), 16.0);
  EXPECT_EQ(filter->GetFitTarget(), Filter::CENTRAL_PROJECTION);

  filter->SetCurvatureContrast(-1.0);
  EXPECT_EQ(filter->GetCurvatureContrast(), 0.0);
  filter->SetCurvatureContrast(1e9);
  EXPECT_EQ(filter->GetCurvatureContrast(), 1000.0);

  filter->SetFeatureAngle(-5.0);
  EXPECT_EQ(filter->GetFeatureAngle(), 0.0);
  filter->SetFeatureAngle(500.0);
  EXPECT_EQ(filter->GetFeatureAngle(), 180.0);
  filter->SetFitTarget(9);
  EXPECT_EQ(filter->GetFitTarget(), Filter::CENTRAL_PROJECTION);
  filter->SetFitTarget(-1);
  EXPECT_EQ(filter->GetFitTarget(), Filter::PROJECTION);
  filter->SetScreeningWeight(0.0);
  EXPECT_EQ(filter->GetScreeningWeight(), 1e-6);
  filter->SetSolver(7);
  EXPECT_EQ(filter->GetSolver(), Filter::EXACT);
  filter->SetSolverIterations(-3);
  EXPECT_EQ(filter->GetSolverIterations(), 0);
  filter->SetNormalSmoothingPasses(5000);
  EXPECT_EQ(filter->GetNormalSmoothingPasses(), 100);
  filter->SetSolverTolerance(2.0);
  EXPECT_EQ(filter->GetSolverTolerance(), 1.0);

  filter->SetNormalSmoothingPasses(3);
  filter->SetScreeningWeight(2.5);
  filter->SetSolverToConjugateGradientTolerance();
  filter->SetSolverIterations(40);
  filter->SetSolverTolerance(1e-7);
  filter->MergeCoincidentPointsOff();
  filter->GenerateSharpenedNormalsOn();
  filter->SetFlowTime(123.25);
  filter->SetFeatureAngle(42.5);
  filter->SetCurvatureContrast(3.5);
  filter->SetFitTargetToShear();
  std::ostringstream os;
  filter->Print(os);
  for (const char* key : { "vtkPolyDataShockSharpenFilter", "FlowTime: 123.25", "NormalSmoothingPasses: 3",
         "ScreeningWeight: 2.5", "Solver: ConjugateGradientTolerance", "SolverIterations: 40",
         "SolverTolerance: 1e-07", "MergeCoincidentPoints: Off", "GenerateSharpenedNormals: On",
         "LastSolverResidual", "LastMaxDisplacement", "FeatureAngle: 42.5", "CurvatureContrast: 3.5", "FitTarget: Shear",
         "LastRepeatedTriangles", "LastDegenerateTriangles", "LastFeatureEdges", "LastGhostLevels: 0",
         "LastRingAttempts: 0" })
  {
    EXPECT_NE(os.str().find(key), std::string::npos) << key << "\n" << os.str();
  }
  filter->SetSolverToExact();
  filter->SetFitTargetToCentralProjection();
  std::ostringstream exact;
  filter->Print(exact);
  EXPECT_NE(exact.str().find("Solver: Exact"), std::string::npos) << exact.str();
  EXPECT_NE(exact.str().find("FitTarget: CentralProjection"), std::string::npos) << exact.str();
}

} // namespace
