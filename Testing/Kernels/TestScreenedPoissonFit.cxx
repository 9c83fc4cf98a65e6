// Unit tests of the screened Poisson fit of positions to target normals
// (Prada and Kazhdan 2015, section 4.1): properties that must hold on any mesh,
// on synthetic meshes generated here (TestScreenedPoissonFit.h), and the refused
// arguments (thread counts and row orders: TestScreenedPoissonFitThreads.cxx;
// an independent solution: TestScreenedPoissonFitReference.cxx).
#include "TestScreenedPoissonFit.h"

namespace
{

TEST(ScreenedPoissonFit, OwnNormalsKeepThePositions)
{
  for (const Mesh& m : { Icosphere(3), FlatGrid(21, 17), Box(6) })
  {
    const TriangleMesh mesh = Build(m);
    const auto targets = OwnNormals(mesh);
    for (FitSolver solver : AllSolvers)
    {
      FitReport report;
      const auto fitted = Fit(mesh, targets, WithSolver(solver), &report);
      EXPECT_LT(MaxDifference(fitted, m.points), 1e-12) << "solver " << static_cast<int>(solver);
      EXPECT_LT(report.residual, 1e-12);
      EXPECT_TRUE(report.converged);
      EXPECT_EQ(report.invalidTargets, 0);
    }
  }
}

TEST(ScreenedPoissonFit, TranslationAndUniformScaleGiveTheTransformedFit)
{
  const Mesh m = Icosphere(3);
  const TriangleMesh mesh = Build(m);
  const auto targets = PerturbedNormals(mesh, 0.5);
  const double scale = 37.5;
  const double shift[3] = { 1000.0, -20.0, 3.5 };
  Mesh moved = m;
  for (size_t i = 0; i < moved.points.size(); ++i)
  {
    moved.points[i] = scale * m.points[i] + shift[i % 3];
  }
  const TriangleMesh movedMesh = Build(moved);
  for (FitSolver solver : AllSolvers)
  {
    const auto fitted = Fit(mesh, targets, WithSolver(solver));
    const auto movedFit = Fit(movedMesh, targets, WithSolver(solver));
    EXPECT_GT(MaxDifference(fitted, m.points), 1e-2) << "the targets must move the mesh";
    double worst = 0.0;
    for (size_t i = 0; i < fitted.size(); ++i)
    {
      worst = std::max(worst, std::abs(movedFit[i] - (scale * fitted[i] + shift[i % 3])));
    }
    EXPECT_LT(worst / scale, 1e-10) << "solver " << static_cast<int>(solver);
  }
}

TEST(ScreenedPoissonFit, FlatGridBendsTowardsTheTargetNormals)
{
  // Targets of the roof z = 0.3 min(x, 1 - x): a crease along x = 0.5.
  const Mesh m = FlatGrid(41, 33);
  const TriangleMesh mesh = Build(m);
  std::vector<double> targets;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double slope = mesh.Centroid(f)[0] < 0.5 ? 0.3 : -0.3;
    const double length = std::sqrt(1.0 + slope * slope);
    targets.insert(targets.end(), { -slope / length, 0.0, 1.0 / length });
  }
  const double before = MeanNormalError(m, m.points, targets);
  for (FitSolver solver : AllSolvers)
  {
    // The whole grid bends: a displacement smoother than any drift radius,
    // which step 5 takes away by design (TheDriftIsRemovedAndTheCreaseKept).
    FitParameters p = WithSolver(solver);
    p.driftRadius = 0.0;
    const auto fitted = Fit(mesh, targets, p);
    const double after = MeanNormalError(m, fitted, targets);
    EXPECT_LT(after, 0.1 * before) << "solver " << static_cast<int>(solver);
    // The ridge rises above the sides.
    const auto z = [&](std::int64_t p) { return fitted[static_cast<size_t>(3 * p + 2)]; };
    EXPECT_GT(z(16 * 41 + 20), z(16 * 41 + 2));
    EXPECT_GT(z(16 * 41 + 20), z(16 * 41 + 38));
  }
}

TEST(ScreenedPoissonFit, RoundedBoxSharpensTowardsTheCube)
{
  std::vector<double> cubeNormals;
  Mesh m = Box(12, &cubeNormals);
  for (size_t p = 0; p < m.points.size(); p += 3)
  {
    const double r = std::sqrt(m.points[p] * m.points[p] + m.points[p + 1] * m.points[p + 1] +
      m.points[p + 2] * m.points[p + 2]);
    for (int k = 0; k < 3; ++k)
    {
      m.points[p + k] = 0.6 * m.points[p + k] + 0.4 * m.points[p + k] / r;
    }
  }
  const TriangleMesh mesh = Build(m);
  const double before = MeanNormalError(m, m.points, cubeNormals);
  for (FitSolver solver : AllSolvers)
  {
    FitParameters paper = WithSolver(solver);
    paper.anchorWeight = 0.0;
    paper.driftRadius = 0.0;
    EXPECT_LT(MeanNormalError(m, Fit(mesh, cubeNormals, paper), cubeNormals), 0.2 * before)
      << "solver " << static_cast<int>(solver);
    // The anchor holds the points of the faces' middles, which the blend
    // bent by less than the anchor angle, so they flatten a little less.
    // (The blend bends the whole box: no drift radius fits inside it.)
    FitParameters anchored = WithSolver(solver);
    anchored.driftRadius = 0.0;
    EXPECT_LT(MeanNormalError(m, Fit(mesh, cubeNormals, anchored), cubeNormals), 0.25 * before)
      << "solver " << static_cast<int>(solver);
  }
}

/// The roof of FlatGridBendsTowardsTheTargetNormals over 0.3 < x < 0.7 only: the rest keeps its own normal.
std::vector<double> RoofInTheMiddle(const TriangleMesh& mesh)
{
  std::vector<double> targets;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double x = mesh.Centroid(f)[0];
    const double slope = x < 0.3 || x > 0.7 ? 0.0 : (x < 0.5 ? 0.3 : -0.3);
    const double length = std::sqrt(1.0 + slope * slope);
    targets.insert(targets.end(), { -slope / length, 0.0, 1.0 / length });
  }
  return targets;
}

TEST(ScreenedPoissonFit, TheAnchorHoldsThePointsWhoseTrianglesDidNotTurn)
{
  // Outside 0.3 < x < 0.7 no triangle is asked to turn. The paper's fit (anchor
  // weight 0) moves those points too: the screening alone holds them. The
  // anchor holds them closer, and the roof still rises.
  const Mesh m = FlatGrid(41, 33);
  const TriangleMesh mesh = Build(m);
  const auto targets = RoofInTheMiddle(mesh);
  auto farMotion = [&](const std::vector<double>& fitted) {
    double worst = 0.0;
    for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
    {
      const double x = m.points[static_cast<size_t>(3 * p)];
      if (x < 0.25 || x > 0.75) // every triangle around p keeps its normal
      {
        for (int k = 0; k < 3; ++k)
        {
          worst = std::max(worst, std::abs(fitted[static_cast<size_t>(3 * p + k)] - m.points[static_cast<size_t>(3 * p + k)]));
        }
      }
    }
    return worst;
  };
  auto rise = [&](const std::vector<double>& fitted) {
    return fitted[static_cast<size_t>(3 * (16 * 41 + 20) + 2)] - fitted[static_cast<size_t>(3 * (16 * 41 + 12) + 2)];
  };
  for (FitSolver solver : AllSolvers)
  {
    FitParameters paper = WithSolver(solver);
    paper.anchorWeight = 0.0;
    paper.driftRadius = 0.0;
    const auto unanchored = Fit(mesh, targets, paper);
    FitParameters anchor = WithSolver(solver); // the defaults anchor
    anchor.driftRadius = 0.0;                  // (the anchor alone: the roof is 16 edges wide)
    const auto anchored = Fit(mesh, targets, anchor);
    EXPECT_GT(farMotion(unanchored), 1e-3) << "the paper's fit moves the untouched parts";
    EXPECT_LT(farMotion(anchored), 0.5 * farMotion(unanchored)) << "solver " << static_cast<int>(solver);
    EXPECT_GT(rise(anchored), 0.5 * rise(unanchored));
    EXPECT_GT(rise(unanchored), 0.02);
    // Either zero is the paper's fit.
    FitParameters noAngle = WithSolver(solver);
    noAngle.anchorAngle = 0.0;
    noAngle.driftRadius = 0.0;
    EXPECT_EQ(Fit(mesh, targets, noAngle), unanchored);
  }
}

TEST(ScreenedPoissonFit, TheDriftIsRemovedAndTheCreaseKept)
{
  // A narrow roof (0.45 < x < 0.55, four edges wide) on a flat grid. Without
  // step 5 the ridge rises and the mean height with it; with it the lumped
  // mass's mean displacement is 0 (the rows of S sum to 0, so the removal takes
  // exactly the area-weighted mean), and the ridge still stands out.
  const Mesh m = FlatGrid(41, 33);
  const TriangleMesh mesh = Build(m);
  std::vector<double> targets;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double x = mesh.Centroid(f)[0];
    const double slope = x < 0.45 || x > 0.55 ? 0.0 : (x < 0.5 ? 0.3 : -0.3);
    const double length = std::sqrt(1.0 + slope * slope);
    targets.insert(targets.end(), { -slope / length, 0.0, 1.0 / length });
  }
  std::vector<double> lumped(static_cast<size_t>(mesh.NumberOfPoints()), 0.0);
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      lumped[static_cast<size_t>(mesh.Corners(f)[c])] += mesh.Area(f) / 3.0;
    }
  }
  auto meanMove = [&](const std::vector<double>& fitted, int k) {
    double sum = 0.0;
    for (size_t p = 0; p < lumped.size(); ++p)
    {
      sum += lumped[p] * (fitted[3 * p + k] - m.points[3 * p + k]);
    }
    return sum;
  };
  auto ridge = [&](const std::vector<double>& fitted) { // the ridge over a point 8 edges away
    return fitted[static_cast<size_t>(3 * (16 * 41 + 20) + 2)] - fitted[static_cast<size_t>(3 * (16 * 41 + 12) + 2)];
  };
  for (FitSolver solver : AllSolvers)
  {
    FitParameters kept = WithSolver(solver);
    kept.driftRadius = 0.0;
    const auto drifting = Fit(mesh, targets, kept);
    FitParameters removed = WithSolver(solver);
    removed.driftRadius = 4.0;
    removed.solver = solver == FitSolver::ConjugateGradient ? FitSolver::ConjugateGradientTolerance : solver;
    removed.tolerance = 1e-12;
    const auto fitted = Fit(mesh, targets, removed);
    EXPECT_GT(meanMove(drifting, 2), 1e-4) << "solver " << static_cast<int>(solver);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(meanMove(fitted, k), 0.0, 1e-9) << "solver " << static_cast<int>(solver) << ", coordinate " << k;
    }
    EXPECT_GT(ridge(drifting), 0.01);
    EXPECT_GT(ridge(fitted), 0.7 * ridge(drifting)) << "solver " << static_cast<int>(solver);
    EXPECT_GT(MaxDifference(fitted, drifting), 1e-3);
  }
  // A wider radius takes away less of the roof's own shape, leaving the fit
  // without step 5 shifted more nearly as a whole.
  FitParameters withoutDrift;
  withoutDrift.driftRadius = 0.0;
  FitParameters wide;
  wide.driftRadius = 40.0;
  FitParameters narrow;
  narrow.driftRadius = 4.0;
  const auto drifting = Fit(mesh, targets, withoutDrift);
  EXPECT_LT(std::abs(ridge(Fit(mesh, targets, wide)) - ridge(drifting)),
    std::abs(ridge(Fit(mesh, targets, narrow)) - ridge(drifting)));
  // On by default, with the radius of 8 edges.
  FitParameters eight;
  eight.driftRadius = 8.0;
  EXPECT_EQ(FitParameters().driftRadius, 8.0);
  EXPECT_EQ(Fit(mesh, targets, FitParameters()), Fit(mesh, targets, eight));
  EXPECT_GT(MaxDifference(Fit(mesh, targets, FitParameters()), drifting), 1e-3);
}

TEST(ScreenedPoissonFit, AKeptSystemGivesEachFitItsOwnAnchor)
{
  // The anchor is written into the kept system's diagonal: a fit with another
  // anchor (or none) on the same system equals a fresh fit, in any order. So
  // does a fit with another drift radius (step 5 keeps a system of its own).
  const Mesh m = FlatGrid(31, 23);
  const TriangleMesh mesh = Build(m);
  const auto roof = RoofInTheMiddle(mesh);
  const auto perturbed = PerturbedNormals(mesh, 0.05);
  FitParameters paper;
  paper.anchorWeight = 0.0;
  paper.driftRadius = 0.0;
  FitParameters strong;
  strong.anchorWeight = 10.0;
  strong.anchorAngle = 5.0;
  FitParameters drift;
  drift.driftRadius = 3.0;
  FitParameters wider;
  wider.driftRadius = 6.0;
  const FitParameters runs[] = { FitParameters(), paper, strong, drift, FitParameters(), wider, drift, paper };
  const std::vector<double>* targetsOf[] = { &roof, &roof, &perturbed, &roof, &perturbed, &roof, &perturbed, &roof };
  FitSystem kept;
  for (int run = 0; run < 8; ++run)
  {
    std::vector<double> positions(static_cast<size_t>(3 * mesh.NumberOfPoints()));
    FitReport report;
    ASSERT_TRUE(FitPositionsToNormals(mesh, targetsOf[run]->data(), positions.data(), runs[run], &report, &kept).Ok());
    EXPECT_EQ(report.reusedSystem, run > 0);
    EXPECT_EQ(positions, Fit(mesh, *targetsOf[run], runs[run])) << "run " << run;
  }
}

TEST(ScreenedPoissonFit, LargeScreeningWeightKeepsThePositions)
{
  const Mesh m = Icosphere(3);
  const TriangleMesh mesh = Build(m);
  const auto targets = PerturbedNormals(mesh, 0.5);
  double previous = std::numeric_limits<double>::infinity();
  for (double weight : { 1.0, 1e2, 1e4, 1e8, 1e300 })
  {
    FitParameters p = WithSolver(FitSolver::Exact);
    p.screeningWeight = weight;
    const auto fitted = Fit(mesh, targets, p);
    const double moved = MaxDifference(fitted, m.points);
    EXPECT_LT(moved, previous) << "weight " << weight;
    previous = moved;
  }
  EXPECT_LT(previous, 1e-12);
}

TEST(ScreenedPoissonFit, ResidualsOfTheSolvers)
{
  const Mesh m = Icosphere(4);
  const TriangleMesh mesh = Build(m);
  const auto targets = PerturbedNormals(mesh, 0.5);

  FitReport exact;
  Fit(mesh, targets, WithSolver(FitSolver::Exact), &exact);
  EXPECT_LT(exact.residual, 1e-12);
  EXPECT_TRUE(exact.converged);
  EXPECT_EQ(exact.iterations, 0);

  double previous = std::numeric_limits<double>::infinity();
  for (int iterations : { 2, 10, 25, 100, 400 })
  {
    FitParameters p;
    p.iterations = iterations;
    FitReport report;
    Fit(mesh, targets, p, &report);
    EXPECT_EQ(report.iterations, iterations);
    EXPECT_LT(report.residual, previous) << iterations << " iterations";
    previous = report.residual;
  }

  FitParameters p = WithSolver(FitSolver::ConjugateGradientTolerance);
  p.tolerance = 1e-9;
  FitReport report;
  const auto fitted = Fit(mesh, targets, p, &report);
  EXPECT_TRUE(report.converged);
  EXPECT_LE(report.residual, 1e-9);
  EXPECT_GT(report.iterations, 0);
  EXPECT_LT(report.iterations, p.maxIterations);
  EXPECT_LT(MaxDifference(fitted, Fit(mesh, targets, WithSolver(FitSolver::Exact))), 1e-7);

  p.maxIterations = 3;
  Fit(mesh, targets, p, &report);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 3);
}

TEST(ScreenedPoissonFit, UnusedPointsKeepTheirPositionsExactly)
{
  Mesh m = Icosphere(2);
  const std::int64_t sphere = m.NumberOfPoints();
  // Two isolated points and a point used only by a degenerate (repeated-id) triangle.
  m.points.insert(m.points.end(), { 5.0, 6.0, 7.0, -3.25, 0.1, 1e-3, 0.3, 0.2, 0.1 });
  m.triangles.insert(m.triangles.end(), { sphere + 2, sphere + 2, 0 });
  const TriangleMesh mesh = Build(m);
  auto targets = PerturbedNormals(mesh, 0.5);
  for (FitSolver solver : AllSolvers)
  {
    const auto fitted = Fit(mesh, targets, WithSolver(solver));
    for (std::int64_t p = sphere; p < m.NumberOfPoints(); ++p)
    {
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(fitted[3 * p + k], m.points[3 * p + k]);
      }
    }
    EXPECT_GT(MaxDifference(fitted, m.points), 1e-2);
  }
}

TEST(ScreenedPoissonFit, DegenerateTrianglesAndInvalidTargetsGiveNoNaN)
{
  Mesh m = FlatGrid(12, 12);
  const std::int64_t np = m.NumberOfPoints();
  // Collinear corners, repeated ids, and a sliver whose corners coincide in space.
  m.points.insert(m.points.end(), { 0.5, 0.5, 0.0, 0.5, 0.5, 0.0 });
  m.triangles.insert(m.triangles.end(), { 0, 1, 2, 3, 3, 4, 5, np, np + 1, 0, 0, 0 });
  const TriangleMesh mesh = Build(m);
  const std::int64_t nt = mesh.NumberOfTriangles();
  ASSERT_TRUE(mesh.Degenerate(nt - 1) && mesh.Degenerate(nt - 2) && mesh.Degenerate(nt - 3) &&
    mesh.Degenerate(nt - 4));

  std::vector<double> targets;
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const double tilt = std::sin(7.0 * mesh.Centroid(f)[0]);
    targets.insert(targets.end(), { 0.3 * tilt, 0.1, 1.0 });
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  // Invalid targets on three good triangles, and NaN on the degenerate ones (not counted).
  for (int k = 0; k < 3; ++k)
  {
    targets[3 * 0 + k] = nan;
    targets[3 * 1 + k] = 0.0;
    targets[static_cast<size_t>(3 * (nt - 1 - 0) + k)] = nan;
    targets[static_cast<size_t>(3 * (nt - 1 - 3) + k)] = nan;
  }
  targets[3 * 2] = inf;
  for (FitSolver solver : AllSolvers)
  {
    FitReport report;
    const auto fitted = Fit(mesh, targets, WithSolver(solver), &report);
    EXPECT_TRUE(AllFinite(fitted));
    EXPECT_EQ(report.invalidTargets, 3);
    EXPECT_TRUE(std::isfinite(report.residual));
  }

  // A mesh with no area at all keeps every position.
  Mesh flat;
  flat.points = { 0, 0, 0, 1, 0, 0, 2, 0, 0 };
  flat.triangles = { 0, 1, 2 };
  const TriangleMesh line = Build(flat);
  EXPECT_EQ(Fit(line, { nan, nan, nan }), flat.points);
}

TEST(ScreenedPoissonFit, InvalidArgumentsAreRejectedAndKeepThePositions)
{
  const Mesh m = Icosphere(1);
  const TriangleMesh mesh = Build(m);
  const auto targets = PerturbedNormals(mesh, 0.5);
  std::vector<double> positions(m.points.size(), -1.0);
  FitParameters p;
  for (double weight : { 0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
         std::numeric_limits<double>::infinity() })
  {
    p.screeningWeight = weight;
    EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), positions.data(), p).Ok());
    EXPECT_EQ(positions, m.points);
  }
  p = FitParameters{};
  p.iterations = -1;
  EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), positions.data(), p).Ok());
  p = FitParameters{};
  p.tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), positions.data(), p).Ok());
  for (double weight : { -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity() })
  {
    p = FitParameters{};
    p.anchorWeight = weight;
    EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), positions.data(), p).Ok());
  }
  for (double angle : { -1.0, 180.5, std::numeric_limits<double>::quiet_NaN() })
  {
    p = FitParameters{};
    p.anchorAngle = angle;
    EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), positions.data(), p).Ok());
  }
  EXPECT_EQ(positions, m.points);
  p = FitParameters{};
  p.solver = static_cast<FitSolver>(7);
  EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), positions.data(), p).Ok());
  EXPECT_FALSE(FitPositionsToNormals(mesh, nullptr, positions.data(), FitParameters{}).Ok());
  EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), nullptr, FitParameters{}).Ok());
}

} // namespace
