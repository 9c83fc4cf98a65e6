// Tests of the VTK-free triangle-mesh shock filter (Filters/Kernels/Mesh/MeshShockAdvection).
#include "GridShockAdvection.h"
#include "MeshShockAdvection.h"
#include "TestMeshes.h"
#include "TestSignals.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
using shocktest::MeshData;

shock::TriangleMesh Build(const MeshData& data, int threads = 0)
{
  shock::TriangleMeshView view;
  view.numberOfPoints = static_cast<std::int64_t>(data.points.size() / 3);
  view.points = data.points.data();
  view.numberOfTriangles = static_cast<std::int64_t>(data.triangles.size() / 3);
  view.triangles = data.triangles.data();
  shock::TriangleMesh mesh;
  const shock::Status status = mesh.Build(view, threads);
  EXPECT_TRUE(status.Ok()) << status.error;
  return mesh;
}

shock::AdvectionParameters Parameters(double time)
{
  shock::AdvectionParameters p;
  p.time = time;
  return p;
}

/// Filter a signal; fails the test on a kernel error.
std::vector<double> Filter(const shock::TriangleMesh& mesh, const std::vector<double>& values,
  int components, const shock::AdvectionParameters& p,
  shock::MeshLocation location = shock::MeshLocation::Points, shock::AdvectionReport* report = nullptr,
  shock::MeshFlowFields* fields = nullptr)
{
  shock::MeshSignal signal;
  signal.location = location;
  signal.components = components;
  signal.values = values.data();
  std::vector<double> out(values.size());
  shock::AdvectionReport local;
  shock::AdvectionReport& r = report ? *report : local;
  const shock::Status status = shock::AdvectMeshSignal(mesh, signal, out.data(), p, &r, fields);
  EXPECT_TRUE(status.Ok()) << status.error;
  // The guard against discrete cycles never cuts a trace in these tests (README).
  EXPECT_EQ(r.truncatedTraces, 0u);
  return out;
}

const double* PointOf(const MeshData& data, size_t p)
{
  return &data.points[3 * p];
}

/// A scalar per point from a function of the position.
template <typename F>
std::vector<double> PointSignal(const MeshData& data, F&& f)
{
  std::vector<double> values(data.points.size() / 3);
  for (size_t p = 0; p < values.size(); ++p)
  {
    values[p] = f(PointOf(data, p));
  }
  return values;
}

/// Number of values strictly inside (lo, hi): the width of a transition band.
size_t CountBetween(const std::vector<double>& values, double lo, double hi)
{
  return static_cast<size_t>(
    std::count_if(values.begin(), values.end(), [&](double v) { return v > lo && v < hi; }));
}

double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    d = std::max(d, std::abs(a[i] - b[i]));
  }
  return d;
}

double Rms(const std::vector<double>& a, const std::vector<double>& b)
{
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    s += (a[i] - b[i]) * (a[i] - b[i]);
  }
  return std::sqrt(s / a.size());
}

/// A blurred step across the sphere's equator, tilted so it is not aligned with the mesh.
std::vector<double> SphereStep(const MeshData& sphere, double sigma)
{
  return PointSignal(sphere, [sigma](const double* x) {
    return shocktest::SmoothStep(0.8 * x[2] + 0.6 * x[0], 0.1, sigma);
  });
}

bool AllFinite(const std::vector<double>& values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// ---------------------------------------------------------------- TriangleMesh

TEST(TriangleMesh, GeometryAndAdjacencyOfAClosedSphere)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  EXPECT_NEAR(mesh.MeanEdgeLength(), shocktest::MeanEdgeLength(sphere), 1e-12);
  EXPECT_EQ(mesh.NumberOfEdges() + 2, mesh.NumberOfPoints() + mesh.NumberOfTriangles()); // Euler
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const std::int64_t* t = mesh.Corners(f);
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t g = mesh.Neighbour(f, e);
      ASSERT_GE(g, 0);
      const std::int64_t* s = mesh.Corners(g);
      const int shared = (s[0] == t[e] || s[1] == t[e] || s[2] == t[e]) +
        (s[0] == t[(e + 1) % 3] || s[1] == t[(e + 1) % 3] || s[2] == t[(e + 1) % 3]);
      EXPECT_EQ(shared, 2);
    }
    // grad(phi_c) . (x_c - x_other) = 1 and the hat gradients sum to zero.
    for (int c = 0; c < 3; ++c)
    {
      const double* g = mesh.HatGradient(f, c);
      const double* xc = mesh.Point(t[c]);
      const double* xo = mesh.Point(t[(c + 1) % 3]);
      EXPECT_NEAR(g[0] * (xc[0] - xo[0]) + g[1] * (xc[1] - xo[1]) + g[2] * (xc[2] - xo[2]), 1.0, 1e-9);
      const double* n = mesh.Normal(f);
      EXPECT_NEAR(g[0] * n[0] + g[1] * n[1] + g[2] * n[2], 0.0, 1e-9);
    }
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(mesh.HatGradient(f, 0)[k] + mesh.HatGradient(f, 1)[k] + mesh.HatGradient(f, 2)[k], 0.0, 1e-9);
    }
  }
}

TEST(TriangleMesh, RejectsBadIdsAndCoordinates)
{
  MeshData data = shocktest::PlaneGrid(3, 3);
  data.triangles[4] = 99;
  shock::TriangleMeshView view{ static_cast<std::int64_t>(data.points.size() / 3), data.points.data(),
    static_cast<std::int64_t>(data.triangles.size() / 3), data.triangles.data() };
  shock::TriangleMesh mesh;
  EXPECT_FALSE(mesh.Build(view, 1).Ok());
  data = shocktest::PlaneGrid(3, 3);
  data.points[4] = std::nan("");
  view.points = data.points.data();
  view.triangles = data.triangles.data();
  EXPECT_NE(mesh.Build(view, 1).error.find("finite"), std::string::npos);
}

TEST(TriangleMesh, DefectsAreMarked)
{
  const MeshData fan = shocktest::NonManifoldFan();
  const shock::TriangleMesh mesh = Build(fan);
  // Every edge shared by three or more triangles joins nothing.
  int nonManifoldSides = 0;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = mesh.Corners(f)[e], b = mesh.Corners(f)[(e + 1) % 3];
      int sharing = 0;
      for (std::int64_t g = 0; g < mesh.NumberOfTriangles(); ++g)
      {
        const std::int64_t* s = mesh.Corners(g);
        const bool hasA = s[0] == a || s[1] == a || s[2] == a;
        const bool hasB = s[0] == b || s[1] == b || s[2] == b;
        sharing += (hasA && hasB) ? 1 : 0;
      }
      if (sharing > 2)
      {
        EXPECT_EQ(mesh.Neighbour(f, e), -1);
        ++nonManifoldSides;
      }
    }
  }
  EXPECT_GE(nonManifoldSides, 3);

  const MeshData degenerate = shocktest::WithDegenerateTriangles(shocktest::Icosphere(2));
  const shock::TriangleMesh withDegenerate = Build(degenerate);
  int flagged = 0;
  for (std::int64_t f = 0; f < withDegenerate.NumberOfTriangles(); ++f)
  {
    flagged += withDegenerate.Degenerate(f) ? 1 : 0;
    if (withDegenerate.Degenerate(f))
    {
      EXPECT_EQ(withDegenerate.Area(f), 0.0);
    }
  }
  EXPECT_GE(flagged, 2);
}

// ---------------------------------------------------------------- tracing

/**
 * A flat strip folded along the line y = 1 by `angle`: the developed plane
 * (u, v) maps to 3D, and a constant developed velocity maps to a per-triangle one.
 */
struct FoldedStrip
{
  MeshData data;
  double angle;
  std::array<double, 3> Embed(double u, double v) const
  {
    if (v <= 1.0)
    {
      return { u, v, 0.0 };
    }
    return { u, 1.0 + (v - 1.0) * std::cos(this->angle), (v - 1.0) * std::sin(this->angle) };
  }
};

FoldedStrip MakeFoldedStrip(int nu, int nv, double angle)
{
  FoldedStrip strip{ shocktest::PlaneGrid(nu, nv, 2.0 / (nv - 1)), angle };
  for (size_t p = 0; p < strip.data.points.size() / 3; ++p)
  {
    const auto x = strip.Embed(strip.data.points[3 * p], strip.data.points[3 * p + 1]);
    std::copy(x.begin(), x.end(), &strip.data.points[3 * p]);
  }
  return strip;
}

TEST(MeshTracing, UnfoldingKeepsAStraightLineStraightAcrossAFold)
{
  const double angle = 1.1;
  const FoldedStrip strip = MakeFoldedStrip(41, 21, angle);
  const shock::TriangleMesh mesh = Build(strip.data);
  // Constant developed velocity (a, b), embedded per triangle.
  const double a = 0.37, b = 0.81;
  std::vector<double> velocity(static_cast<size_t>(3 * mesh.NumberOfTriangles()));
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const bool upper = mesh.Centroid(f)[2] > 1e-9;
    velocity[3 * f] = a;
    velocity[3 * f + 1] = upper ? b * std::cos(angle) : b;
    velocity[3 * f + 2] = upper ? b * std::sin(angle) : 0.0;
  }
  for (shock::Tracing tracing : { shock::Tracing::FaceCrossing, shock::Tracing::Stepped })
  {
    shock::AdvectionParameters p;
    p.tracing = tracing;
    // Start inside a lower triangle, trace across the fold.
    shock::SurfacePoint q;
    q.triangle = 7;
    q.barycentric[0] = 0.2;
    q.barycentric[1] = 0.3;
    q.barycentric[2] = 0.5;
    std::array<double, 3> start{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      for (int d = 0; d < 3; ++d)
      {
        start[d] += q.barycentric[k] * mesh.Point(mesh.Corners(q.triangle)[k])[d];
      }
    }
    ASSERT_LT(start[1], 1.0);
    const double time = 2.0;
    const std::int64_t steps = shock::TraceOnMesh(mesh, velocity.data(), q, time, p);
    EXPECT_GT(steps, 5);
    std::array<double, 3> end{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_GE(q.barycentric[k], 0.0);
      for (int d = 0; d < 3; ++d)
      {
        end[d] += q.barycentric[k] * mesh.Point(mesh.Corners(q.triangle)[k])[d];
      }
    }
    const auto expected = strip.Embed(start[0] + a * time, start[1] + b * time);
    ASSERT_GT(start[1] + b * time, 1.2); // the line crossed the fold
    for (int d = 0; d < 3; ++d)
    {
      EXPECT_NEAR(end[d], expected[d], 1e-9) << "tracing mode " << static_cast<int>(tracing);
    }
  }
}

TEST(MeshTracing, TracedPointsStayOnTheirTriangles)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  // A random tangent velocity per triangle: traces wander across many edges.
  std::mt19937 random(5);
  std::normal_distribution<double> normal;
  std::vector<double> velocity(static_cast<size_t>(3 * mesh.NumberOfTriangles()));
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    double v[3] = { normal(random), normal(random), normal(random) };
    const double* n = mesh.Normal(f);
    const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
    for (int k = 0; k < 3; ++k)
    {
      velocity[3 * f + k] = 0.3 * (v[k] - vn * n[k]);
    }
  }
  for (shock::Tracing tracing : { shock::Tracing::FaceCrossing, shock::Tracing::Stepped })
  {
    shock::AdvectionParameters p;
    p.tracing = tracing;
    for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); f += 7)
    {
      shock::SurfacePoint q;
      q.triangle = f;
      shock::TraceOnMesh(mesh, velocity.data(), q, 10.0, p);
      ASSERT_GE(q.triangle, 0);
      ASSERT_LT(q.triangle, mesh.NumberOfTriangles());
      double sum = 0.0;
      for (double l : q.barycentric)
      {
        EXPECT_GE(l, 0.0);
        sum += l;
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
    }
  }
}

TEST(MeshTracing, TracesStopAtBoundaries)
{
  const MeshData plane = shocktest::PlaneGrid(11, 11);
  const shock::TriangleMesh mesh = Build(plane);
  std::vector<double> velocity(static_cast<size_t>(3 * mesh.NumberOfTriangles()), 0.0);
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    velocity[3 * f] = 1.0; // towards +x, off the mesh at x = 10
  }
  for (shock::Tracing tracing : { shock::Tracing::FaceCrossing, shock::Tracing::Stepped })
  {
    shock::AdvectionParameters p;
    p.tracing = tracing;
    shock::SurfacePoint q;
    q.triangle = 0;
    shock::TraceOnMesh(mesh, velocity.data(), q, 1e6, p);
    double x = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      x += q.barycentric[k] * mesh.Point(mesh.Corners(q.triangle)[k])[0];
    }
    EXPECT_NEAR(x, 10.0, 1e-6);
  }
}

// ---------------------------------------------------------------- filtering

TEST(MeshShockAdvection, TimeZeroIsTheIdentity)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  const std::vector<double> values = SphereStep(sphere, 0.3);
  EXPECT_EQ(Filter(mesh, values, 1, Parameters(0.0)), values);
}

TEST(MeshShockAdvection, OutputStaysInTheInputRangeAndAStepSharpens)
{
  const MeshData sphere = shocktest::Icosphere(4);
  const shock::TriangleMesh mesh = Build(sphere);
  // sigma = 0.15 is about 2 mean edge lengths: sharpening needs t of order 10 sigma^4.
  const std::vector<double> values = SphereStep(sphere, 0.15);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  for (double t : { 1024.0, 4096.0, 16384.0 })
  {
    const std::vector<double> out = Filter(mesh, values, 1, Parameters(t));
    for (double v : out)
    {
      ASSERT_GE(v, *lo);
      ASSERT_LE(v, *hi);
    }
    EXPECT_LT(CountBetween(out, 0.1, 0.9), CountBetween(values, 0.1, 0.9) / 3) << "t = " << t;
  }
}

TEST(MeshShockAdvection, IsolatedSmoothExtremumKeepsItsValue)
{
  const MeshData sphere = shocktest::Icosphere(4);
  const shock::TriangleMesh mesh = Build(sphere);
  // A Gaussian bump centred exactly on vertex 0.
  const double* top = PointOf(sphere, 0);
  const std::vector<double> values = PointSignal(sphere, [top](const double* x) {
    const double d2 = (x[0] - top[0]) * (x[0] - top[0]) + (x[1] - top[1]) * (x[1] - top[1]) +
      (x[2] - top[2]) * (x[2] - top[2]);
    return std::exp(-d2 / 0.18);
  });
  const std::vector<double> out = Filter(mesh, values, 1, Parameters(1024.0));
  const double range = 1.0 - *std::min_element(values.begin(), values.end());
  EXPECT_NEAR(*std::max_element(out.begin(), out.end()), 1.0, 0.005 * range);
  // The identity keeps the top too: the bump's flanks must have moved.
  double moved = 0.0;
  for (size_t i = 0; i < out.size(); ++i)
  {
    moved = std::max(moved, std::abs(out[i] - values[i]));
  }
  EXPECT_GT(moved, 0.01 * range);
}

TEST(MeshShockAdvection, StableForHugeTimesAndReachesASteadyState)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  const std::vector<double> values = SphereStep(sphere, 0.3);
  const std::vector<double> huge = Filter(mesh, values, 1, Parameters(1e9));
  EXPECT_TRUE(AllFinite(huge));
  for (double v : huge)
  {
    EXPECT_GE(v, 0.0);
    EXPECT_LE(v, 1.0);
  }
  // The change between t and 2t vanishes as t grows (flow lines end at ridges of the potential).
  std::vector<double> changes;
  for (double t : { 1024.0, 65536.0, 4194304.0, 268435456.0 })
  {
    const std::vector<double> a = Filter(mesh, values, 1, Parameters(t));
    const std::vector<double> b = Filter(mesh, values, 1, Parameters(2 * t));
    const std::vector<double> zero(a.size(), 0.0);
    std::vector<double> difference(a.size());
    std::transform(a.begin(), a.end(), b.begin(), difference.begin(), std::minus<double>());
    changes.push_back(Rms(difference, zero));
  }
  for (size_t k = 1; k < changes.size(); ++k)
  {
    EXPECT_LT(changes[k], changes[k - 1]);
  }
  EXPECT_LT(changes.back(), 1e-4);
}

TEST(MeshShockAdvection, InvariantToMeshScaleAndValueScale)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const std::vector<double> values = SphereStep(sphere, 0.3);
  const std::vector<double> reference = Filter(Build(sphere), values, 1, Parameters(128.0));
  const MeshData moved = shocktest::Transformed(sphere, 37.5, { 3.0, -20.0, 7.0 });
  std::vector<double> scaledValues = values;
  for (double& v : scaledValues)
  {
    v = 255.0 * v - 40.0;
  }
  std::vector<double> out = Filter(Build(moved), scaledValues, 1, Parameters(128.0));
  for (double& v : out)
  {
    v = (v + 40.0) / 255.0;
  }
  EXPECT_LT(MaxAbsDifference(out, reference), 1e-9);
}

TEST(MeshShockAdvection, OneAndTwoThreadsAgreeExactly)
{
  const MeshData sphere = shocktest::Icosphere(4);
  std::vector<double> rgb;
  for (size_t p = 0; p < sphere.points.size() / 3; ++p)
  {
    const double* x = PointOf(sphere, p);
    rgb.push_back(shocktest::SmoothStep(x[0], 0.2, 0.2));
    rgb.push_back(shocktest::SmoothStep(x[1], -0.1, 0.3));
    rgb.push_back(0.5 + 0.5 * std::sin(3 * x[2]));
  }
  for (shock::FlowMode mode : { shock::FlowMode::Fixed, shock::FlowMode::Composed })
  {
    shock::AdvectionParameters p = Parameters(200.0);
    p.flowMode = mode;
    p.flowUpdates = 3;
    p.numberOfThreads = 1;
    const std::vector<double> one = Filter(Build(sphere, 1), rgb, 3, p);
    p.numberOfThreads = 2;
    EXPECT_EQ(one, Filter(Build(sphere, 2), rgb, 3, p));
  }
}

TEST(MeshShockAdvection, ChannelsMoveTogether)
{
  // Two colours joined by a blurred edge: every output colour stays on the segment between them.
  const MeshData sphere = shocktest::Icosphere(4);
  const double c0[3] = { 0.9, 0.1, 0.3 }, c1[3] = { 0.2, 0.7, 0.95 };
  std::vector<double> rgb;
  for (size_t p = 0; p < sphere.points.size() / 3; ++p)
  {
    const double s = shocktest::SmoothStep(PointOf(sphere, p)[0], 0.0, 0.25);
    for (int c = 0; c < 3; ++c)
    {
      rgb.push_back((1 - s) * c0[c] + s * c1[c]);
    }
  }
  const std::vector<double> out = Filter(Build(sphere), rgb, 3, Parameters(512.0));
  for (size_t p = 0; p < out.size() / 3; ++p)
  {
    const double s = (out[3 * p] - c0[0]) / (c1[0] - c0[0]);
    for (int c = 1; c < 3; ++c)
    {
      EXPECT_NEAR(out[3 * p + c], (1 - s) * c0[c] + s * c1[c], 1e-9);
    }
  }
}

TEST(MeshShockAdvection, FlatPlaneAgreesWithTheImageFilter)
{
  // The same signal on an n x n image and on the plane grid triangulated from it.
  const int n = 64;
  const shock::GridShape grid = shocktest::Grid(n, n);
  const std::vector<double> values = shocktest::Bumps(grid, 1);
  const MeshData plane = shocktest::PlaneGrid(n, n);
  const double t = 1024.0;
  const shock::TriangleMesh triangles = Build(plane);
  const std::vector<double> mesh = Filter(triangles, values, 1, Parameters(t));
  // Lengths are normalised by the mean edge length, which the diagonals make
  // longer on the mesh; displacements scale as l^4 (P ~ l^2, u ~ l^3, x ~ l u t),
  // so the image time that matches the mesh's t is t (l_mesh / l_image)^4.
  const double matchingTime = t * std::pow(triangles.MeanEdgeLength() / grid.MeanEdgeLength(), 4);
  std::vector<double> image(values.size());
  ASSERT_TRUE(shock::AdvectGridSignal(grid, 1, values.data(), image.data(), Parameters(matchingTime)).Ok());
  // The discretisations differ (triangle vs square gradients, diagonal edges in
  // the mean edge length), so compare the changes made, away from the border.
  std::vector<double> meshChange, imageChange;
  for (int j = 4; j < n - 4; ++j)
  {
    for (int i = 4; i < n - 4; ++i)
    {
      const size_t s = static_cast<size_t>(j * n + i);
      meshChange.push_back(mesh[s] - values[s]);
      imageChange.push_back(image[s] - values[s]);
    }
  }
  const std::vector<double> zero(meshChange.size(), 0.0);
  const double imageChangeRms = Rms(imageChange, zero);
  ASSERT_GT(imageChangeRms, 0.01);
  EXPECT_LT(Rms(meshChange, imageChange), 0.35 * imageChangeRms);
}

TEST(MeshShockAdvection, SteppedTracingConvergesToFaceCrossing)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  const std::vector<double> values = SphereStep(sphere, 0.3);
  const std::vector<double> exact = Filter(mesh, values, 1, Parameters(32.0));
  std::vector<double> errors;
  for (double delta : { 0.2, 0.05, 0.0125 })
  {
    shock::AdvectionParameters p = Parameters(32.0);
    p.tracing = shock::Tracing::Stepped;
    p.stepFraction = delta;
    errors.push_back(Rms(Filter(mesh, values, 1, p), exact));
  }
  EXPECT_LT(errors[2], errors[0]);
  EXPECT_LT(errors[2], 0.01);
}

TEST(MeshShockAdvection, CellSignalsSharpenInRange)
{
  const MeshData sphere = shocktest::Icosphere(4);
  const shock::TriangleMesh mesh = Build(sphere);
  std::vector<double> cells(static_cast<size_t>(mesh.NumberOfTriangles()));
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const shock::Vec3 c = mesh.Centroid(f);
    cells[static_cast<size_t>(f)] = shocktest::SmoothStep(0.8 * c[2] + 0.6 * c[0], 0.1, 0.15);
  }
  const auto [lo, hi] = std::minmax_element(cells.begin(), cells.end());
  for (shock::Sampling sampling : { shock::Sampling::Linear, shock::Sampling::Nearest })
  {
    shock::AdvectionParameters p = Parameters(4096.0);
    p.sampling = sampling;
    const std::vector<double> out = Filter(mesh, cells, 1, p, shock::MeshLocation::Triangles);
    for (double v : out)
    {
      ASSERT_GE(v, *lo);
      ASSERT_LE(v, *hi);
    }
    EXPECT_LT(CountBetween(out, 0.1, 0.9), CountBetween(cells, 0.1, 0.9) / 3);
    if (sampling == shock::Sampling::Nearest)
    {
      // Nearest sampling copies input values.
      for (double v : out)
      {
        EXPECT_TRUE(std::find(cells.begin(), cells.end(), v) != cells.end());
      }
    }
  }
  EXPECT_EQ(Filter(mesh, cells, 1, Parameters(0.0), shock::MeshLocation::Triangles), cells);
}

TEST(MeshShockAdvection, FlowModes)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  const std::vector<double> values = SphereStep(sphere, 0.3);
  shock::AdvectionParameters p = Parameters(1024.0);
  const std::vector<double> fixed = Filter(mesh, values, 1, p);
  p.flowMode = shock::FlowMode::Composed;
  p.flowUpdates = 1;
  EXPECT_EQ(Filter(mesh, values, 1, p), fixed);
  for (shock::FlowMode mode : { shock::FlowMode::Composed, shock::FlowMode::Naive })
  {
    p.flowMode = mode;
    p.flowUpdates = 4;
    const std::vector<double> out = Filter(mesh, values, 1, p);
    EXPECT_NE(out, fixed);
    for (double v : out)
    {
      ASSERT_GE(v, 0.0);
      ASSERT_LE(v, 1.0);
    }
    EXPECT_LT(CountBetween(out, 0.1, 0.9), CountBetween(values, 0.1, 0.9) / 2);
  }
}

TEST(MeshShockAdvection, FlowFieldsAreTangentAndPointUphill)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  shock::MeshFlowFields fields;
  Filter(mesh, SphereStep(sphere, 0.3), 1, Parameters(1.0), shock::MeshLocation::Points, nullptr, &fields);
  ASSERT_EQ(fields.potential.size(), static_cast<size_t>(mesh.NumberOfPoints()));
  ASSERT_EQ(fields.flow.size(), static_cast<size_t>(3 * mesh.NumberOfTriangles()));
  for (double v : fields.potential)
  {
    EXPECT_GE(v, 0.0);
  }
  double moving = 0.0;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double* u = &fields.flow[static_cast<size_t>(3 * f)];
    const double* n = mesh.Normal(f);
    const double speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    EXPECT_LE(std::abs(u[0] * n[0] + u[1] * n[1] + u[2] * n[2]), 1e-9 * (1 + speed));
    moving = std::max(moving, speed);
  }
  EXPECT_GT(moving, 0.0);
}

TEST(MeshShockAdvection, NonFiniteValuesStayPut)
{
  const MeshData sphere = shocktest::Icosphere(3);
  const shock::TriangleMesh mesh = Build(sphere);
  std::vector<double> values = SphereStep(sphere, 0.3);
  values[17] = std::nan("");
  values[40] = INFINITY;
  const std::vector<double> out = Filter(mesh, values, 1, Parameters(512.0));
  EXPECT_TRUE(std::isnan(out[17]));
  EXPECT_EQ(out[40], INFINITY);
  for (size_t p = 0; p < out.size(); ++p)
  {
    if (p != 17 && p != 40)
    {
      ASSERT_TRUE(std::isfinite(out[p])) << p;
      EXPECT_GE(out[p], 0.0);
      EXPECT_LE(out[p], 1.0);
    }
  }
}

TEST(MeshShockAdvection, MeshDefectsGiveFiniteInRangeResults)
{
  const std::vector<std::pair<const char*, MeshData>> meshes = {
    { "holes", shocktest::WithHoles(shocktest::Icosphere(4), { { { 0.0, 0.0, 1.0 }, 0.4 }, { { 1.0, 0.0, 0.0 }, 0.3 } }) },
    { "non-manifold", shocktest::NonManifoldFan() },
    { "duplicate points", shocktest::WithDuplicatePoints(shocktest::Icosphere(4)) },
    { "degenerate", shocktest::WithDegenerateTriangles(shocktest::Icosphere(4)) },
    { "isolated points", shocktest::WithIsolatedPoints(shocktest::Icosphere(3), 5) },
    { "two components", shocktest::TwoComponents() },
  };
  for (const auto& [name, data] : meshes)
  {
    const shock::TriangleMesh mesh = Build(data);
    const std::vector<double> values = PointSignal(data, [](const double* x) {
      return shocktest::SmoothStep(0.8 * x[2] + 0.6 * x[0] + 0.3 * x[1], 0.1, 0.3);
    });
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    for (shock::Tracing tracing : { shock::Tracing::FaceCrossing, shock::Tracing::Stepped })
    {
      shock::AdvectionParameters p = Parameters(1e6);
      p.tracing = tracing;
      const std::vector<double> out = Filter(mesh, values, 1, p);
      ASSERT_TRUE(AllFinite(out)) << name;
      for (size_t i = 0; i < out.size(); ++i)
      {
        ASSERT_GE(out[i], *lo) << name;
        ASSERT_LE(out[i], *hi) << name;
        if (mesh.PointTriangles().Begin(static_cast<std::int64_t>(i)) ==
          mesh.PointTriangles().End(static_cast<std::int64_t>(i)))
        {
          EXPECT_EQ(out[i], values[i]) << name << ": a point without triangles keeps its value";
        }
      }
    }
  }
}

TEST(MeshShockAdvection, AbortReturnsTheInput)
{
  const MeshData sphere = shocktest::Icosphere(4);
  const shock::TriangleMesh mesh = Build(sphere);
  const std::vector<double> values = SphereStep(sphere, 0.3);
  shock::MeshSignal signal;
  signal.values = values.data();
  std::vector<double> out(values.size());
  int calls = 0;
  shock::AdvectionReport report;
  ASSERT_TRUE(shock::AdvectMeshSignal(mesh, signal, out.data(), Parameters(512.0), &report, nullptr,
    [&calls](double) { return ++calls < 2; }).Ok());
  EXPECT_TRUE(report.aborted);
  EXPECT_EQ(out, values);
  EXPECT_LE(calls, 2);
}

TEST(MeshShockAdvection, RejectsInvalidArguments)
{
  const MeshData plane = shocktest::PlaneGrid(4, 4);
  const shock::TriangleMesh mesh = Build(plane);
  std::vector<double> values(16, 1.0), out(16);
  shock::MeshSignal signal;
  signal.values = values.data();
  EXPECT_FALSE(shock::AdvectMeshSignal(mesh, signal, out.data(), Parameters(-1.0)).Ok());
  EXPECT_FALSE(shock::AdvectMeshSignal(mesh, signal, out.data(), Parameters(NAN)).Ok());
  EXPECT_FALSE(shock::AdvectMeshSignal(mesh, signal, values.data(), Parameters(1.0)).Ok());
  signal.components = 0;
  EXPECT_FALSE(shock::AdvectMeshSignal(mesh, signal, out.data(), Parameters(1.0)).Ok());
}

TEST(MeshShockAdvection, ConstantSignalIsUnchanged)
{
  const MeshData sphere = shocktest::Icosphere(2);
  const std::vector<double> values(sphere.points.size() / 3, 0.42);
  EXPECT_EQ(Filter(Build(sphere), values, 1, Parameters(1e3)), values);
}

} // namespace
