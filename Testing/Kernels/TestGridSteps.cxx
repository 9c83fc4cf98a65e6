// Each step of the grid shock filter (Appendix A of Prada and Kazhdan 2015)
// against an independent computation written from the paper, on small grids
// that are irregular on purpose: anisotropic spacing, several channels, uneven
// dimensions, random values. The references (TestGridReferences.h) loop over
// (i, j, k) coordinates and never use the kernel's strides, blocks or buffers.
// The fast paths against the plain ones: TestGridFastPaths.cxx.
#include "TestGridReferences.h"

namespace
{


TEST(GridSteps, UmbrellaSmoothingUsesGaussianWeightsOfTheNormalisedEdgeLengths)
{
  for (const RefGrid g : { RefGrid{ { 5, 4, 1 }, { 1.0, 2.5, 1.0 } },
         RefGrid{ { 4, 3, 3 }, { 0.7, 1.0, 1.9 } }, RefGrid{ { 1, 6, 1 }, { 1.0, 0.3, 1.0 } } })
  {
    const int C = 3;
    const auto input = Random(g.Samples() * C, 11);
    const auto expected = RefSmooth(g, C, input);
    std::vector<double> out(input.size());
    const auto check = [&](auto lattice) {
      SmoothPass(lattice, C, input.data(), 1.0, out.data(), nullptr, 2);
      for (size_t v = 0; v < out.size(); ++v)
        EXPECT_NEAR(out[v], expected[v], 1e-14) << v;
      // Something changed: the smoothing is not the identity.
      double change = 0.0;
      for (size_t v = 0; v < out.size(); ++v)
        change = std::max(change, std::abs(out[v] - input[v]));
      EXPECT_GT(change, 0.05);
      // Two passes are two applications; `scale` multiplies the result.
      std::vector<double> twice(out.size()), scratch(out.size());
      UmbrellaSmooth(lattice, C, input.data(), 3.0, twice.data(), scratch.data(), nullptr, 2, 2);
      const auto expectedTwice = RefSmooth(g, C, expected);
      for (size_t v = 0; v < out.size(); ++v)
        EXPECT_NEAR(twice[v], 3.0 * expectedTwice[v], 1e-13) << v;
    };
    switch (g.Shape().ActiveAxes())
    {
      case 1: check(Lattice<1>(g.Shape())); break;
      case 2: check(Lattice<2>(g.Shape())); break;
      default: check(Lattice<3>(g.Shape())); break;
    }
  }
}

TEST(GridSteps, UmbrellaSmoothingSkipsInvalidSamples)
{
  const RefGrid g{ { 5, 4, 1 }, { 1.0, 2.5, 1.0 } };
  const int C = 2;
  auto input = Random(g.Samples() * C, 12);
  std::vector<unsigned char> valid(g.Samples(), 1);
  valid[g.Index(2, 1, 0)] = 0;
  valid[g.Index(0, 3, 0)] = 0;
  input[g.Index(2, 1, 0) * C] = 1e6; // must not leak into its neighbours
  const auto expected = RefSmooth(g, C, input, &valid);
  std::vector<double> out(input.size());
  SmoothPass(Lattice<2>(g.Shape()), C, input.data(), 1.0, out.data(), valid.data(), 1);
  for (size_t v = 0; v < out.size(); ++v)
    EXPECT_NEAR(out[v], expected[v], 1e-9) << v;
  EXPECT_EQ(out[g.Index(2, 1, 0) * C], 1e6);
}

template <int D>
void CheckGradientsAndEnergy(const RefGrid& g, int C)
{
  const Lattice<D> L(g.Shape());
  const auto values = Random(g.Samples() * C, 13 + D, -2.0, 3.0);
  const auto faces = RefFaces(g);
  ASSERT_EQ(static_cast<std::int64_t>(faces.size()), L.numFaces);
  std::vector<double> energy(faces.size());
  FaceEnergy<D>(L, C, values.data(), nullptr, energy.data(), 1);
  for (size_t f = 0; f < faces.size(); ++f)
  {
    const auto c = faces[f];
    std::array<std::int64_t, D> coords;
    const auto axes = g.ActiveAxes();
    for (int d = 0; d < D; ++d)
      coords[d] = c[axes[d]];
    ASSERT_EQ(L.FaceIndex(coords), static_cast<std::int64_t>(f));
    for (int ch = 0; ch < C; ++ch)
    {
      const auto expected = RefFaceGradient(g, C, ch, values, c);
      const auto actual = FaceGradient<D>(L, values.data(), C, ch, L.SampleIndex(coords));
      for (int d = 0; d < D; ++d)
        EXPECT_NEAR(actual[d], expected[d], 1e-12) << "face " << f << " channel " << ch;
    }
    // Section 3.3: the energy sums the squared gradients of all channels.
    EXPECT_NEAR(energy[f], RefEnergy(g, C, values, c), 1e-11) << f;
  }
  // Invalid faces carry no energy.
  std::vector<unsigned char> validFace(faces.size(), 1);
  validFace[1] = 0;
  FaceEnergy<D>(L, C, values.data(), validFace.data(), energy.data(), 1);
  EXPECT_EQ(energy[1], 0.0);
  EXPECT_GT(energy[0], 0.0);
}

TEST(GridSteps, FaceGradientsAverageTheParallelEdgesAndEnergySumsChannels)
{
  CheckGradientsAndEnergy<1>(RefGrid{ { 6, 1, 1 }, { 0.8, 1.0, 1.0 } }, 2);
  CheckGradientsAndEnergy<2>(RefGrid{ { 4, 3, 1 }, { 1.0, 2.5, 1.0 } }, 3);
  CheckGradientsAndEnergy<3>(RefGrid{ { 3, 4, 3 }, { 0.6, 1.0, 1.7 } }, 2);
}

template <int D>
void CheckPotential(const RefGrid& g)
{
  const Lattice<D> L(g.Shape());
  const auto energy = Random(L.numFaces, 17 + D, 0.0, 5.0);
  const auto expected = RefPotential(g, energy);
  std::vector<double> potential(g.Samples());
  FacesToSamples<D>(L, energy.data(), nullptr, potential.data(), 1);
  for (int s = 0; s < g.Samples(); ++s)
    EXPECT_NEAR(potential[s], expected[s], 1e-13) << s;
  // Invalid faces are left out of the average (not counted as zero).
  std::vector<unsigned char> valid(L.numFaces, 1);
  valid[0] = 0;
  FacesToSamples<D>(L, energy.data(), valid.data(), potential.data(), 1);
  // Sample 0 (the grid's corner) has only face 0: nothing valid is left.
  EXPECT_EQ(potential[0], 0.0);
  // Sample 1 along x has faces 0 and (when D = 1) 1: the average is over face 1 alone.
  if (D == 1)
    EXPECT_NEAR(potential[1], energy[1], 1e-15);
}

TEST(GridSteps, PotentialAveragesTheAdjacentFaces)
{
  CheckPotential<1>(RefGrid{ { 7, 1, 1 }, { 1.0, 1.0, 1.0 } });
  CheckPotential<2>(RefGrid{ { 4, 5, 1 }, { 1.0, 2.5, 1.0 } });
  CheckPotential<3>(RefGrid{ { 3, 3, 4 }, { 1.0, 0.5, 2.0 } });
}

TEST(GridSteps, BackTraceVelocityIsMinusHalfThePotentialGradientInIndexUnits)
{
  const RefGrid g{ { 4, 3, 1 }, { 1.0, 2.5, 1.0 } };
  const Lattice<2> L(g.Shape());
  const auto potential = Random(g.Samples(), 19, 0.0, 4.0);
  std::vector<float> velocity(L.numFaces * 2);
  BackTraceVelocity<2>(L, potential.data(), nullptr, velocity.data(), 1);
  const double l = g.MeanEdge();
  const auto faces = RefFaces(g);
  for (size_t f = 0; f < faces.size(); ++f)
  {
    const auto grad = RefFaceGradient(g, 1, 0, potential, faces[f]);
    for (int d = 0; d < 2; ++d)
    {
      // u = 1/2 grad P in units of l-bar; the back trace moves by -u, in samples: / (h / l).
      const double expected = -0.5 * grad[d] / (g.spacing[d] / l);
      EXPECT_NEAR(velocity[f * 2 + d], expected, 1e-6 * (1.0 + std::abs(expected))) << f;
    }
  }
}

TEST(GridSteps, TheKernelsFlowFieldsEqualTheAppendixPipeline)
{
  // Section 3.3 and Appendix A chained: range normalisation, smoothing before
  // both gradients, channels coupled, area-weighted potential, u = 1/2 grad P.
  for (int passes : { 0, 1, 2 })
  {
    for (const RefGrid g :
      { RefGrid{ { 6, 5, 1 }, { 1.0, 2.5, 1.0 } }, RefGrid{ { 4, 3, 3 }, { 0.6, 1.0, 1.7 } } })
    {
      const int C = 3;
      auto input = Random(g.Samples() * C, 23 + passes, -1.0, 4.0);
      input[4] = 7.5; // the range spans all channels
      std::vector<double> potential;
      std::vector<std::vector<double>> flow;
      // The range is max - min over all channels.
      const double range = 7.5 - *std::min_element(input.begin(), input.end());
      RefFlow(g, C, input, range, passes, potential, flow);
      AdvectionParameters p;
      p.smoothingPasses = passes;
      GridFlowFields fields;
      std::vector<double> out(input.size());
      ASSERT_TRUE(AdvectGridSignal(g.Shape(), C, input.data(), out.data(), p, nullptr, &fields).Ok());
      double largest = 0.0;
      for (int s = 0; s < g.Samples(); ++s)
      {
        EXPECT_NEAR(fields.potential[s], potential[s], 1e-12 * (1.0 + potential[s])) << s;
        largest = std::max(largest, potential[s]);
      }
      EXPECT_GT(largest, 0.01);
      const auto axes = g.ActiveAxes();
      for (size_t f = 0; f < flow.size(); ++f)
        for (size_t d = 0; d < axes.size(); ++d)
          EXPECT_NEAR(fields.flow[f * 3 + axes[d]], flow[f][d], 2e-7 * (1.0 + std::abs(flow[f][d])))
            << "face " << f << " passes " << passes;
    }
  }
}

TEST(GridSteps, SamplingIsMultilinearOrNearest)
{
  const RefGrid g{ { 4, 3, 1 }, { 1.0, 2.5, 1.0 } };
  const Lattice<2> L(g.Shape());
  const int C = 2;
  const auto values = Random(g.Samples() * C, 29);
  const auto at = [&](int i, int j, int c) { return values[g.Index(i, j, 0) * C + c]; };
  const std::array<double, 2> q{ 1.3, 1.6 };
  Stencil<2> linear;
  ASSERT_TRUE(SampleGrid<2>(L, nullptr, Sampling::Linear, q, linear));
  for (int c = 0; c < C; ++c)
  {
    const double expected = 0.7 * 0.4 * at(1, 1, c) + 0.3 * 0.4 * at(2, 1, c) +
      0.7 * 0.6 * at(1, 2, c) + 0.3 * 0.6 * at(2, 2, c);
    EXPECT_NEAR(linear.Apply(values.data(), C, c), expected, 1e-14);
  }
  Stencil<2> nearest;
  ASSERT_TRUE(SampleGrid<2>(L, nullptr, Sampling::Nearest, q, nearest));
  for (int c = 0; c < C; ++c)
    EXPECT_EQ(nearest.Apply(values.data(), C, c), at(1, 2, c));
  // At the grid's far corner the cell is the last one.
  Stencil<2> corner;
  ASSERT_TRUE(SampleGrid<2>(L, nullptr, Sampling::Linear, { 3.0, 2.0 }, corner));
  EXPECT_NEAR(corner.Apply(values.data(), C, 1), at(3, 2, 1), 1e-15);
  // An invalid corner is left out and the other weights renormalised.
  std::vector<unsigned char> valid(g.Samples(), 1);
  valid[g.Index(2, 2, 0)] = 0;
  Stencil<2> partial;
  ASSERT_TRUE(SampleGrid<2>(L, valid.data(), Sampling::Linear, q, partial));
  const double total = 0.7 * 0.4 + 0.3 * 0.4 + 0.7 * 0.6;
  EXPECT_NEAR(partial.Apply(values.data(), C, 0),
    (0.7 * 0.4 * at(1, 1, 0) + 0.3 * 0.4 * at(2, 1, 0) + 0.7 * 0.6 * at(1, 2, 0)) / total, 1e-14);
  // Nearest falls back to the linear rule when the nearest sample is invalid.
  valid[g.Index(1, 2, 0)] = 0;
  Stencil<2> fallback;
  ASSERT_TRUE(SampleGrid<2>(L, valid.data(), Sampling::Nearest, q, fallback));
  EXPECT_NEAR(fallback.Apply(values.data(), C, 0),
    (0.7 * 0.4 * at(1, 1, 0) + 0.3 * 0.4 * at(2, 1, 0)) / (0.7 * 0.4 + 0.3 * 0.4), 1e-14);
}

/// A 2D lattice with a hand-made velocity per face (index units).
struct HandFlow
{
  RefGrid g;
  Lattice<2> L;
  std::vector<float> v;
  explicit HandFlow(RefGrid grid)
    : g(grid)
    , L(grid.Shape())
    , v(static_cast<size_t>(L.numFaces * 2), 0.0f)
  {
  }
  void Set(int i, int j, float vx, float vy)
  {
    const auto f = L.FaceIndex({ i, j });
    v[f * 2] = vx;
    v[f * 2 + 1] = vy;
  }
  std::array<double, 2> Trace(std::array<double, 2> q, double t, Tracing tracing, double delta = 0.1)
  {
    AdvectionParameters p;
    p.tracing = tracing;
    p.stepFraction = delta;
    const GridTracer<2> tracer(L, v.data(), p);
    std::array<std::int64_t, 2> c;
    const auto f = tracer.FaceOf(q, c);
    bool truncated = false;
    tracer.Trace(q, c, f, t, truncated);
    EXPECT_FALSE(truncated);
    return q;
  }
};

TEST(GridSteps, TraceMovesUntilTheTimeIsUsedUp)
{
  HandFlow h(RefGrid{ { 6, 5, 1 }, { 1.0, 2.5, 1.0 } });
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i)
      h.Set(i, j, 0.5f, 0.25f);
  for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
  {
    const auto q = h.Trace({ 0.3, 0.4 }, 3.0, tracing);
    EXPECT_NEAR(q[0], 1.8, 1e-9);
    EXPECT_NEAR(q[1], 1.15, 1e-9);
  }
}

TEST(GridSteps, TraceStopsAtTheGridBoundary)
{
  HandFlow h(RefGrid{ { 6, 5, 1 }, { 1.0, 2.5, 1.0 } });
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i)
      h.Set(i, j, -1.0f, 0.5f);
  // Leaves through x = 0 after 0.3: y has moved by 0.15 only.
  const auto q = h.Trace({ 0.3, 0.4 }, 10.0, Tracing::FaceCrossing);
  EXPECT_NEAR(q[0], 0.0, 1e-12);
  EXPECT_NEAR(q[1], 0.55, 1e-9);
  const auto s = h.Trace({ 0.3, 0.4 }, 10.0, Tracing::Stepped);
  EXPECT_NEAR(s[0], 0.0, 1e-12);
  EXPECT_LE(s[1], 0.55 + 0.1);
}

TEST(GridSteps, TraceStopsWhereTheFlowReversesInThePhysicalMetric)
{
  // Spacing (1, 3): face (1, 0)'s velocity (0.2, -1) makes an acute angle with
  // face (0, 0)'s (1, 0.1) in index space (0.2 - 0.1 > 0) but an obtuse one in
  // space (0.2 h_x^2 - 0.1 h_y^2 < 0): the paper's <v, v0> > 0 is measured in space.
  HandFlow h(RefGrid{ { 3, 2, 1 }, { 1.0, 3.0, 1.0 } });
  h.Set(0, 0, 1.0f, 0.1f);
  h.Set(1, 0, 0.2f, -1.0f);
  const auto q = h.Trace({ 0.5, 0.5 }, 5.0, Tracing::FaceCrossing);
  EXPECT_NEAR(q[0], 1.0, 1e-9);
  EXPECT_NEAR(q[1], 0.55, 1e-7);
  // The stepped trace stops after its first step into face (1, 0).
  const auto s = h.Trace({ 0.5, 0.5 }, 5.0, Tracing::Stepped, 0.05);
  EXPECT_GT(s[0], 1.0);
  EXPECT_LT(s[0], 1.0 + 0.1);
  // Something changed: with an acute angle in space the trace goes on.
  h.Set(1, 0, 1.0f, 0.05f);
  EXPECT_NEAR(h.Trace({ 0.5, 0.5 }, 1.0, Tracing::FaceCrossing)[0], 1.5, 1e-7);
}


TEST(GridSteps, AdvectVerticesAveragesTheTracesFromTheOffsetsIntoTheAdjacentFaces)
{
  // A uniform back-trace velocity and a linear signal: each trace ends at
  // (its offset start) + v t, clipped where it meets the boundary, and the
  // linear signal is read exactly there. The result is the average over the
  // sample's adjacent faces (Appendix A AdvectVertices, epsilon = 0.001).
  const RefGrid g{ { 6, 5, 1 }, { 1.0, 2.5, 1.0 } };
  const Lattice<2> L(g.Shape());
  const int C = 2;
  std::vector<double> values(g.Samples() * C);
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i)
    {
      values[g.Index(i, j, 0) * C] = 0.3 * i - 0.7 * j;
      values[g.Index(i, j, 0) * C + 1] = 2.0 + 0.1 * i + 0.4 * j;
    }
  const std::array<double, 2> v{ 0.6, -0.35 };
  std::vector<float> velocity(L.numFaces * 2);
  for (std::int64_t f = 0; f < L.numFaces; ++f)
  {
    velocity[f * 2] = static_cast<float>(v[0]);
    velocity[f * 2 + 1] = static_cast<float>(v[1]);
  }
  AdvectionParameters p;
  const GridTracer<2> tracer(L, velocity.data(), p);
  AdvectionReport report;
  const ProgressFunction none;
  const AdvectionContext<2> ctx{ L, C, 1, Sampling::Linear, nullptr, none, report };
  const double t = 1.7;
  std::vector<double> out(values.size());
  ASSERT_TRUE(AdvectVertices<2>(ctx, tracer, t, values.data(), Into(out, C), nullptr, RowBlocks<2>(L.n), 0.0, 1.0));
  const double vx = static_cast<float>(v[0]), vy = static_cast<float>(v[1]);
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i)
    {
      double sum[2] = { 0.0, 0.0 };
      int traces = 0;
      for (int dj = -1; dj <= 0; ++dj)
        for (int di = -1; di <= 0; ++di)
        {
          const int fi = i + di, fj = j + dj;
          if (fi < 0 || fj < 0 || fi >= g.n[0] - 1 || fj >= g.n[1] - 1)
            continue;
          // The start, offset by epsilon x (face centre - sample) = epsilon (+-1/2, +-1/2).
          double x = i + 0.001 * (fi + 0.5 - i), y = j + 0.001 * (fj + 0.5 - j);
          // Straight until the time is used up or the boundary is met.
          const double tx = vx > 0 ? (g.n[0] - 1 - x) / vx : x / -vx;
          const double ty = vy > 0 ? (g.n[1] - 1 - y) / vy : y / -vy;
          const double te = std::min({ t, tx, ty });
          x += vx * te;
          y += vy * te;
          sum[0] += 0.3 * x - 0.7 * y;
          sum[1] += 2.0 + 0.1 * x + 0.4 * y;
          ++traces;
        }
      for (int c = 0; c < C; ++c)
        EXPECT_NEAR(out[g.Index(i, j, 0) * C + c], sum[c] / traces, 1e-9) << i << "," << j;
    }
  EXPECT_GT(report.traceSteps, 0u);
}

TEST(GridSteps, TheSignalsRangeIsItsSmallestAndLargestValue)
{
  // The range that normalises the intensities: 8-bit samples scanned in parts
  // per thread; float samples also say whether every value is finite.
  std::mt19937 random(5);
  std::uniform_int_distribution<int> byte(40, 200);
  for (const std::int64_t samples : { std::int64_t(1), std::int64_t(7), std::int64_t(1001) })
  {
    for (int where = 0; where < 3; ++where)
    {
      const int C = 3;
      std::vector<unsigned char> values(static_cast<size_t>(samples * C));
      for (auto& v : values)
        v = static_cast<unsigned char>(byte(random));
      // The extremes at the ends, or in the middle of the array.
      const size_t n = values.size();
      const size_t low = where == 0 ? 0 : (where == 1 ? n - 1 : n / 2);
      const size_t high = where == 0 ? n - 1 : (where == 1 ? 0 : n / 2 + 1);
      values[low] = 3;
      values[high] = 251;
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      for (int threads : { 1, 2, 3 })
      {
        const SignalRange range = ScanSignal(samples, C, values.data(), threads);
        EXPECT_EQ(range.low, static_cast<double>(*lo)) << samples << " " << where << " " << threads;
        EXPECT_EQ(range.high, static_cast<double>(*hi)) << samples << " " << where << " " << threads;
        EXPECT_TRUE(range.allFinite);
      }
      EXPECT_EQ(*lo, 3);
      EXPECT_EQ(*hi, 251);
    }
  }
  // Floats: a sample with a non-finite component takes no part.
  std::vector<float> floats = { 0.5f, 2.0f, -1.0f, 7.0f, std::numeric_limits<float>::quiet_NaN(),
    100.0f, 3.0f, -4.0f };
  for (int threads : { 1, 2 })
  {
    const SignalRange range = ScanSignal(4, 2, floats.data(), threads);
    EXPECT_EQ(range.low, -4.0);
    EXPECT_EQ(range.high, 7.0);
    EXPECT_FALSE(range.allFinite);
  }
}

} // namespace
