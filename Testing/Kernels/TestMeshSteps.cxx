// Each step of the mesh shock filter (section 4 and Appendix A of Prada and
// Kazhdan 2015) against an independent computation written from the paper, on
// small meshes that are irregular on purpose: jittered, curved, triangles of
// very different areas, several channels. The references compute gradients by
// solving the interpolation conditions, areas from cross products, and never
// use the mesh's hat gradients, weights or adjacency lists.
#include "TestMeshSteps.h"

namespace
{
using namespace shock;
using namespace meshsteps;


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
} // namespace
