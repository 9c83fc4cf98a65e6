// Unit tests of the screened Poisson fit of positions to target normals: one,
// two and three threads, nested parallel regions and the rows in the mesh's
// order give the same fit (the other tests: TestScreenedPoissonFit.cxx,
// TestScreenedPoissonFitReference.cxx).
#include "TestScreenedPoissonFit.h"

namespace
{

TEST(ScreenedPoissonFit, OneAndTwoThreadsGiveIdenticalResults)
{
  // Large enough (40962 points) for the fit to use two threads.
  const Mesh m = Icosphere(6);
  const TriangleMesh mesh = Build(m);
  const auto targets = PerturbedNormals(mesh, 0.5);
  for (FitSolver solver : AllSolvers)
  {
    FitParameters one = WithSolver(solver);
    one.maxIterations = 60;
    one.numberOfThreads = 1;
    FitParameters two = one;
    two.numberOfThreads = 2;
    EXPECT_EQ(Fit(mesh, targets, one), Fit(mesh, targets, two))
      << "solver " << static_cast<int>(solver);
  }
}

TEST(ScreenedPoissonFit, RowsInTheMeshsOrderGiveTheSameFit)
{
  // Rows numbered breadth-first (the default) or in the points' own numbering
  // (rowsInMeshOrder, for meshes renumbered for locality): the same system in
  // another order, so the same fit up to rounding; identical over thread counts;
  // a kept system built for one order is not reused for the other.
  const Mesh m = Icosphere(6);
  const TriangleMesh mesh = Build(m);
  const auto targets = PerturbedNormals(mesh, 0.5);
  for (FitSolver solver : AllSolvers)
  {
    FitParameters breadthFirst = WithSolver(solver);
    breadthFirst.maxIterations = 60;
    FitParameters meshOrder = breadthFirst;
    meshOrder.rowsInMeshOrder = true;
    const std::vector<double> a = Fit(mesh, targets, breadthFirst);
    const std::vector<double> b = Fit(mesh, targets, meshOrder);
    double difference = 0.0;
    double moved = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
    {
      difference = std::max(difference, std::abs(a[i] - b[i]));
      moved = std::max(moved, std::abs(a[i] - m.points[i]));
    }
    EXPECT_LE(difference, 1e-10) << "solver " << static_cast<int>(solver);
    EXPECT_GT(moved, 1e-4) << "solver " << static_cast<int>(solver); // the fit did something
    FitParameters one = meshOrder;
    one.numberOfThreads = 1;
    FitParameters two = meshOrder;
    two.numberOfThreads = 2;
    EXPECT_EQ(Fit(mesh, targets, one), Fit(mesh, targets, two)) << "solver " << static_cast<int>(solver);
  }
  FitSystem kept;
  std::vector<double> positions(m.points.size());
  FitReport report;
  FitParameters meshOrder;
  meshOrder.rowsInMeshOrder = true;
  ASSERT_TRUE(FitPositionsToNormals(mesh, targets.data(), positions.data(), meshOrder, &report, &kept).Ok());
  EXPECT_FALSE(report.reusedSystem);
  ASSERT_TRUE(FitPositionsToNormals(mesh, targets.data(), positions.data(), meshOrder, &report, &kept).Ok());
  EXPECT_TRUE(report.reusedSystem);
  ASSERT_TRUE(FitPositionsToNormals(mesh, targets.data(), positions.data(), FitParameters(), &report, &kept).Ok());
  EXPECT_FALSE(report.reusedSystem);
}

TEST(ScreenedPoissonFit, ThreadCountsAgreeWhenRowsReadFarRows)
{
  // The conjugate gradients update each direction row just before the rows
  // that read it; a row that reads rows of every other thread's range must
  // still see them updated. A cone whose apex joins 60000 rim points (its row
  // reads every rim row, every rim row reads it), then a grid whose rows read
  // nearby rows only: enough points for three threads.
  Mesh m;
  const int rim = 60000;
  m.points = { 0.0, 0.0, 1.0 };
  for (int i = 0; i < rim; ++i)
  {
    const double angle = 2.0 * 3.14159265358979323846 * i / rim;
    m.points.insert(m.points.end(), { std::cos(angle), std::sin(angle), 0.1 * std::sin(7.0 * angle) });
  }
  for (std::int64_t i = 0; i < rim; ++i)
  {
    m.triangles.insert(m.triangles.end(), { 0, 1 + i, 1 + (i + 1) % rim });
  }
  const Mesh grid = FlatGrid(150, 150);
  const std::int64_t offset = m.NumberOfPoints();
  m.points.insert(m.points.end(), grid.points.begin(), grid.points.end());
  for (std::int64_t id : grid.triangles)
  {
    m.triangles.push_back(offset + id);
  }
  const TriangleMesh mesh = Build(m);
  const auto targets = PerturbedNormals(mesh, 0.5);
  for (FitSolver solver : { FitSolver::ConjugateGradient, FitSolver::ConjugateGradientTolerance })
  {
    FitParameters one = WithSolver(solver);
    one.maxIterations = 40;
    one.numberOfThreads = 1;
    FitReport report;
    const auto reference = Fit(mesh, targets, one, &report);
    EXPECT_GT(report.iterations, 10) << "solver " << static_cast<int>(solver);
    for (int threads : { 2, 3 })
    {
      FitParameters more = one;
      more.numberOfThreads = threads;
      EXPECT_EQ(reference, Fit(mesh, targets, more))
        << "solver " << static_cast<int>(solver) << ", " << threads << " threads";
    }
    // Inside another parallel region the fit may get fewer threads than it
    // asked for (nested regions are off by default): still the same result.
    FitParameters three = one;
    three.numberOfThreads = 3;
    std::vector<double> nested;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
      nested = Fit(mesh, targets, three);
    }
    EXPECT_EQ(reference, nested) << "solver " << static_cast<int>(solver) << ", nested";
  }
}

} // namespace
