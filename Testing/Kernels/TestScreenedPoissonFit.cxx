// Unit tests of the screened Poisson fit of positions to target normals
// (Prada and Kazhdan 2015, section 4.1): properties that must hold on any mesh,
// on synthetic meshes generated here.
#include "ScreenedPoissonFit.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace
{
using namespace shock;

struct Mesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  std::int64_t NumberOfPoints() const { return static_cast<std::int64_t>(this->points.size() / 3); }
};

TriangleMesh Build(const Mesh& m, int threads = 0)
{
  TriangleMesh mesh;
  const Status status = mesh.Build({ m.NumberOfPoints(), m.points.data(),
                                     static_cast<std::int64_t>(m.triangles.size() / 3),
                                     m.triangles.data() },
    threads);
  EXPECT_TRUE(status.Ok()) << status.error;
  return mesh;
}

/// Unit sphere: an icosahedron subdivided `levels` times (10 * 4^levels + 2 points).
Mesh Icosphere(int levels)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.points = { -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, t,
    0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1 };
  m.triangles = { 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10,
    7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6,
    7, 9, 8, 1 };
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> midpoints;
    auto midpoint = [&](std::int64_t a, std::int64_t b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoints.find(key);
      if (found != midpoints.end())
      {
        return found->second;
      }
      const std::int64_t id = m.NumberOfPoints();
      for (int k = 0; k < 3; ++k)
      {
        m.points.push_back(0.5 * (m.points[3 * a + k] + m.points[3 * b + k]));
      }
      midpoints.emplace(key, id);
      return id;
    };
    std::vector<std::int64_t> finer;
    for (size_t f = 0; f < m.triangles.size(); f += 3)
    {
      const std::int64_t a = m.triangles[f], b = m.triangles[f + 1], c = m.triangles[f + 2];
      const std::int64_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), { a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca });
    }
    m.triangles = std::move(finer);
  }
  for (size_t p = 0; p < m.points.size(); p += 3)
  {
    const double r = std::sqrt(m.points[p] * m.points[p] + m.points[p + 1] * m.points[p + 1] +
      m.points[p + 2] * m.points[p + 2]);
    for (int k = 0; k < 3; ++k)
    {
      m.points[p + k] /= r;
    }
  }
  return m;
}

/// Flat nx x ny grid of points on [0,1]^2 at z = 0, normals +z.
Mesh FlatGrid(int nx, int ny)
{
  Mesh m;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      m.points.insert(m.points.end(), { i / (nx - 1.0), j / (ny - 1.0), 0.0 });
    }
  }
  for (int j = 0; j + 1 < ny; ++j)
  {
    for (int i = 0; i + 1 < nx; ++i)
    {
      const std::int64_t a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      m.triangles.insert(m.triangles.end(), { a, b, c, a, c, d });
    }
  }
  return m;
}

/// Surface of the cube [-1,1]^3, n x n squares per face, welded, outward normals;
/// faceNormals receives the outward axis normal of each triangle.
Mesh Box(int n, std::vector<double>* faceNormals = nullptr)
{
  Mesh m;
  std::map<std::array<int, 3>, std::int64_t> ids;
  auto point = [&](const std::array<int, 3>& lattice) {
    const auto found = ids.find(lattice);
    if (found != ids.end())
    {
      return found->second;
    }
    const std::int64_t id = m.NumberOfPoints();
    for (int k = 0; k < 3; ++k)
    {
      m.points.push_back(2.0 * lattice[k] / n - 1.0);
    }
    ids.emplace(lattice, id);
    return id;
  };
  for (int a = 0; a < 3; ++a)
  {
    for (int side : { -1, 1 })
    {
      const int b = (a + 1) % 3, c = (a + 2) % 3; // e_b x e_c = e_a
      for (int i = 0; i < n; ++i)
      {
        for (int j = 0; j < n; ++j)
        {
          std::int64_t q[4];
          const int corners[4][2] = { { i, j }, { i + 1, j }, { i + 1, j + 1 }, { i, j + 1 } };
          for (int k = 0; k < 4; ++k)
          {
            std::array<int, 3> lattice;
            lattice[a] = side > 0 ? n : 0;
            lattice[b] = corners[k][0];
            lattice[c] = corners[k][1];
            q[k] = point(lattice);
          }
          if (side > 0)
          {
            m.triangles.insert(m.triangles.end(), { q[0], q[1], q[2], q[0], q[2], q[3] });
          }
          else
          {
            m.triangles.insert(m.triangles.end(), { q[0], q[2], q[1], q[0], q[3], q[2] });
          }
          if (faceNormals)
          {
            for (int t = 0; t < 2; ++t)
            {
              for (int k = 0; k < 3; ++k)
              {
                faceNormals->push_back(k == a ? side : 0.0);
              }
            }
          }
        }
      }
    }
  }
  return m;
}

std::vector<double> OwnNormals(const TriangleMesh& mesh)
{
  std::vector<double> normals;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    normals.insert(normals.end(), mesh.Normal(f), mesh.Normal(f) + 3);
  }
  return normals;
}

/// Smoothly perturbed unit normals: a target field that differs from the mesh's.
std::vector<double> PerturbedNormals(const TriangleMesh& mesh, double amount)
{
  std::vector<double> normals;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double* n = mesh.Normal(f);
    const shock::Vec3 c = mesh.Centroid(f);
    double t[3] = { n[0] + amount * std::sin(3.0 * c[1]), n[1] + amount * std::cos(2.0 * c[2]),
      n[2] + amount * std::sin(5.0 * c[0]) };
    const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (double v : t)
    {
      normals.push_back(v / length);
    }
  }
  return normals;
}

std::vector<double> Fit(const TriangleMesh& mesh, const std::vector<double>& targets,
  const FitParameters& parameters = {}, FitReport* report = nullptr)
{
  std::vector<double> positions(static_cast<size_t>(3 * mesh.NumberOfPoints()));
  const Status status =
    FitPositionsToNormals(mesh, targets.data(), positions.data(), parameters, report);
  EXPECT_TRUE(status.Ok()) << status.error;
  return positions;
}

FitParameters WithSolver(FitSolver solver)
{
  FitParameters p;
  p.solver = solver;
  return p;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst;
}

bool AllFinite(const std::vector<double>& values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

/// Area-weighted mean angle (radians) between the normals of `m` with new positions and targets.
double MeanNormalError(const Mesh& m, const std::vector<double>& positions,
  const std::vector<double>& targets)
{
  Mesh moved = m;
  moved.points = positions;
  const TriangleMesh mesh = Build(moved);
  double sum = 0.0, area = 0.0;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double* n = mesh.Normal(f);
    const double* t = &targets[static_cast<size_t>(3 * f)];
    const double cosine = std::clamp(n[0] * t[0] + n[1] * t[1] + n[2] * t[2], -1.0, 1.0);
    sum += mesh.Area(f) * std::acos(cosine);
    area += mesh.Area(f);
  }
  return sum / area;
}

const FitSolver AllSolvers[] = { FitSolver::ConjugateGradient,
  FitSolver::ConjugateGradientTolerance, FitSolver::Exact };

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
    const auto fitted = Fit(mesh, targets, WithSolver(solver));
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
    const auto fitted = Fit(mesh, cubeNormals, WithSolver(solver));
    EXPECT_LT(MeanNormalError(m, fitted, cubeNormals), 0.2 * before)
      << "solver " << static_cast<int>(solver);
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

using Vec3 = std::array<double, 3>;
Vec3 Sub(const Vec3& a, const Vec3& b) { return { a[0] - b[0], a[1] - b[1], a[2] - b[2] }; }
double Dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

/// Solve a small dense system by Gaussian elimination with partial pivoting.
std::vector<double> SolveDense(std::vector<std::vector<double>> a, std::vector<double> b)
{
  const size_t n = b.size();
  for (size_t c = 0; c < n; ++c)
  {
    size_t pivot = c;
    for (size_t r = c + 1; r < n; ++r)
    {
      pivot = std::abs(a[r][c]) > std::abs(a[pivot][c]) ? r : pivot;
    }
    std::swap(a[c], a[pivot]);
    std::swap(b[c], b[pivot]);
    for (size_t r = c + 1; r < n; ++r)
    {
      const double factor = a[r][c] / a[c][c];
      for (size_t k = c; k < n; ++k)
      {
        a[r][k] -= factor * a[c][k];
      }
      b[r] -= factor * b[c];
    }
  }
  std::vector<double> x(n);
  for (size_t r = n; r-- > 0;)
  {
    double sum = b[r];
    for (size_t k = r + 1; k < n; ++k)
    {
      sum -= a[r][k] * x[k];
    }
    x[r] = sum / a[r][r];
  }
  return x;
}

TEST(ScreenedPoissonFit, MatchesAnIndependentCotangentSolution)
{
  // Two random triangles sharing an edge, random targets: the exact fit must equal
  // the solution of the system built here from the classical cotangent formula,
  // barycentric gradients from the Gram matrix, and the unit-area screening weight,
  // for each fit target T: the target Jacobian is T J (J the position's Jacobian),
  // with T = I - N N^T (the paper's projection), the rotation about n x N by the
  // angle between them (axis-angle form), or (I - n N^T / c) / c^p for the shear
  // (p = 0) and the central projection (p = 1), c = <n, N> (tilts below 45 degrees).
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 80; ++trial)
  {
    const FitTarget target = static_cast<FitTarget>(trial % 4);
    Mesh m;
    for (int i = 0; i < 12; ++i)
    {
      m.points.push_back(3.0 * uniform(random));
    }
    m.triangles = { 0, 1, 2, 0, 2, 3 };
    const TriangleMesh mesh = Build(m);
    ASSERT_FALSE(mesh.Degenerate(0) || mesh.Degenerate(1));
    // Targets tilted from the triangles' normals by less than 45 degrees.
    std::vector<double> targets;
    for (int f = 0; f < 2; ++f)
    {
      for (int k = 0; k < 3; ++k)
      {
        targets.push_back(mesh.Normal(f)[k] + 0.4 * uniform(random));
      }
    }
    const double weight = trial % 2 ? 1.0 : 0.1 + 10.0 * (uniform(random) + 1.0);

    auto point = [&](std::int64_t p) {
      return Vec3{ m.points[3 * p], m.points[3 * p + 1], m.points[3 * p + 2] };
    };
    std::vector<std::vector<double>> stiffness(4, std::vector<double>(4, 0.0));
    std::vector<std::vector<double>> mass = stiffness;
    std::vector<std::vector<double>> divergence(4, std::vector<double>(3, 0.0));
    double totalArea = 0.0;
    for (int f = 0; f < 2; ++f)
    {
      const std::int64_t* t = &m.triangles[static_cast<size_t>(3 * f)];
      const Vec3 x[3] = { point(t[0]), point(t[1]), point(t[2]) };
      const Vec3 e1 = Sub(x[1], x[0]), e2 = Sub(x[2], x[0]);
      const double area = 0.5 * std::sqrt(Dot(Cross(e1, e2), Cross(e1, e2)));
      totalArea += area;
      for (int c = 0; c < 3; ++c)
      {
        // The angle at corner c weighs the opposite edge (i, j): S_ij = -cot/2.
        const int i = (c + 1) % 3, j = (c + 2) % 3;
        const Vec3 a = Sub(x[i], x[c]), b = Sub(x[j], x[c]);
        const Vec3 axb = Cross(a, b);
        const double cot = Dot(a, b) / std::sqrt(Dot(axb, axb));
        stiffness[t[i]][t[j]] -= 0.5 * cot;
        stiffness[t[j]][t[i]] -= 0.5 * cot;
        stiffness[t[i]][t[i]] += 0.5 * cot;
        stiffness[t[j]][t[j]] += 0.5 * cot;
        for (int d = 0; d < 3; ++d)
        {
          mass[t[c]][t[d]] += area / 12.0 * (c == d ? 2.0 : 1.0);
        }
      }
      // Gradients of the barycentric coordinates: E (E^T E)^-1, E = [e1 e2].
      const double g11 = Dot(e1, e1), g12 = Dot(e1, e2), g22 = Dot(e2, e2);
      const double det = g11 * g22 - g12 * g12;
      Vec3 grad[3];
      for (int k = 0; k < 3; ++k)
      {
        grad[1][k] = (g22 * e1[k] - g12 * e2[k]) / det;
        grad[2][k] = (g11 * e2[k] - g12 * e1[k]) / det;
        grad[0][k] = -grad[1][k] - grad[2][k];
      }
      Vec3 n = { targets[3 * f], targets[3 * f + 1], targets[3 * f + 2] };
      const double length = std::sqrt(Dot(n, n));
      for (double& v : n)
      {
        v /= length;
      }
      // Jacobian of the position, J[k] = grad x_k, and the target map T.
      const Vec3 own = [&] {
        const Vec3 c = Cross(e1, e2);
        const double l = std::sqrt(Dot(c, c));
        return Vec3{ c[0] / l, c[1] / l, c[2] / l };
      }();
      const double cosine = Dot(own, n);
      double map[3][3];
      const Vec3 axis = Cross(own, n);
      const double sine = std::sqrt(Dot(axis, axis));
      for (int i = 0; i < 3; ++i)
      {
        for (int j = 0; j < 3; ++j)
        {
          const double delta = i == j ? 1.0 : 0.0;
          switch (target)
          {
            case FitTarget::Projection:
              map[i][j] = delta - n[i] * n[j];
              break;
            case FitTarget::Rotation:
            {
              const double u[3] = { axis[0] / sine, axis[1] / sine, axis[2] / sine };
              const double k[3][3] = { { 0, -u[2], u[1] }, { u[2], 0, -u[0] }, { -u[1], u[0], 0 } };
              map[i][j] = cosine * delta + sine * k[i][j] + (1.0 - cosine) * u[i] * u[j];
              break;
            }
            case FitTarget::Shear:
              map[i][j] = delta - own[i] * n[j] / cosine;
              break;
            case FitTarget::CentralProjection:
              map[i][j] = (delta - own[i] * n[j] / cosine) / cosine;
              break;
          }
        }
      }
      Vec3 jacobian[3] = {};
      for (int k = 0; k < 3; ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          for (int d = 0; d < 3; ++d)
          {
            jacobian[k][d] += x[c][k] * grad[c][d];
          }
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        Vec3 w = {};
        for (int j = 0; j < 3; ++j)
        {
          for (int d = 0; d < 3; ++d)
          {
            w[d] += map[k][j] * jacobian[j][d];
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          divergence[t[c]][k] += area * Dot(grad[c], w);
        }
      }
    }
    // Unit-area normalisation: eps on the normalised mesh is eps / area here.
    const double screening = weight / totalArea;
    std::vector<std::vector<double>> a(4, std::vector<double>(4));
    for (int i = 0; i < 4; ++i)
    {
      for (int j = 0; j < 4; ++j)
      {
        a[i][j] = screening * mass[i][j] + stiffness[i][j];
      }
    }
    FitParameters p = WithSolver(FitSolver::Exact);
    p.screeningWeight = weight;
    p.target = target;
    const auto fitted = Fit(mesh, targets, p);
    for (int k = 0; k < 3; ++k)
    {
      std::vector<double> b(4, 0.0);
      for (int i = 0; i < 4; ++i)
      {
        for (int j = 0; j < 4; ++j)
        {
          b[i] += screening * mass[i][j] * m.points[3 * j + k];
        }
        b[i] += divergence[i][k];
      }
      const auto expected = SolveDense(a, b);
      for (int i = 0; i < 4; ++i)
      {
        EXPECT_NEAR(fitted[3 * i + k], expected[i], 1e-9) << "trial " << trial << ", target " << static_cast<int>(target);
      }
    }
  }
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
  p = FitParameters{};
  p.solver = static_cast<FitSolver>(7);
  EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), positions.data(), p).Ok());
  EXPECT_FALSE(FitPositionsToNormals(mesh, nullptr, positions.data(), FitParameters{}).Ok());
  EXPECT_FALSE(FitPositionsToNormals(mesh, targets.data(), nullptr, FitParameters{}).Ok());
}

} // namespace
