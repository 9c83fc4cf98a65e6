// Unit tests of the Osher-Rudin PDE baseline (GridShockPDE.h): the properties
// the scheme must have (stability at the CFL step, extrema preserved, edges
// sharpened) and its agreement with the advection on 1D profiles.
#include "GridShockAdvection.h"
#include "GridShockPDE.h"
#include "TestSignals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace
{
using namespace shock;
using namespace shocktest;

PDEParameters PDEAt(double t)
{
  PDEParameters p;
  p.time = t;
  return p;
}

std::vector<double> SolvePDE(const GridShape& shape, int components,
  const std::vector<double>& input, const PDEParameters& p, PDEReport* report = nullptr)
{
  std::vector<double> output(input.size());
  const Status status =
    SolveGridShockPDE(shape, components, input.data(), output.data(), p, report);
  EXPECT_TRUE(status.Ok()) << status.error;
  return output;
}

/// A blurred unit step along x at x0 (samples), blur sigma (samples), on an n-sample row.
std::vector<double> BlurredStep(int n, double x0, double sigma)
{
  std::vector<double> v(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    v[i] = SmoothStep(i, x0, sigma);
  }
  return v;
}

/// Largest difference between adjacent samples.
double MaxJump(const std::vector<double>& v)
{
  double jump = 0.0;
  for (size_t i = 1; i < v.size(); ++i)
  {
    jump = std::max(jump, std::abs(v[i] - v[i - 1]));
  }
  return jump;
}

/// Position of the first crossing of `level` (linear interpolation), -1 if none.
double Crossing(const std::vector<double>& v, double level)
{
  for (size_t i = 0; i + 1 < v.size(); ++i)
  {
    const double a = v[i] - level, b = v[i + 1] - level;
    if ((a <= 0.0) != (b <= 0.0))
    {
      return static_cast<double>(i) + a / (a - b);
    }
  }
  return -1.0;
}

TEST(GridShockPDE, ZeroTimeReturnsTheInputExactly)
{
  for (const GridShape& shape : { Grid(40, 1), Grid(40, 30), Grid(12, 10, 8) })
  {
    const auto input = Bumps(shape, 3);
    PDEReport report;
    EXPECT_EQ(SolvePDE(shape, 3, input, PDEAt(0.0), &report), input);
    EXPECT_EQ(report.iterations, 0);
  }
}

TEST(GridShockPDE, StableAtTheCFLStepForAnyTime)
{
  // Noisy data is the hard case for an explicit scheme: the step must adapt so
  // that nothing overshoots, whatever t. The result stays within the input range
  // (a maximum principle) and finite.
  const GridShape shape = Grid(64, 48);
  const auto input = Noisy(Bumps(shape, 2), 0.08, 3);
  const auto [low, high] = std::minmax_element(input.begin(), input.end());
  for (double courant : { 0.25, 0.5, 1.0 })
  {
    for (double t : { 0.5, 16.0, 256.0 })
    {
      PDEParameters p = PDEAt(t);
      p.courantNumber = courant;
      PDEReport report;
      const auto out = SolvePDE(shape, 2, input, p, &report);
      const auto [outLow, outHigh] = std::minmax_element(out.begin(), out.end());
      const double eps = 1e-12 * (*high - *low);
      EXPECT_GE(*outLow, *low - eps) << "courant " << courant << " t " << t;
      EXPECT_LE(*outHigh, *high + eps) << "courant " << courant << " t " << t;
      EXPECT_TRUE(std::all_of(out.begin(), out.end(), [](double v) { return std::isfinite(v); }));
      EXPECT_GT(report.iterations, 0);
      EXPECT_FALSE(report.iterationLimit);
      EXPECT_DOUBLE_EQ(report.reachedTime, t);
      EXPECT_GT(report.smallestStep, 0.0);
      EXPECT_LE(report.smallestStep, report.largestStep);
    }
  }
}

TEST(GridShockPDE, TotalVariationDoesNotGrowIn1D)
{
  // In 1D the minmod scheme is total-variation diminishing under the CFL step
  // (Osher and Rudin 1990): no new oscillations, even on noisy data.
  const GridShape shape = Grid(400, 1);
  const auto input = Noisy(Bumps(shape, 1), 0.05, 11);
  const double tv0 = TotalVariation(input);
  for (double t : { 1.0, 32.0, 1024.0 })
  {
    const auto out = SolvePDE(shape, 1, input, PDEAt(t));
    EXPECT_LE(TotalVariation(out), tv0 * (1.0 + 1e-12)) << "t " << t;
  }
}

TEST(GridShockPDE, ExtremaKeepTheirValues)
{
  // A smooth 1D profile with interior maxima and minima: the minmod gradient is
  // zero there, so their values do not move however long the flow runs.
  const int n = 300;
  const GridShape shape = Grid(n, 1);
  std::vector<double> input(n);
  for (int i = 0; i < n; ++i)
  {
    input[i] = std::sin(2.0 * M_PI * i / 97.0) + 0.3 * std::sin(2.0 * M_PI * i / 41.0 + 0.4);
  }
  std::vector<int> extrema;
  for (int i = 1; i + 1 < n; ++i)
  {
    if ((input[i] > input[i - 1] && input[i] > input[i + 1]) ||
      (input[i] < input[i - 1] && input[i] < input[i + 1]))
    {
      extrema.push_back(i);
    }
  }
  ASSERT_GE(extrema.size(), 6u);
  for (double t : { 4.0, 256.0 })
  {
    const auto out = SolvePDE(shape, 1, input, PDEAt(t));
    for (int i : extrema)
    {
      EXPECT_NEAR(out[i], input[i], 1e-12) << "extremum at " << i << ", t " << t;
    }
  }
}

TEST(GridShockPDE, BlurredEdgeSharpensInOneAndTwoDimensions)
{
  // 1D: an error-function edge 5 samples wide (10%-90%) becomes a jump of
  // almost the whole range between two samples, at the same place; the
  // plateaus keep their values. (The flow speed grows with the edge's
  // steepness, so a wide edge needs a much longer time: about width^3.)
  {
    const int n = 120;
    const auto input = BlurredStep(n, 60.3, 2.0);
    const double width0 = RiseWidth(input.data(), n);
    ASSERT_GT(width0, 4.5);
    double previous = width0;
    std::vector<double> out;
    for (double t : { 256.0, 2048.0, 16384.0 })
    {
      out = SolvePDE(Grid(n, 1), 1, input, PDEAt(t));
      const double width = RiseWidth(out.data(), n);
      EXPECT_LE(width, previous) << "t " << t;
      previous = width;
      EXPECT_NEAR(Crossing(out, 0.5), 60.3, 0.7) << "t " << t;
      EXPECT_NEAR(out.front(), input.front(), 1e-12);
      EXPECT_NEAR(out.back(), input.back(), 1e-12);
    }
    EXPECT_LT(previous, 1.0);
    EXPECT_GT(MaxJump(out), 0.9);
  }
  // 2D: a blurred straight edge at an angle sharpens along every row.
  {
    const int nx = 80, ny = 60;
    const GridShape shape = Grid(nx, ny);
    std::vector<double> input(static_cast<size_t>(nx * ny));
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        input[j * nx + i] = SmoothStep(i + 0.3 * j, 48.0, 2.0);
      }
    }
    const auto out = SolvePDE(shape, 1, input, PDEAt(2048.0));
    for (int j = 5; j < ny - 5; j += 10)
    {
      const double before = RiseWidth(&input[j * nx], nx);
      const double after = RiseWidth(&out[j * nx], nx);
      EXPECT_LT(after, 0.4 * before) << "row " << j;
    }
  }
}

TEST(GridShockPDE, AgreesWithTheAdvectionOnOneDimensionalProfiles)
{
  // Both methods solve equation (2), so on 1D profiles they must agree: at
  // short times, where the advection's fixed flow is the PDE's flow at t = 0,
  // and in the limit t -> infinity, where both turn each blurred edge into a
  // jump at the same place between the same plateaus. (They differ by about
  // one sample per edge: the advection keeps the value of the sample on the
  // potential's ridge, the PDE moves it to one side.)
  const int n = 200;
  const GridShape shape = Grid(n, 1);
  std::vector<double> profile(n);
  for (int i = 0; i < n; ++i)
  {
    profile[i] = SmoothStep(i, 40.3, 2.0) - 0.7 * SmoothStep(i, 90.6, 2.5) +
      0.5 * std::exp(-std::pow((i - 150.2) / 5.0, 2));
  }
  const double range = Range(profile);

  for (double t : { 4.0, 16.0, 64.0 })
  {
    const auto pde = SolvePDE(shape, 1, profile, PDEAt(t));
    AdvectionParameters a;
    a.time = t;
    const auto advected = Filter(shape, 1, profile, a);
    const double moved = MeanAbsDifference(pde, profile);
    ASSERT_GT(moved, 1e-6 * range);
    EXPECT_LT(MeanAbsDifference(pde, advected), 0.25 * moved) << "t " << t;
  }

  const auto pde = SolvePDE(shape, 1, profile, PDEAt(65536.0));
  AdvectionParameters a;
  a.time = 65536.0;
  const auto advected = Filter(shape, 1, profile, a);
  EXPECT_LT(MeanAbsDifference(pde, advected), 0.01 * range);
  EXPECT_LT(RiseWidth(&pde[20], 40), 1.0);
  EXPECT_LT(RiseWidth(&advected[20], 40), 2.0);
  for (const auto& [from, level] : { std::pair<int, double>{ 20, 0.5 }, { 70, 0.65 }, { 120, 0.5 } })
  {
    const std::vector<double> pdePart(pde.begin() + from, pde.begin() + from + 40);
    const std::vector<double> advectedPart(advected.begin() + from, advected.begin() + from + 40);
    EXPECT_NEAR(Crossing(pdePart, level), Crossing(advectedPart, level), 1.0) << "edge at " << from;
  }
  // The plateaus: the extremes of the profile, kept by both.
  for (int i : { 5, 60, 120, 195 })
  {
    EXPECT_NEAR(pde[i], advected[i], 0.02 * range) << i;
  }
}

TEST(GridShockPDE, APerfectStepIsAFixedPoint)
{
  std::vector<double> input(50, 0.0);
  std::fill(input.begin() + 20, input.end(), 1.0);
  PDEReport report;
  const auto out = SolvePDE(Grid(50, 1), 1, input, PDEAt(1000.0), &report);
  EXPECT_EQ(out, input);
  EXPECT_TRUE(report.steadyState);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_DOUBLE_EQ(report.reachedTime, 1000.0);
}

TEST(GridShockPDE, IndependentOfValueScaleOffsetAndGridScale)
{
  const GridShape shape = Grid(50, 40);
  const auto input = Bumps(shape, 1);
  const auto reference = SolvePDE(shape, 1, input, PDEAt(20.0));
  std::vector<double> scaled(input.size());
  std::transform(input.begin(), input.end(), scaled.begin(), [](double v) { return 250.0 * v - 40.0; });
  GridShape bigger = shape;
  bigger.spacing = { 3.5, 3.5, 1.0 };
  const auto out = SolvePDE(bigger, 1, scaled, PDEAt(20.0));
  for (size_t i = 0; i < input.size(); ++i)
  {
    ASSERT_NEAR((out[i] + 40.0) / 250.0, reference[i], 1e-9) << i;
  }
}

TEST(GridShockPDE, ChannelsShareOneFlow)
{
  // Two copies of a channel move exactly alike, and a second, different channel
  // changes how the first moves (the flow is coupled, as in the advection).
  const GridShape shape = Grid(40, 30);
  const auto one = Bumps(shape, 1);
  std::vector<double> twin(2 * one.size()), pair(2 * one.size());
  const auto other = Bumps(shape, 1, 2.0);
  for (size_t s = 0; s < one.size(); ++s)
  {
    twin[2 * s] = twin[2 * s + 1] = one[s];
    pair[2 * s] = one[s];
    pair[2 * s + 1] = other[s];
  }
  const auto single = SolvePDE(shape, 1, one, PDEAt(16.0));
  const auto twins = SolvePDE(shape, 2, twin, PDEAt(16.0));
  const auto coupled = SolvePDE(shape, 2, pair, PDEAt(16.0));
  double coupling = 0.0;
  for (size_t s = 0; s < one.size(); ++s)
  {
    ASSERT_EQ(twins[2 * s], twins[2 * s + 1]);
    coupling = std::max(coupling, std::abs(coupled[2 * s] - single[s]));
  }
  EXPECT_GT(coupling, 1e-3);
}

TEST(GridShockPDE, VolumesSharpen)
{
  // A blurred ball in a 3D volume: its boundary becomes sharp, its centre and
  // the background keep their values.
  const int n = 24;
  const GridShape shape = Grid(n, n, n);
  std::vector<double> input(static_cast<size_t>(n * n * n));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double r = std::sqrt((i - 11.5) * (i - 11.5) + (j - 11.5) * (j - 11.5) + (k - 11.5) * (k - 11.5));
        input[(k * n + j) * n + i] = 1.0 - SmoothStep(r, 7.0, 1.5);
      }
  const auto out = SolvePDE(shape, 1, input, PDEAt(256.0));
  std::vector<double> rowBefore(n), rowAfter(n);
  for (int i = 0; i < n; ++i)
  {
    rowBefore[i] = input[(12 * n + 12) * n + i];
    rowAfter[i] = out[(12 * n + 12) * n + i];
  }
  EXPECT_LT(RiseWidth(rowAfter.data(), n / 2), 0.5 * RiseWidth(rowBefore.data(), n / 2));
  EXPECT_NEAR(out[0], input[0], 1e-6);
}

TEST(GridShockPDE, NonFiniteSamplesStayPutAndDoNotSpread)
{
  const GridShape shape = Grid(30, 20);
  auto input = Bumps(shape, 2);
  input[2 * (7 * 30 + 9)] = std::numeric_limits<double>::quiet_NaN();
  input[2 * (12 * 30 + 20) + 1] = std::numeric_limits<double>::infinity();
  const auto out = SolvePDE(shape, 2, input, PDEAt(64.0));
  for (size_t v = 0; v < out.size(); ++v)
  {
    const size_t sample = v / 2;
    if (sample == 7 * 30 + 9 || sample == 12 * 30 + 20)
    {
      // The whole sample is kept bit for bit, finite components included.
      EXPECT_TRUE(std::memcmp(&out[v], &input[v], sizeof(double)) == 0) << v;
    }
    else
    {
      EXPECT_TRUE(std::isfinite(out[v])) << v;
    }
  }
}

TEST(GridShockPDE, ThreadCountDoesNotChangeTheResult)
{
  const GridShape shape = Grid(300, 7);
  const auto input = Noisy(Bumps(shape, 3), 0.02, 5);
  PDEParameters p = PDEAt(32.0);
  p.numberOfThreads = 1;
  const auto serial = SolvePDE(shape, 3, input, p);
  p.numberOfThreads = 2;
  EXPECT_EQ(SolvePDE(shape, 3, input, p), serial);
}

TEST(GridShockPDE, CheckpointsSeeTheSolutionAtTheirTimes)
{
  const GridShape shape = Grid(60, 40);
  const auto input = Bumps(shape, 1);
  PDEParameters p = PDEAt(16.0);
  p.checkpointTimes = { 2.0, 5.0, 16.0 };
  std::vector<double> times, seconds;
  std::vector<std::vector<double>> snapshots;
  std::vector<double> output(input.size());
  PDEReport report;
  const Status status = SolveGridShockPDE(shape, 1, input.data(), output.data(), p, &report,
    nullptr, ProgressFunction(), [&](double t, double s, const double* values) {
      times.push_back(t);
      seconds.push_back(s);
      snapshots.emplace_back(values, values + input.size());
    });
  ASSERT_TRUE(status.Ok()) << status.error;
  EXPECT_EQ(times, p.checkpointTimes);
  EXPECT_TRUE(std::is_sorted(seconds.begin(), seconds.end()));
  EXPECT_EQ(snapshots.back(), output);
  // Up to the first checkpoint, the steps are those of a run that ends there.
  EXPECT_EQ(snapshots[0], SolvePDE(shape, 1, input, PDEAt(2.0)));
  EXPECT_NE(snapshots[1], snapshots[0]);
}

TEST(GridShockPDE, StopsAtTheIterationLimitAndSaysSo)
{
  const GridShape shape = Grid(40, 30);
  const auto input = Bumps(shape, 1);
  PDEParameters p = PDEAt(1000.0);
  p.maximumIterations = 3;
  PDEReport report;
  const auto out = SolvePDE(shape, 1, input, p, &report);
  EXPECT_TRUE(report.iterationLimit);
  EXPECT_EQ(report.iterations, 3);
  EXPECT_LT(report.reachedTime, 1000.0);
  EXPECT_GT(report.reachedTime, 0.0);
  EXPECT_NE(out, input);
}

TEST(GridShockPDE, AbortLeavesTheInput)
{
  const GridShape shape = Grid(40, 30);
  const auto input = Bumps(shape, 1);
  std::vector<double> output(input.size());
  PDEReport report;
  int calls = 0;
  const Status status = SolveGridShockPDE(shape, 1, input.data(), output.data(), PDEAt(100.0),
    &report, nullptr, [&](double) { return ++calls < 2; });
  ASSERT_TRUE(status.Ok());
  EXPECT_TRUE(report.aborted);
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(output, input);
}

TEST(GridShockPDE, RejectsInvalidArguments)
{
  const GridShape shape = Grid(10, 10);
  std::vector<double> input(100, 0.5), output(100);
  auto fails = [&](PDEParameters p) {
    return !SolveGridShockPDE(shape, 1, input.data(), output.data(), p).Ok();
  };
  PDEParameters p = PDEAt(1.0);
  EXPECT_FALSE(fails(p));
  p.time = -1.0;
  EXPECT_TRUE(fails(p));
  p.time = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(fails(p));
  p = PDEAt(1.0);
  p.courantNumber = 0.0;
  EXPECT_TRUE(fails(p));
  p.courantNumber = 1.5;
  EXPECT_TRUE(fails(p));
  p = PDEAt(1.0);
  p.maximumIterations = 0;
  EXPECT_TRUE(fails(p));
  p = PDEAt(1.0);
  p.checkpointTimes = { 0.5, 0.25 };
  EXPECT_TRUE(fails(p));
  p.checkpointTimes = { 2.0 };
  EXPECT_TRUE(fails(p));
  p = PDEAt(1.0);
  p.smoothingPasses = -1;
  EXPECT_TRUE(fails(p));
  EXPECT_FALSE(SolveGridShockPDE(shape, 1, input.data(), input.data(), PDEAt(1.0)).Ok());
  EXPECT_FALSE(SolveGridShockPDE(shape, 0, input.data(), output.data(), PDEAt(1.0)).Ok());
  GridShape flat = shape;
  flat.spacing[0] = 0.0;
  EXPECT_FALSE(SolveGridShockPDE(flat, 1, input.data(), output.data(), PDEAt(1.0)).Ok());
}

} // namespace
