// Unit tests of the VTK-free grid kernel: properties of the shock filter that
// must hold on any input (paper sections 3.2-3.3), on synthetic grids.
#include "GridShockAdvection.h"
#include "TestSignals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace
{
using namespace shock;
using namespace shocktest;

AdvectionParameters WithTime(double t)
{
  AdvectionParameters p;
  p.time = t;
  return p;
}

TEST(GridShockAdvection, ZeroTimeReturnsTheInputExactly)
{
  for (const GridShape& shape : { Grid(40, 30), Grid(12, 10, 8) })
  {
    const auto input = Bumps(shape, 3);
    for (FlowMode mode : { FlowMode::Fixed, FlowMode::Composed, FlowMode::Naive })
    {
      AdvectionParameters p = WithTime(0.0);
      p.flowMode = mode;
      p.flowUpdates = 3;
      EXPECT_EQ(Filter(shape, 3, input, p), input);
    }
  }
}

TEST(GridShockAdvection, OutputStaysWithinTheInputRange)
{
  const GridShape shape = Grid(48, 40);
  const auto input = Noisy(Bumps(shape, 1), 0.05, 7);
  const auto [low, high] = std::minmax_element(input.begin(), input.end());
  const double eps = 1e-12 * (*high - *low);
  for (FlowMode mode : { FlowMode::Fixed, FlowMode::Composed, FlowMode::Naive })
  {
    for (Sampling sampling : { Sampling::Linear, Sampling::Nearest })
    {
      for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
      {
        for (double t : { 1.0, 64.0, 1e4 })
        {
          AdvectionParameters p = WithTime(t);
          p.flowMode = mode;
          p.flowUpdates = 4;
          p.sampling = sampling;
          p.tracing = tracing;
          const auto out = Filter(shape, 1, input, p);
          const auto [outLow, outHigh] = std::minmax_element(out.begin(), out.end());
          EXPECT_GE(*outLow, *low - eps);
          EXPECT_LE(*outHigh, *high + eps);
          // The identity keeps the range too: the filter must also have changed the
          // signal (Nearest sampling reads the samples themselves until traces
          // move half a sample).
          if (sampling == Sampling::Linear || t > 1000.0)
          {
            EXPECT_GT(MeanAbsDifference(out, input), 1e-5) << "t = " << t;
          }
        }
      }
    }
  }
}

TEST(GridShockAdvection, SmoothExtremumKeepsItsValue)
{
  // An isolated Gaussian bump: the flow vanishes at its top, so the maximum stays.
  const GridShape shape = Grid(61, 61);
  std::vector<double> input(shape.NumberOfSamples());
  for (int j = 0; j < 61; ++j)
  {
    for (int i = 0; i < 61; ++i)
    {
      input[j * 61 + i] = std::exp(-((i - 30.0) * (i - 30.0) + (j - 30.0) * (j - 30.0)) / 50.0);
    }
  }
  for (double t : { 10.0, 1000.0, 1e6 })
  {
    const auto out = Filter(shape, 1, input, WithTime(t));
    EXPECT_NEAR(out[30 * 61 + 30], 1.0, 0.005) << "t = " << t;
    EXPECT_NEAR(*std::max_element(out.begin(), out.end()), 1.0, 0.005);
    // ...while the flanks of the bump do move (the identity would keep the top too).
    EXPECT_GT(MaxAbsDifference(out, input), t > 100.0 ? 0.01 : 1e-3) << "t = " << t;
  }
}

TEST(GridShockAdvection, StableAndFiniteForHugeTimes)
{
  for (const GridShape& shape : { Grid(64, 48), Grid(16, 14, 12), Grid(200, 1) })
  {
    const auto input = Noisy(Bumps(shape, 1), 0.02, 3);
    const auto [low, high] = std::minmax_element(input.begin(), input.end());
    AdvectionReport report;
    const auto out = Filter(shape, 1, input, WithTime(1e9), &report);
    for (double v : out)
    {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, *low - 1e-12);
      ASSERT_LE(v, *high + 1e-12);
    }
    EXPECT_EQ(report.truncatedTraces, 0u);
  }
}

TEST(GridShockAdvection, ConvergesToASteadyState)
{
  // Times are range-normalised: a blur of sigma samples needs t of order sigma^4
  // to sharpen, so the steady state of this noisy signal is reached near t = 1e7.
  const GridShape shape = Grid(96, 96);
  const auto input = Noisy(Bumps(shape, 1), 0.02, 9);
  std::vector<double> changes;
  for (double t : { 65536.0, 262144.0, 1048576.0, 4194304.0, 16777216.0 })
  {
    changes.push_back(MeanAbsDifference(Filter(shape, 1, input, WithTime(t)),
      Filter(shape, 1, input, WithTime(2 * t))));
  }
  for (size_t k = 1; k < changes.size(); ++k)
  {
    EXPECT_LT(changes[k], changes[k - 1]);
  }
  EXPECT_LT(changes.back(), 1e-4 * Range(input));
}

TEST(GridShockAdvection, PreservesTotalVariationIn1D)
{
  const GridShape shape = Grid(400, 1);
  std::vector<double> input(400);
  for (int i = 0; i < 400; ++i)
  {
    input[i] = SmoothStep(i, 80, 4) - 0.7 * SmoothStep(i, 200, 6) + 0.4 * SmoothStep(i, 300, 3) +
      0.2 * std::exp(-(i - 350.0) * (i - 350.0) / 40.0);
  }
  const double tv = TotalVariation(input);
  for (double t : { 16.0, 256.0, 4096.0 })
  {
    const auto out = Filter(shape, 1, input, WithTime(t));
    EXPECT_NEAR(TotalVariation(out), tv, 0.005 * tv) << "t = " << t;
    // The identity keeps the total variation too: the steps must have sharpened.
    EXPECT_LT(RiseWidth(out.data() + 60, 40), RiseWidth(input.data() + 60, 40)) << "t = " << t;
  }
}

TEST(GridShockAdvection, BlurredStepBecomesSharper)
{
  const GridShape shape = Grid(80, 20);
  std::vector<double> input(shape.NumberOfSamples());
  for (int j = 0; j < 20; ++j)
  {
    for (int i = 0; i < 80; ++i)
    {
      input[j * 80 + i] = SmoothStep(i, 40.3, 4.0);
    }
  }
  const double before = RiseWidth(&input[10 * 80], 80);
  double previous = before;
  for (double t : { 256.0, 4096.0, 65536.0 })
  {
    const auto out = Filter(shape, 1, input, WithTime(t));
    const double width = RiseWidth(&out[10 * 80], 80);
    EXPECT_LE(width, previous + 1e-9);
    previous = width;
  }
  EXPECT_LT(previous, 0.25 * before);
}

TEST(GridShockAdvection, ConstantImageIsUnchanged)
{
  const GridShape shape = Grid(30, 20, 5);
  const std::vector<double> input(shape.NumberOfSamples() * 2, 0.37);
  EXPECT_EQ(Filter(shape, 2, input, WithTime(100.0)), input);
}

TEST(GridShockAdvection, PotentialIsSummedOverChannels)
{
  // Section 3.3: one flow for all channels, from the sum of |grad I_j|^2.
  const GridShape shape = Grid(40, 30);
  const auto a = Bumps(shape, 1);
  auto b = Bumps(shape, 1, 0.7);
  std::vector<double> both(2 * a.size());
  for (size_t s = 0; s < a.size(); ++s)
  {
    both[2 * s] = a[s];
    both[2 * s + 1] = b[s];
  }
  // Same range for all three signals, so the normalisations agree.
  ASSERT_DOUBLE_EQ(Range(a), Range(b));
  GridFlowFields fa, fb, fab;
  Filter(shape, 1, a, WithTime(1.0), nullptr, &fa);
  Filter(shape, 1, b, WithTime(1.0), nullptr, &fb);
  Filter(shape, 2, both, WithTime(1.0), nullptr, &fab);
  for (size_t s = 0; s < a.size(); ++s)
  {
    ASSERT_NEAR(fab.potential[s], fa.potential[s] + fb.potential[s], 1e-12);
  }
}

TEST(GridShockAdvection, ColouredEdgeHasNoFringes)
{
  // A blurred edge between two colours: every output colour stays on the segment
  // between them, because all channels are sampled at the same traced points.
  const GridShape shape = Grid(50, 40);
  const double A[3] = { 200, 30, 40 }, B[3] = { 20, 90, 220 };
  std::vector<double> input(3 * shape.NumberOfSamples());
  for (int j = 0; j < 40; ++j)
  {
    for (int i = 0; i < 50; ++i)
    {
      const double s = SmoothStep(i + 0.4 * j, 33, 3);
      for (int c = 0; c < 3; ++c)
      {
        input[3 * (j * 50 + i) + c] = (1 - s) * A[c] + s * B[c];
      }
    }
  }
  const auto out = Filter(shape, 3, input, WithTime(256.0));
  // The identity has no fringes either: the edge must have sharpened.
  {
    std::vector<double> before(50), after(50);
    for (int i = 0; i < 50; ++i)
    {
      before[i] = input[3 * (20 * 50 + i)];
      after[i] = out[3 * (20 * 50 + i)];
    }
    EXPECT_LT(RiseWidth(after.data(), 50), 0.8 * RiseWidth(before.data(), 50));
  }
  for (size_t s = 0; s < out.size() / 3; ++s)
  {
    const double u = (out[3 * s] - A[0]) / (B[0] - A[0]);
    ASSERT_GE(u, -1e-9);
    ASSERT_LE(u, 1 + 1e-9);
    for (int c = 1; c < 3; ++c)
    {
      ASSERT_NEAR(out[3 * s + c], (1 - u) * A[c] + u * B[c], 1e-9);
    }
  }
}

TEST(GridShockAdvection, InvariantToIntensityScaleAndOffset)
{
  const GridShape shape = Grid(40, 36);
  const auto input = Noisy(Bumps(shape, 1), 0.03, 11);
  std::vector<double> scaled(input);
  for (double& v : scaled)
  {
    v = 255.0 * v + 17.0;
  }
  const auto out = Filter(shape, 1, input, WithTime(200.0));
  const auto outScaled = Filter(shape, 1, scaled, WithTime(200.0));
  for (size_t s = 0; s < out.size(); ++s)
  {
    ASSERT_NEAR(outScaled[s], 255.0 * out[s] + 17.0, 1e-9 * 255.0);
  }
}

TEST(GridShockAdvection, InvariantToUniformSpacingScale)
{
  for (const auto& spacing : { std::array<double, 3>{ 1, 1, 1 }, std::array<double, 3>{ 1, 2.5, 1.5 } })
  {
    GridShape a = Grid(32, 28, 6);
    a.spacing = spacing;
    GridShape b = a;
    for (double& s : b.spacing)
    {
      s *= 3.7;
    }
    const auto input = Bumps(a, 1);
    EXPECT_LT(MaxAbsDifference(Filter(a, 1, input, WithTime(300.0)), Filter(b, 1, input, WithTime(300.0))),
      1e-6);
  }
}

TEST(GridShockAdvection, ComposedWithOneUpdateEqualsFixed)
{
  const GridShape shape = Grid(40, 32);
  const auto input = Bumps(shape, 3);
  AdvectionParameters composed = WithTime(500.0);
  composed.flowMode = FlowMode::Composed;
  composed.flowUpdates = 1;
  EXPECT_LT(MaxAbsDifference(Filter(shape, 3, input, composed), Filter(shape, 3, input, WithTime(500.0))),
    1e-5 * Range(input));
}

TEST(GridShockAdvection, MultiStepModesConvergeToFixedForShortTimes)
{
  // For a short time the flow barely changes, so all three modes nearly agree:
  // their difference from the fixed flow is a small fraction of what the fixed
  // flow itself changes, and it shrinks as the time does.
  const GridShape shape = Grid(40, 32);
  const auto input = Bumps(shape, 1);
  for (FlowMode mode : { FlowMode::Composed, FlowMode::Naive })
  {
    double previous = 0.0;
    for (double t : { 8.0, 2.0 })
    {
      const auto fixed = Filter(shape, 1, input, WithTime(t));
      const double change = MeanAbsDifference(fixed, input);
      EXPECT_GT(change, 1e-5 * t);
      AdvectionParameters p = WithTime(t);
      p.flowMode = mode;
      p.flowUpdates = 4;
      const double difference = MeanAbsDifference(Filter(shape, 1, input, p), fixed);
      EXPECT_LT(difference, 0.2 * change) << "t " << t;
      if (previous > 0.0)
      {
        EXPECT_LT(difference, previous) << "t " << t;
      }
      previous = difference;
    }
  }
}

TEST(GridShockAdvection, TheTestSignalHasItsBumpsOnEveryGrid)
{
  // Bumps() must not degenerate to a straight edge on flat grids: it has an
  // interior local maximum and minimum in 1D, 2D and 3D.
  for (const GridShape& shape : { Grid(60, 1), Grid(40, 32), Grid(14, 12, 10) })
  {
    const auto v = Bumps(shape, 1);
    const auto& n = shape.dimensions;
    int maxima = 0, minima = 0;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 1; i + 1 < n[0]; ++i)
        {
          const auto at = [&](int a, int b, int c) {
            a = std::clamp(a, 0, n[0] - 1);
            b = std::clamp(b, 0, n[1] - 1);
            c = std::clamp(c, 0, n[2] - 1);
            return v[static_cast<size_t>((c * n[1] + b) * n[0] + a)];
          };
          const double x = at(i, j, k);
          bool high = true, low = true;
          for (const auto& d : { std::array<int, 3>{ 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 },
                 { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } })
          {
            const double y = at(i + d[0], j + d[1], k + d[2]);
            const bool same = (d[1] != 0 && n[1] == 1) || (d[2] != 0 && n[2] == 1);
            high = high && (same || x > y);
            low = low && (same || x < y);
          }
          maxima += high;
          minima += low;
        }
    EXPECT_GE(maxima, 1) << n[0] << "x" << n[1] << "x" << n[2];
    EXPECT_GE(minima, 1) << n[0] << "x" << n[1] << "x" << n[2];
  }
}

TEST(GridShockAdvection, ResultDoesNotDependOnTheThreadCount)
{
  for (const GridShape& shape : { Grid(70, 50), Grid(14, 12, 10) })
  {
    const auto input = Noisy(Bumps(shape, 3), 0.05, 5);
    for (FlowMode mode : { FlowMode::Fixed, FlowMode::Composed, FlowMode::Naive })
    {
      AdvectionParameters p = WithTime(300.0);
      p.flowMode = mode;
      p.flowUpdates = 3;
      p.numberOfThreads = 1;
      const auto serial = Filter(shape, 3, input, p);
      for (int threads : { 2, 3 })
      {
        p.numberOfThreads = threads;
        EXPECT_EQ(Filter(shape, 3, input, p), serial);
      }
    }
  }
}

// 8-bit samples are read in place (no float copy): every path of the kernel
// that reads the signal (flow, short and general sampling roads, stored
// positions, coarse levels) must give exactly the result of the float copy.
TEST(GridShockAdvection, EightBitSamplesGiveTheResultOfTheirFloatCopy)
{
  for (const GridShape& shape : { Grid(67, 45), Grid(13, 11, 9), Grid(23, 1) })
  {
    const int C = 3;
    std::mt19937 random(11);
    std::uniform_int_distribution<int> byte(0, 255);
    const auto smooth = Bumps(shape, C);
    std::vector<unsigned char> bytes(smooth.size());
    for (size_t k = 0; k < bytes.size(); ++k)
    {
      // Bumps in [0, 1] to [0, 250], with noise so that some samples are 0 or 255.
      bytes[k] = static_cast<unsigned char>(
        std::clamp(static_cast<int>(250.0 * smooth[k]) + byte(random) % 11 - 5, 0, 255));
    }
    const std::vector<float> floats(bytes.begin(), bytes.end());
    // Variant 5: a short time, where most traces stay in their faces (the
    // short road's neighbourhood reads bytes too); the others trace everything.
    for (int variant = 0; variant < 6; ++variant)
    {
      AdvectionParameters p = WithTime(variant == 5 ? 4.0 : 200.0);
      p.flowMode = variant == 1 ? FlowMode::Composed : (variant == 2 ? FlowMode::Naive : FlowMode::Fixed);
      p.flowUpdates = 3;
      p.sampling = variant == 3 ? Sampling::Nearest : Sampling::Linear;
      p.hierarchyLevels = variant == 4 ? 2 : 1;
      std::vector<double> fromBytes(bytes.size()), fromFloats(bytes.size());
      const auto into = [C](std::vector<double>& out) {
        return [&out, C](std::int64_t first, std::int64_t count, const double* values) {
          std::copy(values, values + count * C, out.begin() + first * C);
        };
      };
      ASSERT_TRUE(AdvectGridSignal(shape, C, bytes.data(), into(fromBytes), p).Ok());
      ASSERT_TRUE(AdvectGridSignal(shape, C, floats.data(), into(fromFloats), p).Ok());
      EXPECT_EQ(fromBytes, fromFloats) << "variant " << variant;
      // Not the identity.
      double change = 0.0;
      for (size_t k = 0; k < bytes.size(); ++k)
      {
        change = std::max(change, std::abs(fromBytes[k] - bytes[k]));
      }
      EXPECT_GT(change, variant == 5 ? 0.1 : 10.0) << "variant " << variant;
    }
  }
}

TEST(GridShockAdvection, FaceCrossingIsTheLimitOfStepping)
{
  // 2D and 3D: the exact tracer (with sliding along valleys and the stepping
  // fallback on grid edges) is what the paper's stepping converges to.
  for (const GridShape& shape : { Grid(48, 40), Grid(20, 18, 16) })
  {
    const auto input = Bumps(shape, 1);
    const auto exact = Filter(shape, 1, input, WithTime(3000.0));
    std::vector<double> errors;
    for (double delta : { 0.2, 0.05, 0.0125 })
    {
      AdvectionParameters p = WithTime(3000.0);
      p.tracing = Tracing::Stepped;
      p.stepFraction = delta;
      errors.push_back(MeanAbsDifference(Filter(shape, 1, input, p), exact));
    }
    EXPECT_LT(errors[1], errors[0]);
    EXPECT_LT(errors[2], errors[1]);
    EXPECT_LT(errors[2], 0.002 * Range(input));
  }
}

TEST(GridShockAdvection, FlatImagesInAnyPlaneGiveTheSameResult)
{
  const int n0 = 30, n1 = 24;
  const auto input = Bumps(Grid(n0, n1), 1);
  const auto xy = Filter(Grid(n0, n1, 1), 1, input, WithTime(200.0));
  EXPECT_EQ(Filter(Grid(n0, 1, n1), 1, input, WithTime(200.0)), xy);
  EXPECT_EQ(Filter(Grid(1, n0, n1), 1, input, WithTime(200.0)), xy);
}

TEST(GridShockAdvection, AnisotropicSpacingIsConsistentUnderTransposition)
{
  const int nx = 36, ny = 22;
  GridShape shape = Grid(nx, ny);
  shape.spacing = { 1.0, 2.5, 1.0 };
  GridShape transposed = Grid(ny, nx);
  transposed.spacing = { 2.5, 1.0, 1.0 };
  const auto input = Bumps(shape, 1);
  std::vector<double> inputT(input.size());
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      inputT[i * ny + j] = input[j * nx + i];
    }
  }
  const auto out = Filter(shape, 1, input, WithTime(150.0));
  const auto outT = Filter(transposed, 1, inputT, WithTime(150.0));
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      ASSERT_NEAR(outT[i * ny + j], out[j * nx + i], 1e-6);
    }
  }
}

TEST(GridShockAdvection, BlurredSphereInAVolumeBecomesSharper)
{
  const int n = 32;
  const GridShape shape = Grid(n, n, n);
  std::vector<double> input(shape.NumberOfSamples());
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double r = std::sqrt((i - 15.5) * (i - 15.5) + (j - 15.2) * (j - 15.2) + (k - 15.7) * (k - 15.7));
        input[(k * n + j) * n + i] = 1.0 - SmoothStep(r, 9.0, 2.5);
      }
    }
  }
  const auto out = Filter(shape, 1, input, WithTime(20000.0));
  // Profile along x through the centre.
  const size_t row = (16 * n + 15) * n;
  EXPECT_LT(RiseWidth(&out[row + 16], n - 16), 0.5 * RiseWidth(&input[row + 16], n - 16));
}

TEST(GridShockAdvection, NonFiniteSamplesStayPutAndDoNotSpread)
{
  const GridShape shape = Grid(40, 30);
  auto input = Bumps(shape, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<size_t> holes = { 0, 455, 456, 800, 1199 };
  const auto [low, high] = std::minmax_element(input.begin(), input.end());
  const double lo = *low, hi = *high;
  for (size_t h : holes)
  {
    input[h] = nan;
  }
  input[600] = std::numeric_limits<double>::infinity();
  for (Sampling sampling : { Sampling::Linear, Sampling::Nearest })
  {
    AdvectionParameters p = WithTime(1000.0);
    p.sampling = sampling;
    const auto out = Filter(shape, 1, input, p);
    for (size_t s = 0; s < out.size(); ++s)
    {
      if (std::find(holes.begin(), holes.end(), s) != holes.end())
      {
        ASSERT_TRUE(std::isnan(out[s]));
      }
      else if (s == 600)
      {
        ASSERT_EQ(out[s], input[s]);
      }
      else
      {
        ASSERT_TRUE(std::isfinite(out[s])) << s;
        ASSERT_GE(out[s], lo - 1e-12);
        ASSERT_LE(out[s], hi + 1e-12);
      }
    }
  }
}

TEST(GridShockAdvection, NearestSamplingAveragesInputValues)
{
  // Nearest sampling copies input values; a sample averages its 4 traces (2D).
  const GridShape shape = Grid(40, 30);
  auto input = Bumps(shape, 1);
  for (double& v : input)
  {
    v = v > 0.5 ? 1.0 : 0.0;
  }
  AdvectionParameters p = WithTime(50.0);
  p.sampling = Sampling::Nearest;
  p.smoothingPasses = 3;
  for (double v : Filter(shape, 1, input, p))
  {
    ASSERT_NEAR(4 * v, std::round(4 * v), 1e-12);
  }
}

TEST(GridShockAdvection, DegenerateGrids)
{
  const std::vector<double> one = { 3.5, -1.0 };
  EXPECT_EQ(Filter(Grid(1, 1, 1), 2, one, WithTime(10.0)), one);
  const auto row = Bumps(Grid(1, 50), 1);
  const auto out = Filter(Grid(1, 50), 1, row, WithTime(10.0));
  EXPECT_EQ(out.size(), row.size());
  std::vector<double> buffer(4);
  EXPECT_FALSE(AdvectGridSignal(Grid(0, 4), 1, buffer.data(), buffer.data() + 2, WithTime(1)).Ok());
}

TEST(GridShockAdvection, RejectsInvalidArguments)
{
  const GridShape shape = Grid(8, 8);
  std::vector<double> in(64, 0.0), out(64);
  in[10] = 1.0;
  auto fails = [&](AdvectionParameters p, GridShape g = Grid(8, 8), int c = 1) {
    return !AdvectGridSignal(g, c, in.data(), out.data(), p).Ok();
  };
  EXPECT_FALSE(fails(WithTime(1.0)));
  EXPECT_TRUE(fails(WithTime(-1.0)));
  EXPECT_TRUE(fails(WithTime(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_TRUE(fails(WithTime(std::numeric_limits<double>::infinity())));
  AdvectionParameters p = WithTime(1.0);
  p.stepFraction = 0.0;
  EXPECT_TRUE(fails(p));
  p = WithTime(1.0);
  p.flowUpdates = 0;
  EXPECT_TRUE(fails(p));
  p = WithTime(1.0);
  p.smoothingPasses = -1;
  EXPECT_TRUE(fails(p));
  GridShape zero = shape;
  zero.spacing[1] = 0.0;
  EXPECT_TRUE(fails(WithTime(1.0), zero));
  EXPECT_TRUE(fails(WithTime(1.0), shape, 0));
  EXPECT_FALSE(AdvectGridSignal(shape, 1, in.data(), in.data(), WithTime(1.0)).Ok());
}

TEST(GridShockAdvection, TracingWorkSaturatesAsTimeGrows)
{
  // The paper's sub-linear cost: flow lines end where the flow reverses, so
  // beyond some time the number of tracing steps stops growing (counted, not timed).
  const GridShape shape = Grid(96, 96);
  const auto input = Noisy(Bumps(shape, 1), 0.02, 9);
  std::vector<std::uint64_t> steps;
  for (double t : { 4096.0, 4194304.0, 16777216.0, 67108864.0 })
  {
    AdvectionReport report;
    Filter(shape, 1, input, WithTime(t), &report);
    steps.push_back(report.traceSteps);
  }
  EXPECT_LT(steps[0], steps[1]);
  EXPECT_LT(static_cast<double>(steps[2]), 1.02 * static_cast<double>(steps[1]));
  EXPECT_LT(static_cast<double>(steps[3]), 1.02 * static_cast<double>(steps[2]));
}

TEST(GridShockAdvection, ProgressIsMonotoneAndAbortStopsTheRun)
{
  const GridShape shape = Grid(300, 200);
  const auto input = Bumps(shape, 1);
  std::vector<double> fractions;
  AdvectionParameters p = WithTime(100.0);
  p.flowMode = FlowMode::Composed;
  p.flowUpdates = 2;
  std::vector<double> out(input.size());
  ASSERT_TRUE(AdvectGridSignal(shape, 1, input.data(), out.data(), p, nullptr, nullptr,
    [&](double f) {
      fractions.push_back(f);
      return true;
    })
                .Ok());
  ASSERT_GT(fractions.size(), 4u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GE(fractions.front(), 0.0);
  EXPECT_LE(fractions.back(), 1.0);

  int calls = 0;
  AdvectionReport report;
  ASSERT_TRUE(AdvectGridSignal(shape, 1, input.data(), out.data(), p, &report, nullptr,
    [&](double) { return ++calls < 2; })
                .Ok());
  EXPECT_TRUE(report.aborted);
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(out, input);
}

} // namespace
