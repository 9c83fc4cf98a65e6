// Tests of what geometry sharpening keeps (Filters/Kernels/Mesh/SharpFeatures, the fit
// targets of ScreenedPoissonFit, MeshSharpening): repeated triangles, feature edges,
// the target gradients against their geometric definitions, sharp shapes kept,
// rounded shapes moved towards their sharp originals.
#include "MeshSharpening.h"
#include "SharpFeatures.h"
#include "TestMeshes.h"
#include "TestSharpShapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

namespace
{
using shocktest::MeshData;
using V = std::array<double, 3>;

shock::TriangleMesh Build(const MeshData& data, int threads = 0)
{
  shock::TriangleMesh mesh;
  const shock::Status status = mesh.Build({ static_cast<std::int64_t>(data.points.size() / 3), data.points.data(),
                                            static_cast<std::int64_t>(data.triangles.size() / 3), data.triangles.data() },
    threads);
  EXPECT_TRUE(status.Ok()) << status.error;
  return mesh;
}

V Sub(const V& a, const V& b) { return { a[0] - b[0], a[1] - b[1], a[2] - b[2] }; }
using shocktest::Cross;
using shocktest::Dot;
using shocktest::Point;
V Unit(const V& a)
{
  const double l = std::sqrt(Dot(a, a));
  return { a[0] / l, a[1] / l, a[2] / l };
}
double Length(const V& a) { return std::sqrt(Dot(a, a)); }

/// The edge e mapped by the target gradients: (W e)_k = w_k . e.
V Mapped(const double w[9], const V& e)
{
  return { w[0] * e[0] + w[1] * e[1] + w[2] * e[2], w[3] * e[0] + w[4] * e[1] + w[5] * e[2],
    w[6] * e[0] + w[7] * e[1] + w[8] * e[2] };
}

std::vector<double> Sharpen(const MeshData& data, const shock::SharpeningParameters& p,
  shock::SharpeningReport* report = nullptr, std::vector<double>* normals = nullptr)
{
  const shock::TriangleMesh mesh = Build(data);
  std::vector<double> positions(data.points.size());
  std::vector<double> target(data.triangles.size());
  const shock::Status status = shock::SharpenMeshGeometry(mesh, p, positions.data(), target.data(), report);
  EXPECT_TRUE(status.Ok()) << status.error;
  if (normals)
  {
    *normals = target;
  }
  return positions;
}

double Diagonal(const MeshData& m)
{
  const auto b = shocktest::Bounds(m);
  return Length(Sub(b[1], b[0]));
}

double MaxDistance(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (size_t p = 0; p < a.size(); p += 3)
  {
    worst = std::max(worst, Length({ a[p] - b[p], a[p + 1] - b[p + 1], a[p + 2] - b[p + 2] }));
  }
  return worst;
}

// ---------------------------------------------------------------------------
// Repeated triangles and feature edges

TEST(SharpFeatures, RepeatedTrianglesPointToTheirFirstOccurrence)
{
  MeshData m;
  for (const V& p : std::vector<V>{ { 0, 0, 0 }, { 1.3, 0.1, 0 }, { 0.2, 0.9, 0.1 }, { 1.1, 1.4, 0.3 } })
  {
    shocktest::AddPoint(m, p);
  }
  // {0,1,2}, {1,2,3}, {0,1,2} reversed, {1,2,3} rotated, {0,1,2} again, {0,1,3} (new).
  m.triangles = { 0, 1, 2, 2, 1, 3, 1, 0, 2, 3, 2, 1, 0, 1, 2, 0, 1, 3 };
  const auto first = shock::FindRepeatedTriangles(Build(m), 2);
  EXPECT_EQ(first, (std::vector<std::int64_t>{ -1, -1, 0, 1, 0, -1 }));
}

TEST(SharpFeatures, RepeatedTrianglesMatchTheirDefinition)
{
  // A closed sphere with copies of some triangles (in other orientations), a
  // triangle alone with its copy (the two share all three edges and nothing
  // else), and a triangle with a repeated id with its copy.
  MeshData m = shocktest::Icosphere(2);
  const std::int64_t n = m.NumberOfTriangles();
  for (std::int64_t f : { std::int64_t{ 5 }, std::int64_t{ 17 }, n - 1 })
  {
    const std::int64_t* t = &m.triangles[static_cast<size_t>(3 * f)];
    const std::int64_t copy[3] = { t[2], t[1], t[0] };
    m.triangles.insert(m.triangles.end(), copy, copy + 3);
  }
  const std::int64_t base = m.NumberOfPoints();
  for (const V& p : std::vector<V>{ { 3, 0, 0 }, { 4, 0, 0 }, { 3, 1, 0 }, { 5, 5, 5 }, { 6, 5, 5 } })
  {
    shocktest::AddPoint(m, p);
  }
  m.triangles.insert(m.triangles.end(), { base, base + 1, base + 2, base + 1, base + 2, base,
                                          base + 3, base + 3, base + 4, base + 4, base + 3, base + 3 });
  std::vector<std::int64_t> expected(static_cast<size_t>(m.NumberOfTriangles()), -1);
  auto sorted = [&m](std::int64_t f) {
    std::array<std::int64_t, 3> s{ m.triangles[static_cast<size_t>(3 * f)],
      m.triangles[static_cast<size_t>(3 * f + 1)], m.triangles[static_cast<size_t>(3 * f + 2)] };
    std::sort(s.begin(), s.end());
    return s;
  };
  int repeats = 0;
  for (std::int64_t f = 0; f < m.NumberOfTriangles(); ++f)
  {
    for (std::int64_t g = 0; g < f; ++g)
    {
      if (sorted(g) == sorted(f))
      {
        expected[static_cast<size_t>(f)] = g;
        ++repeats;
        break;
      }
    }
  }
  EXPECT_EQ(repeats, 5);
  for (int threads : { 1, 2 })
  {
    EXPECT_EQ(shock::FindRepeatedTriangles(Build(m), threads), expected);
  }
}

TEST(SharpFeatures, CubeCornersSplitIntoOneCopyPerFace)
{
  const MeshData cube = shocktest::BoxSurface(1, 1.0, 1.0, 1.0); // 8 points, 12 triangles
  const shock::TriangleMesh mesh = Build(cube);
  std::vector<double> normals;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    normals.insert(normals.end(), mesh.Normal(f), mesh.Normal(f) + 3);
  }
  for (double angle : { 30.0, 89.0 })
  {
    shock::FeatureSplitMesh split;
    ASSERT_TRUE(shock::SplitAtFeatureEdges(mesh, normals.data(), angle, 2, split).Ok());
    EXPECT_EQ(split.featureEdges, 12) << angle;
    ASSERT_EQ(split.mesh.NumberOfPoints(), 24) << angle;
    ASSERT_EQ(split.mesh.NumberOfTriangles(), 12);
    // Every copy lies where its original is, and all its triangles share one normal.
    for (std::int64_t q = 0; q < 24; ++q)
    {
      const std::int64_t p = split.original[static_cast<size_t>(q)];
      EXPECT_EQ(Length(Sub(Point(cube, p), { split.mesh.Point(q)[0], split.mesh.Point(q)[1], split.mesh.Point(q)[2] })), 0.0);
      const auto& around = split.mesh.PointTriangles();
      std::set<std::array<double, 3>> faceNormals;
      for (std::int64_t k = around.Begin(q); k < around.End(q); ++k)
      {
        const double* n = split.mesh.Normal(around.items[static_cast<size_t>(k)]);
        faceNormals.insert({ std::round(n[0]), std::round(n[1]), std::round(n[2]) });
      }
      EXPECT_EQ(faceNormals.size(), 1u) << q;
    }
  }
  for (double angle : { 91.0, 180.0 })
  {
    shock::FeatureSplitMesh split;
    ASSERT_TRUE(shock::SplitAtFeatureEdges(mesh, normals.data(), angle, 2, split).Ok());
    EXPECT_EQ(split.featureEdges, 0) << angle;
    EXPECT_EQ(split.mesh.NumberOfPoints(), 0) << angle;
  }
  shock::FeatureSplitMesh split;
  EXPECT_FALSE(shock::SplitAtFeatureEdges(mesh, normals.data(), -1.0, 2, split).Ok());
  EXPECT_FALSE(shock::SplitAtFeatureEdges(mesh, normals.data(), 181.0, 2, split).Ok());
}

TEST(SharpFeatures, AFoldSplitsOnlyAboveItsAngle)
{
  // Two irregular triangles folded by 20 degrees along the edge (0, 1), plus a third flat one.
  const double fold = 20.0 * std::acos(-1.0) / 180.0;
  MeshData m;
  shocktest::AddPoint(m, { 0, 0, 0 });
  shocktest::AddPoint(m, { 1.7, 0, 0 });
  shocktest::AddPoint(m, { 0.4, 1.1, 0 });
  shocktest::AddPoint(m, { 0.9, -0.8 * std::cos(fold), 0.8 * std::sin(fold) });
  shocktest::AddPoint(m, { 2.0, 1.0, 0 });
  m.triangles = { 0, 1, 2, 1, 0, 3, 1, 4, 2 };
  const shock::TriangleMesh mesh = Build(m);
  std::vector<double> normals;
  for (std::int64_t f = 0; f < 3; ++f)
  {
    normals.insert(normals.end(), mesh.Normal(f), mesh.Normal(f) + 3);
  }
  shock::FeatureSplitMesh split;
  ASSERT_TRUE(shock::SplitAtFeatureEdges(mesh, normals.data(), 25.0, 1, split).Ok());
  EXPECT_EQ(split.featureEdges, 0);
  ASSERT_TRUE(shock::SplitAtFeatureEdges(mesh, normals.data(), 15.0, 1, split).Ok());
  EXPECT_EQ(split.featureEdges, 1);
  // Points 0 and 1 split (two copies each); 2, 3 and 4 do not.
  EXPECT_EQ(split.mesh.NumberOfPoints(), 7);
  EXPECT_EQ(split.mesh.Neighbour(0, 0), -1); // the fold is a boundary now
  EXPECT_EQ(split.mesh.Neighbour(0, 1), 2);  // the flat edge (1, 2) still joins
}

// ---------------------------------------------------------------------------
// Target gradients against their geometric definitions

TEST(FitTargets, EdgesMapAsDefined)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial)
  {
    MeshData m;
    for (int p = 0; p < 3; ++p)
    {
      shocktest::AddPoint(m, { 2.0 * uniform(random), uniform(random), 0.5 * uniform(random) });
    }
    m.triangles = { 0, 1, 2 };
    const shock::TriangleMesh mesh = Build(m);
    const V n = Unit(Cross(Sub(Point(m, 1), Point(m, 0)), Sub(Point(m, 2), Point(m, 0))));
    // A target tilted from n by up to 80 degrees (both Shear branches); every 5th trial, n itself.
    const V tangent = Unit(Cross(n, { uniform(random), uniform(random), uniform(random) }));
    const double tilt = trial % 5 == 0 ? 0.0 : 0.7 * std::abs(uniform(random)) * 2.0;
    const V N = Unit({ std::cos(tilt) * n[0] + std::sin(tilt) * tangent[0],
      std::cos(tilt) * n[1] + std::sin(tilt) * tangent[1], std::cos(tilt) * n[2] + std::sin(tilt) * tangent[2] });
    const double c = Dot(n, N);
    for (auto target : { shock::FitTarget::Projection, shock::FitTarget::Rotation, shock::FitTarget::Shear,
           shock::FitTarget::CentralProjection })
    {
      double w[9];
      shock::FitTargetGradients(mesh, 0, N.data(), target, w);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_NEAR(Dot({ w[3 * k], w[3 * k + 1], w[3 * k + 2] }, n), 0.0, 1e-12) << "in-plane gradients";
      }
      const V e1 = Sub(Point(m, 1), Point(m, 0)), e2 = Sub(Point(m, 2), Point(m, 0));
      const V m1 = Mapped(w, e1), m2 = Mapped(w, e2);
      for (const V& e : { e1, e2 })
      {
        const V we = Mapped(w, e);
        EXPECT_NEAR(Dot(we, N), 0.0, 1e-12) << "every target lies in the target plane";
        if (trial % 5 == 0)
        {
          EXPECT_NEAR(Length(Sub(we, e)), 0.0, 1e-12) << "the own normal keeps every edge";
        }
        if (target == shock::FitTarget::Projection)
        {
          const V expected = Sub(e, { N[0] * Dot(N, e), N[1] * Dot(N, e), N[2] * Dot(N, e) });
          EXPECT_NEAR(Length(Sub(we, expected)), 0.0, 1e-12);
        }
        const bool sheared = target == shock::FitTarget::Shear || target == shock::FitTarget::CentralProjection;
        const bool rotated = target == shock::FitTarget::Rotation || (sheared && c < std::sqrt(0.5));
        if (rotated)
        {
          EXPECT_NEAR(Length(we), Length(e), 1e-12) << "rotations keep lengths";
        }
        else if (target == shock::FitTarget::Shear)
        {
          // Moved along n only: the footprint e is kept.
          const V along = Sub(we, e);
          EXPECT_NEAR(Length(Cross(along, n)), 0.0, 1e-12);
          EXPECT_GE(Length(we), Length(e) - 1e-12);
        }
        else if (target == shock::FitTarget::CentralProjection)
        {
          // Central projection from the centre of curvature C = x - rho n onto the plane
          // with normal N at distance rho from C: x + e goes to C + s (rho n + e) with
          // s = rho / <N, rho n + e>, x to C + rho n / c. The difference of the images is
          // W e up to terms in |e|^2 / rho.
          const double rho = 1e8;
          const V ray{ rho * n[0] + e[0], rho * n[1] + e[1], rho * n[2] + e[2] };
          const double s0 = 1.0 / c, s1 = rho / Dot(N, ray);
          const V image{ (s1 * ray[0] - s0 * rho * n[0]), (s1 * ray[1] - s0 * rho * n[1]), (s1 * ray[2] - s0 * rho * n[2]) };
          EXPECT_NEAR(Length(Sub(we, image)), 0.0, 1e-6 * Length(e));
        }
      }
      // The mapped triangle faces N (its orientation is kept).
      EXPECT_GT(Dot(Cross(m1, m2), N), 0.0);
      if (target == shock::FitTarget::Rotation)
      {
        EXPECT_NEAR(Dot(m1, m2), Dot(e1, e2), 1e-12) << "angles kept";
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Sharpening: sharp shapes kept, rounded ones recovered, repeats ignored

TEST(SharpeningKeeps, AlreadySharpShapesAtDefaultSettings)
{
  const std::vector<std::pair<const char*, MeshData>> shapes = { { "cube", shocktest::BoxSurface(1, 1.0, 1.0, 1.0) },
    { "subdivided cube", shocktest::BoxSurface(8, 1.0, 1.0, 1.0) },
    { "capped cylinder", shocktest::CappedCylinder(24, 6, 0.5, 1.2) },
    { "slotted L block", shocktest::SlottedLBlock() } };
  for (const auto& shape : shapes)
  {
    shock::SharpeningParameters p; // defaults
    shock::SharpeningReport report;
    const auto after = Sharpen(shape.second, p, &report);
    EXPECT_LT(MaxDistance(after, shape.second.points), 0.01 * Diagonal(shape.second)) << shape.first;
    EXPECT_GT(report.featureEdges, 0) << shape.first;
    EXPECT_EQ(report.flippedTriangles, 0) << shape.first;
    // The paper's per-point normals (no feature angle) round them: something to keep.
    p.featureAngle = 180.0;
    p.fit.target = shock::FitTarget::Projection;
    p.keepUnmovedNormals = false; // the paper's sampling: the averages also where the flow is zero
    const auto paper = Sharpen(shape.second, p);
    if (shape.first != std::string("capped cylinder"))
    {
      EXPECT_GT(MaxDistance(paper, shape.second.points), 0.01 * Diagonal(shape.second)) << shape.first;
    }
    EXPECT_GT(MaxDistance(paper, shape.second.points), 10.0 * MaxDistance(after, shape.second.points) + 1e-9)
      << shape.first;
  }
}

/// Mean angle to the cube's normal and mean distance to the surface of the cube [-1, 1]^3.
std::pair<double, double> CubeErrors(const MeshData& m, const std::vector<double>& positions)
{
  MeshData moved = m;
  moved.points = positions;
  double angle = 0.0, distance = 0.0;
  const std::int64_t nt = moved.NumberOfTriangles();
  for (std::int64_t t = 0; t < nt; ++t)
  {
    const V c = shocktest::TriangleCentroid(moved, t);
    const int axis = static_cast<int>(std::max_element(c.begin(), c.end(), [](double a, double b) {
      return std::abs(a) < std::abs(b);
    }) - c.begin());
    V normal{ 0, 0, 0 };
    normal[static_cast<size_t>(axis)] = c[static_cast<size_t>(axis)] > 0 ? 1.0 : -1.0;
    angle += std::acos(std::clamp(Dot(shocktest::TriangleNormal(moved, t), normal), -1.0, 1.0)) / nt;
  }
  for (std::int64_t p = 0; p < moved.NumberOfPoints(); ++p)
  {
    const V x = Point(moved, p);
    const V outside{ std::max(std::abs(x[0]) - 1, 0.0), std::max(std::abs(x[1]) - 1, 0.0), std::max(std::abs(x[2]) - 1, 0.0) };
    const double inside = 1.0 - std::max({ std::abs(x[0]), std::abs(x[1]), std::abs(x[2]) });
    distance += (Length(outside) > 0.0 ? Length(outside) : inside) / moved.NumberOfPoints();
  }
  return { angle, distance };
}

TEST(SharpeningKeeps, RoundedCubeMovesTowardsTheCubeWithBothSolvers)
{
  const MeshData rounded = shocktest::RoundedBox(24, 2.0, 0.3);
  const auto before = CubeErrors(rounded, rounded.points);
  for (auto solver : { shock::FitSolver::ConjugateGradient, shock::FitSolver::Exact })
  {
    shock::SharpeningParameters p;
    p.advection.time = 1024.0;
    p.fit.solver = solver;
    shock::SharpeningReport report;
    const auto after = CubeErrors(rounded, Sharpen(rounded, p, &report));
    EXPECT_LT(after.first, 0.5 * before.first) << "normal error, solver " << static_cast<int>(solver);
    EXPECT_LT(after.second, before.second) << "distance, solver " << static_cast<int>(solver);
    EXPECT_EQ(report.flippedTriangles, 0);
    // The paper's projection pulls the faces in: further from the cube than the input.
    p.fit.target = shock::FitTarget::Projection;
    const auto paper = CubeErrors(rounded, Sharpen(rounded, p));
    EXPECT_GT(paper.second, after.second) << "solver " << static_cast<int>(solver);
  }
}

TEST(SharpeningKeeps, RepeatedAndDegenerateTrianglesChangeNothing)
{
  const MeshData once = shocktest::RoundedBox(8, 2.0, 0.4);
  MeshData twice = once;
  for (size_t t = 0; t < once.triangles.size(); t += 3)
  {
    // The copy in the opposite orientation, as a mesh appended to its mirror image would give.
    twice.triangles.insert(twice.triangles.end(), { once.triangles[t], once.triangles[t + 2], once.triangles[t + 1] });
  }
  // Zero-area triangles: a repeated point on an edge, and a corner, an edge midpoint and the other corner.
  MeshData degenerate = once;
  const std::int64_t a = once.triangles[0], b = once.triangles[1], c = once.triangles[2];
  using shocktest::operator+;
  using shocktest::operator*;
  const std::int64_t mid = shocktest::AddPoint(degenerate, 0.5 * (Point(once, b) + Point(once, c)));
  shocktest::AddTriangle(degenerate, a, a, b);
  shocktest::AddTriangle(degenerate, b, mid, c);
  shock::SharpeningParameters p;
  p.advection.time = 512.0;
  p.advection.numberOfThreads = 2;
  std::vector<double> normalsOnce, normalsTwice;
  shock::SharpeningReport report;
  const auto expected = Sharpen(once, p, &report, &normalsOnce);
  EXPECT_EQ(report.repeatedTriangles, 0);
  ASSERT_GT(MaxDistance(expected, once.points), 1e-3) << "the mesh must move";
  const auto doubled = Sharpen(twice, p, &report, &normalsTwice);
  EXPECT_EQ(report.repeatedTriangles, once.NumberOfTriangles());
  EXPECT_EQ(doubled, expected);
  for (size_t i = 0; i < normalsOnce.size(); ++i)
  {
    EXPECT_EQ(normalsTwice[i], normalsOnce[i]);
    EXPECT_EQ(normalsTwice[i + normalsOnce.size()], normalsOnce[i]);
  }
  const auto withDegenerate = Sharpen(degenerate, p, &report);
  EXPECT_EQ(report.degenerateTriangles, 2);
  EXPECT_EQ(report.repeatedTriangles, 0);
  ASSERT_EQ(withDegenerate.size(), degenerate.points.size());
  EXPECT_LT(MaxDistance(std::vector<double>(withDegenerate.begin(), withDegenerate.begin() + expected.size()), expected),
    1e-9 * Diagonal(once));
}

TEST(SharpeningKeeps, FeatureSplitResultsDoNotDependOnTheThreadCount)
{
  const MeshData block = shocktest::SlottedLBlock(0.1);
  shock::SharpeningParameters p;
  p.advection.time = 256.0;
  p.featureAngle = 60.0;
  p.advection.numberOfThreads = 1;
  shock::SharpeningReport report;
  const auto one = Sharpen(block, p, &report);
  EXPECT_GT(report.featureEdges, 0);
  p.advection.numberOfThreads = 2;
  EXPECT_EQ(Sharpen(block, p), one);
}

TEST(SharpeningKeeps, FlowFieldsCoverTheInputsPointsAndTriangles)
{
  // A split mesh (sharp cap edges, curved side) with every triangle given twice: the
  // fields are per input point and triangle; a copy has its first occurrence's flow.
  const MeshData block = shocktest::CappedCylinder(24, 6, 0.5, 1.2);
  MeshData twice = block;
  twice.triangles.insert(twice.triangles.end(), block.triangles.begin(), block.triangles.end());
  const shock::TriangleMesh mesh = Build(twice);
  shock::SharpeningParameters p;
  p.advection.time = 256.0;
  p.featureAngle = 60.0;
  // The paper's potential: the default contrast leaves none on this already-sharp
  // shape, and the fields must show one.
  p.curvatureContrast = 0.0;
  std::vector<double> positions(twice.points.size());
  shock::SharpeningReport report;
  shock::MeshFlowFields fields;
  ASSERT_TRUE(shock::SharpenMeshGeometry(mesh, p, positions.data(), nullptr, &report, &fields).Ok());
  EXPECT_GT(report.featureEdges, 0);
  EXPECT_EQ(report.repeatedTriangles, block.NumberOfTriangles());
  ASSERT_EQ(fields.potential.size(), static_cast<size_t>(twice.NumberOfPoints()));
  ASSERT_EQ(fields.flow.size(), static_cast<size_t>(3 * twice.NumberOfTriangles()));
  EXPECT_TRUE(std::all_of(fields.potential.begin(), fields.potential.end(), [](double v) { return std::isfinite(v) && v >= 0.0; }));
  EXPECT_GT(*std::max_element(fields.potential.begin(), fields.potential.end()), 0.0);
  const size_t half = fields.flow.size() / 2;
  for (size_t i = 0; i < half; ++i)
  {
    EXPECT_EQ(fields.flow[i + half], fields.flow[i]);
  }
}

TEST(SharpeningKeeps, InvalidFeatureAngleAndFitTargetAreRejected)
{
  const shock::TriangleMesh mesh = Build(shocktest::Icosphere(1));
  std::vector<double> positions(static_cast<size_t>(3 * mesh.NumberOfPoints()));
  for (double angle : { -0.5, 180.5, std::nan("") })
  {
    shock::SharpeningParameters p;
    p.featureAngle = angle;
    EXPECT_FALSE(shock::SharpenMeshGeometry(mesh, p, positions.data()).Ok()) << angle;
  }
  shock::SharpeningParameters p;
  p.fit.target = static_cast<shock::FitTarget>(7);
  EXPECT_FALSE(shock::SharpenMeshGeometry(mesh, p, positions.data()).Ok());
}

} // namespace
