// The grid shock filter as a whole, and its multi-step flows (section 3.3),
// against an independent 1D implementation written from the paper: the signal
// is normalised by its range, umbrella-smoothed, its face gradients give the
// energy (summed over channels) averaged to the samples, smoothed again, and
// u = 1/2 grad P; every sample is traced back along -u from an offset of 0.001
// into each adjacent segment (exactly, segment by segment, stopping where the
// flow reverses or at the ends) and the input is read there linearly.
#include "GridShockAdvection.h"
#include "TestSignals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
using namespace shock;
using namespace shocktest;

/// A 1D multi-channel signal: n samples, C channels, spacing h (l-bar = h).
struct Signal1D
{
  int n;
  int C;
  std::vector<double> values; // n x C

  double Range() const
  {
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    return *hi - *lo;
  }
};

std::vector<double> Smooth1D(const std::vector<double>& in, int n, int C)
{
  const double a = std::exp(-1.0); // neighbours at one l-bar
  std::vector<double> out(in.size());
  for (int i = 0; i < n; ++i)
  {
    const double total = 1.0 + (i > 0 ? a : 0.0) + (i + 1 < n ? a : 0.0);
    for (int c = 0; c < C; ++c)
    {
      double s = in[i * C + c];
      s += i > 0 ? a * in[(i - 1) * C + c] : 0.0;
      s += i + 1 < n ? a * in[(i + 1) * C + c] : 0.0;
      out[i * C + c] = s / total;
    }
  }
  return out;
}

/// Back-trace velocity -u per segment (in samples per unit time) of `signal`, divided by `range`.
std::vector<double> BackTraceVelocity1D(const Signal1D& s, double range, int passes)
{
  std::vector<double> v(s.values);
  for (double& x : v)
    x /= range;
  for (int k = 0; k < passes; ++k)
    v = Smooth1D(v, s.n, s.C);
  std::vector<double> energy(s.n - 1, 0.0);
  for (int f = 0; f + 1 < s.n; ++f)
    for (int c = 0; c < s.C; ++c)
    {
      const double g = v[(f + 1) * s.C + c] - v[f * s.C + c];
      energy[f] += g * g;
    }
  std::vector<double> potential(s.n);
  for (int i = 0; i < s.n; ++i)
  {
    const bool left = i > 0, right = i + 1 < s.n;
    potential[i] = ((left ? energy[i - 1] : 0.0) + (right ? energy[i] : 0.0)) / (left + right);
  }
  for (int k = 0; k < passes; ++k)
    potential = Smooth1D(potential, s.n, 1);
  std::vector<double> velocity(s.n - 1);
  for (int f = 0; f + 1 < s.n; ++f)
    velocity[f] = static_cast<float>(-0.5 * (potential[f + 1] - potential[f]));
  return velocity;
}

/// Exact trace of x (in segment `segment`) along the piecewise-constant velocity for time t.
double Trace1D(const std::vector<double>& velocity, double x, int segment, double t)
{
  const int m = static_cast<int>(velocity.size());
  double v = velocity[segment];
  while (t > 0.0 && v != 0.0)
  {
    const double boundary = v > 0.0 ? segment + 1 : segment;
    const double exit = (boundary - x) / v;
    if (exit >= t)
      return x + v * t;
    x = boundary;
    t -= exit;
    const int next = segment + (v > 0.0 ? 1 : -1);
    if (next < 0 || next >= m || velocity[next] * v <= 0.0)
      return x; // the end of the signal, or the flow reverses
    segment = next;
    v = velocity[segment];
  }
  return x;
}

double Read1D(const Signal1D& s, double x, int c)
{
  const int cell = std::min(static_cast<int>(x), s.n - 2);
  const double w = x - cell;
  return (1.0 - w) * s.values[cell * s.C + c] + w * s.values[(cell + 1) * s.C + c];
}

/// The trace starts of sample i: offsets of 0.001 x (segment centre - sample) into each adjacent segment.
std::vector<std::pair<double, int>> Starts1D(int i, int n)
{
  std::vector<std::pair<double, int>> starts;
  if (i > 0)
    starts.push_back({ i - 0.0005, i - 1 });
  if (i + 1 < n)
    starts.push_back({ i + 0.0005, i });
  return starts;
}

/// Appendix A AdvectVertices in 1D: `source` read at the traced starts, averaged.
Signal1D Advect1D(const Signal1D& source, const std::vector<double>& velocity, double t)
{
  Signal1D out = source;
  for (int i = 0; i < source.n; ++i)
  {
    const auto starts = Starts1D(i, source.n);
    for (int c = 0; c < source.C; ++c)
    {
      double sum = 0.0;
      for (const auto& [x, segment] : starts)
        sum += Read1D(source, Trace1D(velocity, x, segment, t), c);
      out.values[i * source.C + c] = sum / starts.size();
    }
  }
  return out;
}

Signal1D TestSignal(int n, int C)
{
  Signal1D s{ n, C, std::vector<double>(static_cast<size_t>(n * C)) };
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < C; ++c)
    {
      const double x = static_cast<double>(i) / (n - 1);
      s.values[i * C + c] = SmoothStep(x, 0.35 + 0.2 * c, 0.07) +
        0.4 * std::exp(-std::pow((x - 0.75 + 0.1 * c) / 0.08, 2)) + 0.15 * std::sin(9.0 * x + c);
    }
  return s;
}

std::vector<double> Filter1D(const Signal1D& s, const AdvectionParameters& p, double spacing = 0.37)
{
  GridShape shape = Grid(s.n, 1);
  shape.spacing = { spacing, 1.0, 1.0 };
  return Filter(shape, s.C, s.values, p);
}

AdvectionParameters Parameters(double t, FlowMode mode = FlowMode::Fixed, int updates = 1)
{
  AdvectionParameters p;
  p.time = t;
  p.flowMode = mode;
  p.flowUpdates = updates;
  return p;
}

constexpr double Tolerance = 1e-9; // rounding only: the reference rounds velocities and composed positions to floats as the kernel stores them

TEST(GridFlows, FixedFlowEqualsTheAppendixComputedIndependently)
{
  const Signal1D input = TestSignal(64, 3);
  for (int passes : { 0, 1, 3 })
  {
    for (double t : { 3.0, 40.0, 400.0 })
    {
      AdvectionParameters p = Parameters(t);
      p.smoothingPasses = passes;
      const auto kernel = Filter1D(input, p);
      const auto expected =
        Advect1D(input, BackTraceVelocity1D(input, input.Range(), passes), t).values;
      EXPECT_LT(MaxAbsDifference(kernel, expected), Tolerance) << "t " << t << " passes " << passes;
      EXPECT_GT(MaxAbsDifference(kernel, input.values), 3e-4) << "t " << t;
    }
  }
}

TEST(GridFlows, NaiveEqualsChainedFixedRunsWithTheInputsRange)
{
  // Naive: K times (flow of the current signal, trace for t/K, resample the
  // current signal), every flow normalised by the input's range.
  const Signal1D input = TestSignal(64, 2);
  const double t = 300.0;
  const int K = 3;
  const auto naive = Filter1D(input, Parameters(t, FlowMode::Naive, K));
  Signal1D chained = input;
  Signal1D reference = input;
  for (int k = 0; k < K; ++k)
  {
    AdvectionParameters step = Parameters(t / K);
    step.valueScale = input.Range();
    chained.values = Filter1D(chained, step);
    reference = Advect1D(reference, BackTraceVelocity1D(reference, input.Range(), 1), t / K);
  }
  EXPECT_LT(MaxAbsDifference(naive, chained.values), 1e-12);
  EXPECT_LT(MaxAbsDifference(naive, reference.values), Tolerance);
  // Something changed, and it is not the fixed flow: the flow was recomputed.
  const auto fixed = Filter1D(input, Parameters(t));
  EXPECT_GT(MaxAbsDifference(naive, fixed), 1e-3);
  EXPECT_GT(MaxAbsDifference(naive, input.values), 0.02);
}

TEST(GridFlows, ComposedTracesBackAlongTheFlowOfTheIntermediateSignal)
{
  // Composed, K = 2: I1 = I0 read at the traces along u(I0) for t/2; then the
  // same traces continue along u(I1) for t/2 and I0 is read where they end.
  const Signal1D input = TestSignal(64, 2);
  const double t = 300.0;
  const auto composed = Filter1D(input, Parameters(t, FlowMode::Composed, 2));

  const double range = input.Range();
  const auto u0 = BackTraceVelocity1D(input, range, 1);
  const Signal1D intermediate = Advect1D(input, u0, t / 2);
  const auto u1 = BackTraceVelocity1D(intermediate, range, 1);
  const auto compose = [&](const std::vector<double>& second) {
    std::vector<double> out(input.values.size());
    for (int i = 0; i < input.n; ++i)
    {
      const auto starts = Starts1D(i, input.n);
      for (int c = 0; c < input.C; ++c)
      {
        double sum = 0.0;
        for (const auto& [x, segment] : starts)
        {
          // The kernel keeps the traced positions as floats, from the start on.
          const double x0 = static_cast<float>(x);
          const double x1 = static_cast<float>(Trace1D(u0, x0, segment, t / 2));
          const int s1 = std::min(static_cast<int>(x1), input.n - 2);
          sum += Read1D(input, Trace1D(second, x1, s1, t / 2), c);
        }
        out[i * input.C + c] = sum / starts.size();
      }
    }
    return out;
  };
  // The kernel's intermediate signal is read at float positions, the reference's at doubles.
  const double tolerance = 1e-6;
  EXPECT_LT(MaxAbsDifference(composed, compose(u1)), tolerance);
  // Not the first flow twice (that would be the fixed flow), and not the naive mode.
  EXPECT_GT(MaxAbsDifference(composed, compose(u0)), 100 * tolerance);
  EXPECT_GT(MaxAbsDifference(composed, Filter1D(input, Parameters(t, FlowMode::Naive, 2))), 100 * tolerance);
}

} // namespace
