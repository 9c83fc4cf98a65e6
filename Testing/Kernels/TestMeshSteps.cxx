// Each step of the mesh shock filter (section 4 and Appendix A of Prada and
// Kazhdan 2015) against an independent computation written from the paper, on
// small meshes that are irregular on purpose: jittered, curved, triangles of
// very different areas, several channels. The references compute gradients by
// solving the interpolation conditions, areas from cross products, and never
// use the mesh's hat gradients, weights or adjacency lists.
#include "MeshAdvect.h"
#include "MeshFlow.h"
#include "MeshShockAdvection.h"
#include "MeshTrace.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace
{
using namespace shock;
using V3 = std::array<double, 3>;

V3 Sub(const V3& a, const V3& b) { return { a[0] - b[0], a[1] - b[1], a[2] - b[2] }; }
V3 Add(const V3& a, const V3& b) { return { a[0] + b[0], a[1] + b[1], a[2] + b[2] }; }
V3 Mul(double s, const V3& a) { return { s * a[0], s * a[1], s * a[2] }; }
double Dot3(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 Cross3(const V3& a, const V3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
double Norm3(const V3& a) { return std::sqrt(Dot3(a, a)); }

/// A mesh as plain arrays, with its TriangleMesh.
struct SmallMesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  TriangleMesh mesh;

  int Points() const { return static_cast<int>(points.size() / 3); }
  int Triangles() const { return static_cast<int>(triangles.size() / 3); }
  V3 P(std::int64_t i) const { return { points[3 * i], points[3 * i + 1], points[3 * i + 2] }; }
  std::array<std::int64_t, 3> T(int f) const
  {
    return { triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2] };
  }
  double Area(int f) const
  {
    const auto t = T(f);
    return 0.5 * Norm3(Cross3(Sub(P(t[1]), P(t[0])), Sub(P(t[2]), P(t[0]))));
  }
  V3 Centre(int f) const
  {
    const auto t = T(f);
    return Mul(1.0 / 3.0, Add(Add(P(t[0]), P(t[1])), P(t[2])));
  }
  /// l-bar: each triangle's three edges, averaged (TriangleMesh's documented convention).
  double MeanEdge() const
  {
    double sum = 0.0;
    for (int f = 0; f < Triangles(); ++f)
    {
      const auto t = T(f);
      for (int e = 0; e < 3; ++e)
        sum += Norm3(Sub(P(t[(e + 1) % 3]), P(t[e])));
    }
    return sum / (3.0 * Triangles());
  }
  std::vector<std::set<std::int64_t>> Neighbours() const
  {
    std::vector<std::set<std::int64_t>> n(Points());
    for (int f = 0; f < Triangles(); ++f)
    {
      const auto t = T(f);
      for (int e = 0; e < 3; ++e)
      {
        n[t[e]].insert(t[(e + 1) % 3]);
        n[t[(e + 1) % 3]].insert(t[e]);
      }
    }
    return n;
  }
  void Build()
  {
    TriangleMeshView view;
    view.numberOfPoints = Points();
    view.points = points.data();
    view.numberOfTriangles = Triangles();
    view.triangles = triangles.data();
    ASSERT_TRUE(mesh.Build(view, 1).Ok());
  }
};

/// A jittered (nx x ny) sheet, diagonals chosen at random, height z(x, y).
SmallMesh Sheet(int nx, int ny, unsigned seed, double bend)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  SmallMesh m;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const bool inside = i > 0 && j > 0 && i + 1 < nx && j + 1 < ny;
      const double x = i + (inside ? jitter(random) : 0.0);
      const double y = 0.8 * j + (inside ? jitter(random) : 0.0);
      m.points.insert(m.points.end(), { x, y, bend * std::sin(0.9 * x) * std::cos(0.7 * y) });
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
    {
      const std::int64_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      if (random() % 2)
        m.triangles.insert(m.triangles.end(), { a, b, d, a, d, c });
      else
        m.triangles.insert(m.triangles.end(), { a, b, c, b, d, c });
    }
  return m;
}

/// Gradient of the linear interpolant of (f0, f1, f2) on a triangle: the vector g in
/// the triangle's plane with g . (x1 - x0) = f1 - f0 and g . (x2 - x0) = f2 - f0.
V3 RefGradient(const V3& x0, const V3& x1, const V3& x2, double f0, double f1, double f2)
{
  const V3 e1 = Sub(x1, x0), e2 = Sub(x2, x0);
  // g = a e1 + b e2 (in the plane); the Gram system.
  const double g11 = Dot3(e1, e1), g12 = Dot3(e1, e2), g22 = Dot3(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  const double a = ((f1 - f0) * g22 - (f2 - f0) * g12) / det;
  const double b = ((f2 - f0) * g11 - (f1 - f0) * g12) / det;
  return Add(Mul(a, e1), Mul(b, e2));
}

V3 RefTriangleGradient(const SmallMesh& m, const std::vector<double>& values, int C, int c, int f)
{
  const auto t = m.T(f);
  return RefGradient(m.P(t[0]), m.P(t[1]), m.P(t[2]), values[t[0] * C + c], values[t[1] * C + c],
    values[t[2] * C + c]);
}

std::vector<double> RefSmooth(const SmallMesh& m, int C, const std::vector<double>& in)
{
  const double l = m.MeanEdge();
  const auto ring = m.Neighbours();
  std::vector<double> out(in.size());
  for (int p = 0; p < m.Points(); ++p)
  {
    double total = 1.0;
    std::vector<double> sum(in.begin() + p * C, in.begin() + (p + 1) * C);
    for (std::int64_t w : ring[p])
    {
      const double d = Norm3(Sub(m.P(p), m.P(w))) / l;
      const double alpha = std::exp(-d * d);
      total += alpha;
      for (int c = 0; c < C; ++c)
        sum[c] += alpha * in[w * C + c];
    }
    for (int c = 0; c < C; ++c)
      out[p * C + c] = sum[c] / total;
  }
  return out;
}

std::vector<double> RefAreaAverage(const SmallMesh& m, const std::vector<double>& perTriangle)
{
  std::vector<double> sum(m.Points(), 0.0), area(m.Points(), 0.0);
  for (int f = 0; f < m.Triangles(); ++f)
    for (std::int64_t p : m.T(f))
    {
      sum[p] += m.Area(f) * perTriangle[f];
      area[p] += m.Area(f);
    }
  for (int p = 0; p < m.Points(); ++p)
    sum[p] /= area[p];
  return sum;
}

std::vector<double> Random(size_t count, unsigned seed, double low, double high)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(low, high);
  std::vector<double> v(count);
  for (double& x : v)
    x = u(random);
  return v;
}

TEST(MeshSteps, TheTestMeshIsIrregular)
{
  SmallMesh m = Sheet(5, 4, 3, 0.4);
  double smallest = 1e300, largest = 0.0;
  for (int f = 0; f < m.Triangles(); ++f)
  {
    smallest = std::min(smallest, m.Area(f));
    largest = std::max(largest, m.Area(f));
  }
  EXPECT_GT(largest / smallest, 2.0); // area weights differ from plain averages
  m.Build();
  EXPECT_NEAR(m.mesh.MeanEdgeLength(), m.MeanEdge(), 1e-14);
  for (int f = 0; f < m.Triangles(); ++f)
    EXPECT_NEAR(m.mesh.Area(f), m.Area(f), 1e-14);
}

TEST(MeshSteps, UmbrellaSmoothingUsesGaussianWeightsOfTheNormalisedEdgeLengths)
{
  SmallMesh m = Sheet(5, 4, 5, 0.4);
  m.Build();
  const int C = 3;
  const auto input = Random(m.Points() * C, 31, -1.0, 2.0);
  const auto weights = UmbrellaWeights(m.mesh, m.mesh.MeanEdgeLength(), 1);
  const std::vector<unsigned char> valid(m.Points(), 1);
  std::vector<double> once(input);
  UmbrellaSmooth(m.mesh, weights, valid, C, once, 1, 1);
  const auto expected = RefSmooth(m, C, input);
  for (size_t i = 0; i < once.size(); ++i)
    EXPECT_NEAR(once[i], expected[i], 1e-13) << i;
  EXPECT_GT(std::abs(once[7] - input[7]), 1e-3); // something changed
  std::vector<double> twice(input);
  UmbrellaSmooth(m.mesh, weights, valid, C, twice, 2, 1);
  const auto expectedTwice = RefSmooth(m, C, expected);
  for (size_t i = 0; i < twice.size(); ++i)
    EXPECT_NEAR(twice[i], expectedTwice[i], 1e-13) << i;
}

TEST(MeshSteps, TriangleGradientIsTheGradientOfTheLinearInterpolant)
{
  SmallMesh m = Sheet(5, 4, 7, 0.5);
  m.Build();
  const int C = 2;
  const auto values = Random(m.Points() * C, 37, -1.0, 1.0);
  const double l = 0.73; // gradients are in units of `length`
  for (int f = 0; f < m.Triangles(); ++f)
    for (int c = 0; c < C; ++c)
    {
      const V3 g = TriangleGradient(m.mesh, values.data(), C, c, f, l);
      const V3 r = Mul(l, RefTriangleGradient(m, values, C, c, f));
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(g[k], r[k], 1e-12) << f;
    }
}

TEST(MeshSteps, EnergySumsTheChannelsAndThePotentialIsAreaWeighted)
{
  SmallMesh m = Sheet(5, 4, 9, 0.4);
  m.Build();
  const int C = 3;
  const auto values = Random(m.Points() * C, 41, 0.0, 1.0);
  const double l = m.MeanEdge();
  std::vector<unsigned char> valid(m.Triangles(), 1);
  const auto energy = TriangleEnergy(m.mesh, values.data(), C, valid, l, 1);
  std::vector<double> expected(m.Triangles(), 0.0);
  for (int f = 0; f < m.Triangles(); ++f)
    for (int c = 0; c < C; ++c)
    {
      const V3 g = Mul(l, RefTriangleGradient(m, values, C, c, f));
      expected[f] += Dot3(g, g);
    }
  for (int f = 0; f < m.Triangles(); ++f)
    EXPECT_NEAR(energy[f], expected[f], 1e-12 * (1.0 + expected[f])) << f;

  std::vector<double> potential;
  TrianglesToPoints(m.mesh, 1, energy.data(), valid, potential, 1);
  const auto average = RefAreaAverage(m, expected);
  double plainDifference = 0.0;
  for (int p = 0; p < m.Points(); ++p)
    EXPECT_NEAR(potential[p], average[p], 1e-12 * (1.0 + average[p])) << p;
  // The plain average differs on this mesh: the test can tell them apart.
  for (int p = 0; p < m.Points(); ++p)
  {
    double sum = 0.0;
    int count = 0;
    for (int f = 0; f < m.Triangles(); ++f)
      for (std::int64_t q : m.T(f))
        if (q == p)
        {
          sum += expected[f];
          ++count;
        }
    plainDifference = std::max(plainDifference, std::abs(sum / count - average[p]));
  }
  EXPECT_GT(plainDifference, 1e-3);
  // Invalid triangles carry no energy and are left out of the averages.
  valid[4] = 0;
  EXPECT_EQ(TriangleEnergy(m.mesh, values.data(), C, valid, l, 1)[4], 0.0);
}

TEST(MeshSteps, FlowIsHalfThePotentialGradient)
{
  SmallMesh m = Sheet(5, 4, 11, 0.4);
  m.Build();
  const auto potential = Random(m.Points(), 43, 0.0, 3.0);
  const std::vector<unsigned char> valid(m.Triangles(), 1);
  const double l = 1.3;
  const auto flow = TriangleFlow(m.mesh, potential, valid, l, 1);
  for (int f = 0; f < m.Triangles(); ++f)
  {
    const V3 g = Mul(0.5 * l, RefTriangleGradient(m, potential, 1, 0, f));
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(flow[3 * f + k], g[k], 1e-12) << f;
  }
}

TEST(MeshSteps, TheKernelsFlowFieldsEqualTheAppendixPipeline)
{
  // Range normalisation, smoothing before both gradients, channels coupled,
  // area-weighted potential, u = 1/2 grad P, lengths in l-bar: chained by hand.
  SmallMesh m = Sheet(6, 5, 13, 0.4);
  m.Build();
  const int C = 3;
  auto values = Random(m.Points() * C, 47, -2.0, 1.0);
  values[5] = 3.0;
  const double range = 3.0 - *std::min_element(values.begin(), values.end());
  const double l = m.MeanEdge();
  for (int passes : { 0, 1, 2 })
  {
    std::vector<double> s(values);
    for (double& x : s)
      x /= range;
    for (int k = 0; k < passes; ++k)
      s = RefSmooth(m, C, s);
    std::vector<double> energy(m.Triangles(), 0.0);
    for (int f = 0; f < m.Triangles(); ++f)
      for (int c = 0; c < C; ++c)
      {
        const V3 g = Mul(l, RefTriangleGradient(m, s, C, c, f));
        energy[f] += Dot3(g, g);
      }
    auto potential = RefAreaAverage(m, energy);
    for (int k = 0; k < passes; ++k)
      potential = RefSmooth(m, 1, potential);

    MeshSignal signal;
    signal.components = C;
    signal.values = values.data();
    AdvectionParameters p;
    p.smoothingPasses = passes;
    MeshFlowFields fields;
    std::vector<double> out(values.size());
    ASSERT_TRUE(AdvectMeshSignal(m.mesh, signal, out.data(), p, nullptr, &fields).Ok());
    for (int q = 0; q < m.Points(); ++q)
      EXPECT_NEAR(fields.potential[q], potential[q], 1e-12 * (1.0 + potential[q])) << q;
    for (int f = 0; f < m.Triangles(); ++f)
    {
      const V3 u = Mul(0.5 * l, RefTriangleGradient(m, potential, 1, 0, f));
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(fields.flow[3 * f + k], u[k], 1e-12 * (1.0 + Norm3(u))) << f;
    }
  }
}

/// The 3D point of a surface point.
V3 Position(const SmallMesh& m, const SurfacePoint& q)
{
  const auto t = m.T(static_cast<int>(q.triangle));
  V3 x{ 0.0, 0.0, 0.0 };
  for (int k = 0; k < 3; ++k)
    x = Add(x, Mul(q.barycentric[k], m.P(t[k])));
  return x;
}

/// Two triangles hinged on the y axis: A flat at z = 0 (x < 0), B leaning back over A.
SmallMesh Hinge()
{
  SmallMesh m;
  m.points = { 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, -1.0, 1.0, 0.0, -0.3, 1.0, 1.0 };
  m.triangles = { 0, 1, 2, 1, 0, 3 };
  return m;
}

/// The minimum of `values` over the points within graph distance `rings` (breadth-first search).
std::vector<double> RefRingMinimum(const SmallMesh& m, const std::vector<double>& values, int rings)
{
  const auto n = m.Neighbours();
  std::vector<double> out(values.size());
  for (int p = 0; p < m.Points(); ++p)
  {
    std::map<std::int64_t, int> distance{ { p, 0 } };
    std::vector<std::int64_t> frontier{ p };
    double low = values[p];
    for (int r = 0; r < rings; ++r)
    {
      std::vector<std::int64_t> next;
      for (std::int64_t q : frontier)
        for (std::int64_t w : n[q])
          if (distance.emplace(w, r + 1).second)
          {
            next.push_back(w);
            low = std::min(low, values[w]);
          }
      frontier.swap(next);
    }
    out[p] = low;
  }
  return out;
}

TEST(MeshSteps, RingMinimumIsTheMinimumWithinTheGivenGraphDistance)
{
  SmallMesh m = Sheet(7, 6, 41, 0.3);
  m.Build();
  const auto values = Random(m.Points(), 43, 0.0, 5.0);
  const std::vector<unsigned char> valid(m.Points(), 1);
  for (int rings : { 1, 2, 4 })
  {
    const auto low = RingMinimum(m.mesh, valid, values, rings, 1);
    const auto expected = RefRingMinimum(m, values, rings);
    for (int p = 0; p < m.Points(); ++p)
      EXPECT_EQ(low[p], expected[p]) << "point " << p << ", rings " << rings;
  }
  // An invalid point neither gives its value nor takes another's.
  std::vector<unsigned char> some(valid);
  const auto global = std::min_element(values.begin(), values.end()) - values.begin();
  some[global] = 0;
  const auto low = RingMinimum(m.mesh, some, values, 1, 1);
  EXPECT_EQ(low[global], values[global]);
  const auto neighbours = m.Neighbours();
  for (std::int64_t w : neighbours[global])
    EXPECT_GT(low[w], values[global]) << w;
}

TEST(MeshSteps, CurvatureContrastKeepsPeaksAndRemovesWhatVariesLessThanTheFactor)
{
  SmallMesh m = Sheet(9, 9, 47, 0.2);
  m.Build();
  const std::vector<unsigned char> valid(m.Points(), 1);
  // A potential that varies by less than the factor (a curved surface): no potential left.
  const auto gentle = Random(m.Points(), 53, 1.0, 1.9);
  std::vector<double> p = gentle;
  CurvatureContrast(m.mesh, valid, p, 2.0, 4, 1);
  for (double v : p)
    EXPECT_EQ(v, 0.0);
  // A ridge over a zero floor (a blurred crease over flat sides): kept as it is.
  std::vector<double> ridge(m.Points(), 0.0);
  for (int p2 = 0; p2 < m.Points(); ++p2)
  {
    const double x = m.P(p2)[0] - 4.0;
    ridge[p2] = std::exp(-x * x);
  }
  // (every point's 4 rings reach a point with x far enough from the ridge that its value is ~0)
  std::vector<double> kept = ridge;
  CurvatureContrast(m.mesh, valid, kept, 8.0, 4, 1);
  const auto floor = RefRingMinimum(m, ridge, 4);
  for (int q = 0; q < m.Points(); ++q)
  {
    EXPECT_EQ(kept[q], std::max(0.0, ridge[q] - 8.0 * floor[q])) << q;
    EXPECT_NEAR(kept[q], ridge[q], 1e-3) << q;
  }
  // 0 is the paper: the potential to the last bit.
  std::vector<double> paper = gentle;
  CurvatureContrast(m.mesh, valid, paper, 0.0, 4, 1);
  EXPECT_EQ(paper, gentle);
}

TEST(MeshSteps, TraceCrossesAnEdgeIntoTheUnfoldedNextTriangle)
{
  // B leans back over A, so its flow away from the edge makes an obtuse angle
  // with A's flow in space, but an acute one once B is unfolded into A's plane:
  // the paper's <v, v0> > 0 is read in the unfolded frame, and the trace goes on.
  SmallMesh m = Hinge();
  m.Build();
  const V3 into = Mul(1.0 / Norm3({ -0.3, 0.0, 1.0 }), { -0.3, 0.0, 1.0 });
  const V3 vB = Add(into, { 0.0, 0.2, 0.0 });
  std::vector<double> velocity = { 1.0, 0.0, 0.0, vB[0], vB[1], vB[2] };
  ASSERT_LT(Dot3(vB, { 1.0, 0.0, 0.0 }), 0.0);
  AdvectionParameters p;
  p.tracing = Tracing::FaceCrossing;
  SurfacePoint q;
  q.triangle = 0;
  const V3 start = Position(m, q); // the centre of A: (-1/3, 1, 0)
  TraceOnMesh(m.mesh, velocity.data(), q, 0.6, p);
  ASSERT_EQ(q.triangle, 1);
  // 1/3 to reach the edge, then 0.6 - 1/3 along B's flow.
  const V3 expected = Add(Add(start, { 1.0 / 3.0, 0.0, 0.0 }), Mul(0.6 - 1.0 / 3.0, vB));
  const V3 x = Position(m, q);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(x[k], expected[k], 1e-12);
}

TEST(MeshSteps, TraceStopsWhereTheUnfoldedFlowReverses)
{
  SmallMesh m = Hinge();
  m.Build();
  const V3 into = Mul(1.0 / Norm3({ -0.3, 0.0, 1.0 }), { -0.3, 0.0, 1.0 });
  // B pushes back towards the edge: unfolded, against A's flow.
  const V3 vB = Add(Mul(-1.0, into), { 0.0, 0.1, 0.0 });
  std::vector<double> velocity = { 1.0, 0.0, 0.0, vB[0], vB[1], vB[2] };
  ASSERT_GT(Dot3(vB, { 1.0, 0.0, 0.0 }), 0.0); // acute in space
  for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
  {
    AdvectionParameters p;
    p.tracing = tracing;
    p.stepFraction = 0.01;
    SurfacePoint q;
    q.triangle = 0;
    const V3 start = Position(m, q);
    TraceOnMesh(m.mesh, velocity.data(), q, 2.0, p);
    const V3 x = Position(m, q);
    // At the edge x = 0, within one step of it for the stepped trace.
    const double step = tracing == Tracing::Stepped ? 0.01 * m.mesh.MeanEdgeLength() : 1e-12;
    EXPECT_NEAR(x[0], 0.0, step + 1e-12);
    EXPECT_NEAR(x[1], start[1], step + 1e-12);
  }
}

TEST(MeshSteps, TraceSlidesAlongAnEdgeBothTrianglesPushInto)
{
  // A's flow crosses the edge x = 0 at (1, +-1); B's, unfolded into A's plane,
  // is (-0.3, +-0.8): it pushes back into the edge yet makes an acute angle with
  // A's, so the trace neither stops nor enters B. The limit of the stepped
  // zig-zag is the Filippov velocity: the convex combination (1 - w) vA + w vB
  // with no component across the edge, w = 1 / 1.3, along the edge at speed
  // (1 - w) 1 + w 0.8. B leans back over A, so unfolding matters.
  SmallMesh m = Hinge();
  m.Build();
  const V3 into = Mul(1.0 / Norm3({ -0.3, 0.0, 1.0 }), { -0.3, 0.0, 1.0 }); // in B, away from the edge
  // Trace from the centre of A, (-1/3, 1, 0), with A's flow (1, sense, 0) and B's
  // flow `across` along `into` plus `along` along the edge (y): at the edge after 1/3.
  auto trace = [&](double sense, double across, double along, double t) {
    const V3 vB = Add(Mul(across, into), { 0.0, along, 0.0 });
    std::vector<double> velocity = { 1.0, sense, 0.0, vB[0], vB[1], vB[2] };
    AdvectionParameters p;
    p.tracing = Tracing::FaceCrossing;
    SurfacePoint q;
    q.triangle = 0;
    TraceOnMesh(m.mesh, velocity.data(), q, t, p);
    return q;
  };
  const double w = 1.0 / 1.3;
  const double speed = (1.0 - w) * 1.0 + w * 0.8;
  const double t = 0.6;
  for (const double sense : { 1.0, -1.0 })
  {
    const V3 x = Position(m, trace(sense, -0.3, 0.8 * sense, t));
    EXPECT_NEAR(x[0], 0.0, 1e-12) << sense;
    EXPECT_NEAR(x[1], 1.0 + sense / 3.0 + sense * speed * (t - 1.0 / 3.0), 1e-12) << sense;
    EXPECT_NEAR(x[2], 0.0, 1e-12) << sense;
  }
  // B's unfolded flow (-0.3, 0.2) makes an obtuse angle with A's (1, 1)
  // (-0.3 + 0.2 < 0): the flow reverses, the trace stops where it meets the edge.
  const V3 stop = Position(m, trace(1.0, -0.3, 0.2, t));
  EXPECT_NEAR(stop[0], 0.0, 1e-12);
  EXPECT_NEAR(stop[1], 4.0 / 3.0, 1e-12);
  // Where B's unfolded flow leaves the edge (+0.3 instead of -0.3) the trace enters B.
  const SurfacePoint entered = trace(1.0, 0.3, 0.8, t);
  EXPECT_EQ(entered.triangle, 1);
  const V3 expected = Add({ 0.0, 4.0 / 3.0, 0.0 }, Mul(t - 1.0 / 3.0, Add(Mul(0.3, into), { 0.0, 0.8, 0.0 })));
  const V3 x = Position(m, entered);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(x[k], expected[k], 1e-12);
}

TEST(MeshSteps, TraceStopsAtTheBoundaryAndWhenTheTimeIsUsedUp)
{
  SmallMesh m = Hinge();
  m.Build();
  std::vector<double> velocity = { -1.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  AdvectionParameters p;
  SurfacePoint q;
  q.triangle = 0;
  const V3 start = Position(m, q);
  TraceOnMesh(m.mesh, velocity.data(), q, 0.1, p);
  EXPECT_NEAR(Position(m, q)[0], start[0] - 0.1, 1e-12);
  // On to the boundary edge from (0, 0) to (-1, 1) or (-1, 1) to (0, 2): x = -1/3 - s, y = 1.
  TraceOnMesh(m.mesh, velocity.data(), q, 10.0, p);
  EXPECT_EQ(q.triangle, 0);
  EXPECT_NEAR(Position(m, q)[0], -1.0, 1e-12);
}

/// A flat irregular sheet (z = 0) for advection with a uniform velocity.
struct FlatCase
{
  SmallMesh m = Sheet(7, 6, 17, 0.0);
  V3 v{ 0.31, -0.17, 0.0 };
  FlatCase() { m.Build(); }
  static double I(const V3& x, int c) { return c == 0 ? 0.4 * x[0] - 0.9 * x[1] : 1.0 + 0.2 * x[1]; }
  /// Distance from x to the sheet's outer rectangle [0, 6] x [0, 4].
  static double Inside(const V3& x) { return std::min({ x[0], 6.0 - x[0], x[1], 4.0 - x[1] }); }
};

TEST(MeshSteps, AdvectVerticesAveragesTracesFromOffsetsIntoEachTriangle)
{
  // Appendix A AdvectVertices with a uniform back-trace velocity v on a flat
  // sheet: the trace from p's offset into triangle f ends at
  // p + 0.001 (centre(f) - p) + v t, and a linear signal is read exactly there.
  FlatCase flat;
  const SmallMesh& m = flat.m;
  const int C = 2;
  std::vector<double> values(m.Points() * C);
  for (int p = 0; p < m.Points(); ++p)
    for (int c = 0; c < C; ++c)
      values[p * C + c] = FlatCase::I(m.P(p), c);
  std::vector<double> velocity;
  for (int f = 0; f < m.Triangles(); ++f)
    velocity.insert(velocity.end(), flat.v.begin(), flat.v.end());
  const double t = 1.3;
  for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
  {
    AdvectionParameters p;
    p.tracing = tracing;
    const SurfaceTracer tracer(m.mesh, velocity.data(), p, m.mesh.MeanEdgeLength());
    AdvectionReport report;
    const ProgressFunction none;
    AdvectionPass pass{ m.mesh, tracer, t, Sampling::Linear, 1, none, 0.0, 1.0, report };
    const std::vector<unsigned char> valid(m.Points(), 1);
    const MeshSource source{ C, values.data(), nullptr, valid.data() };
    std::vector<double> out(values.size(), 123.0);
    ASSERT_TRUE(AdvectVertices(pass, source, out.data(), nullptr));
    int checked = 0;
    for (int q = 0; q < m.Points(); ++q)
    {
      if (FlatCase::Inside(m.P(q)) < Norm3(flat.v) * t + 0.01)
        continue; // a trace may reach the boundary
      double sum[2] = { 0.0, 0.0 };
      int traces = 0;
      for (int f = 0; f < m.Triangles(); ++f)
      {
        const auto tri = m.T(f);
        if (std::find(tri.begin(), tri.end(), q) == tri.end())
          continue;
        const V3 start = Add(m.P(q), Mul(0.001, Sub(m.Centre(f), m.P(q))));
        const V3 end = Add(start, Mul(t, flat.v));
        for (int c = 0; c < C; ++c)
          sum[c] += FlatCase::I(end, c);
        ++traces;
      }
      for (int c = 0; c < C; ++c)
        EXPECT_NEAR(out[q * C + c], sum[c] / traces, 1e-9) << q;
      ++checked;
    }
    EXPECT_GE(checked, 4);
  }
}

/// The triangle of the flat sheet that holds x (by barycentric signs).
int Holding(const SmallMesh& m, const V3& x)
{
  for (int f = 0; f < m.Triangles(); ++f)
  {
    const auto t = m.T(f);
    const V3 n = Cross3(Sub(m.P(t[1]), m.P(t[0])), Sub(m.P(t[2]), m.P(t[0])));
    bool inside = true;
    for (int e = 0; e < 3; ++e)
    {
      const V3 side = Cross3(Sub(m.P(t[(e + 1) % 3]), m.P(t[e])), Sub(x, m.P(t[e])));
      inside = inside && Dot3(side, n) > 1e-9;
    }
    if (inside)
      return f;
  }
  return -1;
}

TEST(MeshSteps, AdvectFacesReadsTheSignalWhereTheTraceFromTheCentreEnds)
{
  FlatCase flat;
  const SmallMesh& m = flat.m;
  const int C = 2;
  std::vector<double> cells = Random(m.Triangles() * C, 53, 0.0, 1.0);
  std::vector<double> points(m.Points() * C);
  for (int p = 0; p < m.Points(); ++p)
    for (int c = 0; c < C; ++c)
      points[p * C + c] = FlatCase::I(m.P(p), c);
  std::vector<double> velocity;
  for (int f = 0; f < m.Triangles(); ++f)
    velocity.insert(velocity.end(), flat.v.begin(), flat.v.end());
  const double t = 1.1;
  AdvectionParameters p;
  const SurfaceTracer tracer(m.mesh, velocity.data(), p, m.mesh.MeanEdgeLength());
  AdvectionReport report;
  const ProgressFunction none;
  const std::vector<unsigned char> valid(m.Points(), 1);
  const MeshSource source{ C, points.data(), cells.data(), valid.data() };
  std::vector<double> nearest(cells.size()), linear(cells.size());
  AdvectionPass byNearest{ m.mesh, tracer, t, Sampling::Nearest, 1, none, 0.0, 1.0, report };
  ASSERT_TRUE(AdvectFaces(byNearest, source, nearest.data(), nullptr));
  AdvectionPass byLinear{ m.mesh, tracer, t, Sampling::Linear, 1, none, 0.0, 1.0, report };
  ASSERT_TRUE(AdvectFaces(byLinear, source, linear.data(), nullptr));
  int checked = 0;
  for (int f = 0; f < m.Triangles(); ++f)
  {
    const V3 end = Add(m.Centre(f), Mul(t, flat.v));
    const int g = Holding(m, end);
    if (FlatCase::Inside(m.Centre(f)) < Norm3(flat.v) * t + 0.01 || g < 0)
      continue;
    for (int c = 0; c < C; ++c)
    {
      EXPECT_EQ(nearest[f * C + c], cells[g * C + c]) << f;
      EXPECT_NEAR(linear[f * C + c], FlatCase::I(end, c), 1e-9) << f;
    }
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

TEST(MeshSteps, SamplingIsBarycentricOrTheNearestCorner)
{
  SmallMesh m = Sheet(4, 4, 19, 0.5);
  m.Build();
  const int C = 2;
  const auto points = Random(m.Points() * C, 59, 0.0, 1.0);
  std::vector<unsigned char> valid(m.Points(), 1);
  const int f = 4;
  const auto t = m.T(f);
  SurfacePoint q;
  q.triangle = f;
  q.barycentric[0] = 0.2;
  q.barycentric[1] = 0.5;
  q.barycentric[2] = 0.3;
  const MeshSource source{ C, points.data(), nullptr, valid.data() };
  for (int c = 0; c < C; ++c)
  {
    double linear[2] = { 0.0, 0.0 };
    ASSERT_TRUE(SampleSurface(m.mesh, q, Sampling::Linear, source, linear));
    EXPECT_NEAR(linear[c],
      0.2 * points[t[0] * C + c] + 0.5 * points[t[1] * C + c] + 0.3 * points[t[2] * C + c], 1e-14);
  }
  // Nearest: the corner closest in space (not the largest coordinate: the triangle is irregular).
  const V3 x = Position(m, q);
  int closest = 0;
  for (int k = 1; k < 3; ++k)
    if (Norm3(Sub(x, m.P(t[k]))) < Norm3(Sub(x, m.P(t[closest]))))
      closest = k;
  double nearest[2] = { 0.0, 0.0 };
  ASSERT_TRUE(SampleSurface(m.mesh, q, Sampling::Nearest, source, nearest));
  EXPECT_EQ(nearest[1], points[t[closest] * C + 1]);
  // An invalid corner is left out and the others renormalised.
  valid[t[1]] = 0;
  double partial[2] = { 0.0, 0.0 };
  ASSERT_TRUE(SampleSurface(m.mesh, q, Sampling::Linear, source, partial));
  EXPECT_NEAR(partial[0], (0.2 * points[t[0] * C] + 0.3 * points[t[2] * C]) / 0.5, 1e-14);
}

std::vector<double> FilterMesh(const SmallMesh& m, const std::vector<double>& values, int C,
  const AdvectionParameters& p, double valueScale = 0.0)
{
  MeshSignal signal;
  signal.components = C;
  signal.values = values.data();
  signal.valueScale = valueScale;
  std::vector<double> out(values.size());
  EXPECT_TRUE(AdvectMeshSignal(m.mesh, signal, out.data(), p).Ok());
  return out;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

std::vector<double> StepSignal(const SmallMesh& m, int C)
{
  std::vector<double> v(m.Points() * C);
  for (int p = 0; p < m.Points(); ++p)
    for (int c = 0; c < C; ++c)
      v[p * C + c] = std::tanh(2.0 * (m.P(p)[0] - 3.0 + 0.5 * c + 0.3 * m.P(p)[1])) + 0.2 * c;
  return v;
}

TEST(MeshSteps, NaiveEqualsChainedFixedRunsWithTheInputsRange)
{
  SmallMesh m = Sheet(9, 7, 23, 0.3);
  m.Build();
  const int C = 2;
  const auto input = StepSignal(m, C);
  const auto [lo, hi] = std::minmax_element(input.begin(), input.end());
  const double range = *hi - *lo;
  const double t = 6.0;
  const int K = 3;
  AdvectionParameters naive;
  naive.time = t;
  naive.flowMode = FlowMode::Naive;
  naive.flowUpdates = K;
  const auto result = FilterMesh(m, input, C, naive);
  std::vector<double> chained = input;
  AdvectionParameters step;
  step.time = t / K;
  for (int k = 0; k < K; ++k)
    chained = FilterMesh(m, chained, C, step, range);
  EXPECT_LT(MaxDifference(result, chained), 1e-12);
  AdvectionParameters fixed;
  fixed.time = t;
  EXPECT_GT(MaxDifference(result, FilterMesh(m, input, C, fixed)), 1e-3);
  EXPECT_GT(MaxDifference(result, input), 1e-2);
}

TEST(MeshSteps, ComposedContinuesTheTracesAlongTheIntermediateFlow)
{
  SmallMesh m = Sheet(9, 7, 29, 0.3);
  m.Build();
  const int C = 2;
  const auto input = StepSignal(m, C);
  const auto [lo, hi] = std::minmax_element(input.begin(), input.end());
  const double range = *hi - *lo;
  const double t = 6.0;
  AdvectionParameters composed;
  composed.time = t;
  composed.flowMode = FlowMode::Composed;
  composed.flowUpdates = 2;
  const auto result = FilterMesh(m, input, C, composed);

  // The flows of the input and of the intermediate signal (the fixed flow for t/2).
  const auto flowOf = [&](const std::vector<double>& signal) {
    MeshSignal s;
    s.components = C;
    s.values = signal.data();
    s.valueScale = range;
    MeshFlowFields fields;
    std::vector<double> out(signal.size());
    EXPECT_TRUE(AdvectMeshSignal(m.mesh, s, out.data(), AdvectionParameters(), nullptr, &fields).Ok());
    for (double& u : fields.flow)
      u *= -m.mesh.MeanEdgeLength(); // back-trace velocity, world units
    return fields.flow;
  };
  AdvectionParameters half;
  half.time = t / 2;
  const auto v0 = flowOf(input);
  const auto v1 = flowOf(FilterMesh(m, input, C, half, range));
  const auto compose = [&](const std::vector<double>& second) {
    std::vector<double> out(input.size(), 0.0);
    std::vector<int> traces(m.Points(), 0);
    for (int p = 0; p < m.Points(); ++p)
      for (int f = 0; f < m.Triangles(); ++f)
      {
        const auto tri = m.T(f);
        if (std::find(tri.begin(), tri.end(), p) == tri.end())
          continue;
        SurfacePoint q;
        q.triangle = f;
        for (int k = 0; k < 3; ++k)
          q.barycentric[k] = tri[k] == p ? 1.0 - 0.001 * 2.0 / 3.0 : 0.001 / 3.0;
        TraceOnMesh(m.mesh, v0.data(), q, t / 2, AdvectionParameters());
        TraceOnMesh(m.mesh, second.data(), q, t / 2, AdvectionParameters());
        const auto e = m.T(static_cast<int>(q.triangle));
        for (int c = 0; c < C; ++c)
          for (int k = 0; k < 3; ++k)
            out[p * C + c] += q.barycentric[k] * input[e[k] * C + c];
        ++traces[p];
      }
    for (int p = 0; p < m.Points(); ++p)
      for (int c = 0; c < C; ++c)
        out[p * C + c] /= traces[p];
    return out;
  };
  EXPECT_LT(MaxDifference(result, compose(v1)), 1e-9);
  // Not the input's flow twice (the fixed flow), and not the naive mode.
  EXPECT_GT(MaxDifference(result, compose(v0)), 1e-4);
  AdvectionParameters naive = composed;
  naive.flowMode = FlowMode::Naive;
  EXPECT_GT(MaxDifference(result, FilterMesh(m, input, C, naive)), 1e-4);
}

} // namespace
