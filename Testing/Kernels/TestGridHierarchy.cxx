// Tests of the grid kernel's coarse-to-fine tracing (hierarchyLevels > 1,
// GridHierarchy.h): beyond the paper, after its section 6 proposal.
#include "GridHierarchy.h"
#include "GridShockAdvection.h"
#include "TestSignals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace
{
using namespace shock;
using namespace shocktest;

AdvectionParameters Levels(int levels, double t)
{
  AdvectionParameters p;
  p.time = t;
  p.hierarchyLevels = levels;
  return p;
}

/// A vertical step at x = nx / 2 blurred with sigma, plus Gaussian noise of `noise` (deterministic).
struct NoisyEdge
{
  GridShape shape;
  std::vector<double> sharp, input;

  NoisyEdge(int nx, int ny, double sigma, double noise, unsigned seed)
    : shape(Grid(nx, ny))
  {
    std::mt19937 random(seed);
    std::normal_distribution<double> gauss(0.0, noise);
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        this->sharp.push_back(i + 0.5 > nx / 2.0 ? 1.0 : 0.0);
        this->input.push_back(SmoothStep(i + 0.5, nx / 2.0, sigma) + gauss(random));
      }
    }
  }

  double Error(const std::vector<double>& v) const
  {
    double sum = 0.0;
    for (size_t s = 0; s < v.size(); ++s)
    {
      sum += (v[s] - this->sharp[s]) * (v[s] - this->sharp[s]);
    }
    return std::sqrt(sum / static_cast<double>(v.size()));
  }
};

bool WithinRange(const std::vector<double>& out, const std::vector<double>& in)
{
  const auto [low, high] = std::minmax_element(in.begin(), in.end());
  const double eps = 1e-12 * (*high - *low);
  return std::all_of(out.begin(), out.end(),
    [&](double v) { return std::isfinite(v) && v >= *low - eps && v <= *high + eps; });
}

TEST(GridHierarchy, PyramidHalvesEveryActiveAxisOverTheSameExtent)
{
  GridShape fine = Grid(101, 40, 1);
  fine.spacing = { 0.5, 2.0, 7.0 };
  const auto shapes = grid::PyramidShapes(fine, 4);
  ASSERT_EQ(shapes.size(), 4u);
  const int expectedX[] = { 101, 51, 26, 14 };
  const int expectedY[] = { 40, 21, 11, 6 };
  for (size_t l = 0; l < shapes.size(); ++l)
  {
    EXPECT_EQ(shapes[l].dimensions[0], expectedX[l]);
    EXPECT_EQ(shapes[l].dimensions[1], expectedY[l]);
    EXPECT_EQ(shapes[l].dimensions[2], 1);
    EXPECT_NEAR(shapes[l].spacing[0] * (shapes[l].dimensions[0] - 1), 50.0, 1e-12);
    EXPECT_NEAR(shapes[l].spacing[1] * (shapes[l].dimensions[1] - 1), 78.0, 1e-12);
    EXPECT_EQ(shapes[l].spacing[2], 7.0);
  }
  // A level is built while every active axis has at least 3 samples.
  EXPECT_EQ(grid::PyramidShapes(Grid(9, 5), 10).size(), 3u); // 9x5, 5x3, 3x2
  EXPECT_EQ(grid::PyramidShapes(Grid(2, 50), 5).size(), 1u);
  EXPECT_EQ(grid::PyramidShapes(Grid(1, 1), 5).size(), 1u);
}

TEST(GridHierarchy, OneLevelIsThePaperSingleLevelFilterBitForBit)
{
  for (const GridShape& shape : { Grid(64, 1), Grid(40, 30), Grid(12, 10, 8) })
  {
    const auto input = Noisy(Bumps(shape, 2), 0.05, 3);
    for (FlowMode mode : { FlowMode::Fixed, FlowMode::Composed, FlowMode::Naive })
    {
      AdvectionParameters today;
      today.time = 500.0;
      today.flowMode = mode;
      today.flowUpdates = 3;
      AdvectionParameters one = today;
      one.hierarchyLevels = 1;
      AdvectionReport report;
      EXPECT_EQ(Filter(shape, 2, input, one, &report), Filter(shape, 2, input, today));
      EXPECT_EQ(report.hierarchyLevels, 1);
      // ... and more levels do change the result (the parameter is used).
      AdvectionParameters three = today;
      three.hierarchyLevels = 3;
      EXPECT_GT(MaxAbsDifference(Filter(shape, 2, input, three, &report), Filter(shape, 2, input, one)), 1e-3);
      EXPECT_EQ(report.hierarchyLevels, 3);
    }
  }
}

TEST(GridHierarchy, ZeroTimeReturnsTheInputExactly)
{
  for (const GridShape& shape : { Grid(50, 1), Grid(40, 30), Grid(12, 10, 8) })
  {
    const auto input = Noisy(Bumps(shape, 3), 0.05, 5);
    EXPECT_EQ(Filter(shape, 3, input, Levels(4, 0.0)), input);
  }
}

TEST(GridHierarchy, OutputStaysWithinTheInputRangeAndIsStableForAnyTime)
{
  const GridShape shape = Grid(48, 40);
  const auto input = Noisy(Bumps(shape, 1), 0.05, 7);
  for (FlowMode mode : { FlowMode::Fixed, FlowMode::Composed, FlowMode::Naive })
  {
    for (Sampling sampling : { Sampling::Linear, Sampling::Nearest })
    {
      for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
      {
        for (double t : { 30.0, 1e3, 1e9 })
        {
          AdvectionParameters p = Levels(3, t);
          p.flowMode = mode;
          p.flowUpdates = 3;
          p.sampling = sampling;
          p.tracing = tracing;
          const auto out = Filter(shape, 1, input, p);
          EXPECT_TRUE(WithinRange(out, input)) << "t = " << t;
          if (t >= 1e3) // it did something (Nearest keeps the input for displacements < 1/2)
          {
            EXPECT_GT(MaxAbsDifference(out, input), 1e-3) << "t = " << t;
          }
        }
      }
    }
  }
  const GridShape volume = Grid(20, 18, 16);
  const auto values = Noisy(Bumps(volume, 2), 0.05, 9);
  for (double t : { 1e2, 1e9 })
  {
    const auto out = Filter(volume, 2, values, Levels(3, t));
    EXPECT_TRUE(WithinRange(out, values));
    EXPECT_GT(MaxAbsDifference(out, values), 1e-3);
  }
}

TEST(GridHierarchy, LargeBlurredEdgeUnderNoiseEndsSharperThanWithOneLevel)
{
  // Section 6's claim: noise puts potential maxima everywhere and single-level
  // traces stop at them, so a wide blurred edge stays soft at any t; traces that
  // start at a coarser level cross the noise and reach the plateaus.
  const NoisyEdge edge(96, 64, 6.0, 0.05, 11);
  const double before = edge.Error(edge.input);
  for (double t : { 1e5, 1e7 })
  {
    const double single = edge.Error(Filter(edge.shape, 1, edge.input, Levels(1, t)));
    const double twoLevels = edge.Error(Filter(edge.shape, 1, edge.input, Levels(2, t)));
    EXPECT_LT(single, 0.97 * before) << "t = " << t;    // one level sharpens too, a little
    EXPECT_LT(twoLevels, 0.8 * single) << "t = " << t; // two levels clearly more
  }
}

TEST(GridHierarchy, CoarseLevelsRunTheSameFlowTimeInTheInputUnits)
{
  // Time scales with the fourth power of length: on a wide, smooth edge (where
  // every level sees the same profile) each level moves a trace as far in t as
  // the finest does, so two levels for t move values about as far as one level
  // for 2t. A coarse level run for t in its own units would move them 16 times
  // as far.
  const GridShape shape = Grid(257, 1);
  std::vector<double> input(257);
  for (int i = 0; i < 257; ++i)
  {
    input[i] = SmoothStep(i, 128.3, 20.0);
  }
  const double t = 1e5;
  const auto oneLevel2t = Filter(shape, 1, input, Levels(1, 2 * t));
  const auto twoLevels = Filter(shape, 1, input, Levels(2, t));
  const double change = MaxAbsDifference(oneLevel2t, input);
  ASSERT_GT(change, 0.02);
  EXPECT_LT(MaxAbsDifference(twoLevels, oneLevel2t), 0.25 * change) << change;
  EXPECT_GT(MaxAbsDifference(twoLevels, Filter(shape, 1, input, Levels(1, t))), 0.25 * change);
}

TEST(GridHierarchy, ResultDoesNotDependOnTheThreadCount)
{
  for (const GridShape& shape : { Grid(300, 1), Grid(70, 50), Grid(20, 18, 16) })
  {
    const auto input = Noisy(Bumps(shape, 2), 0.05, 13);
    for (FlowMode mode : { FlowMode::Fixed, FlowMode::Composed })
    {
      AdvectionParameters p = Levels(3, 2e3);
      p.flowMode = mode;
      p.numberOfThreads = 1;
      const auto serial = Filter(shape, 2, input, p);
      p.numberOfThreads = 2;
      EXPECT_EQ(Filter(shape, 2, input, p), serial);
    }
  }
}

TEST(GridHierarchy, NonFiniteSamplesKeepTheirValueAndDoNotSpread)
{
  const GridShape shape = Grid(40, 36);
  auto input = Noisy(Bumps(shape, 1), 0.03, 17);
  input[15 * 40 + 12] = std::numeric_limits<double>::quiet_NaN();
  input[30 * 40 + 33] = std::numeric_limits<double>::infinity();
  const auto out = Filter(shape, 1, input, Levels(4, 1e4));
  ASSERT_EQ(out.size(), input.size());
  for (size_t s = 0; s < out.size(); ++s)
  {
    if (std::isfinite(input[s]))
    {
      EXPECT_TRUE(std::isfinite(out[s])) << s;
    }
  }
  EXPECT_TRUE(std::isnan(out[15 * 40 + 12]));
  EXPECT_EQ(out[30 * 40 + 33], input[30 * 40 + 33]);
}

TEST(GridHierarchy, MoreLevelsThanTheGridHoldsAreNotBuilt)
{
  const GridShape shape = Grid(9, 5);
  const auto input = Bumps(shape, 1);
  AdvectionReport report;
  const auto many = Filter(shape, 1, input, Levels(16, 100.0), &report);
  EXPECT_EQ(report.hierarchyLevels, 3);
  EXPECT_EQ(many, Filter(shape, 1, input, Levels(3, 100.0)));
  AdvectionParameters bad = Levels(0, 1.0);
  std::vector<double> out(input.size());
  EXPECT_FALSE(AdvectGridSignal(shape, 1, input.data(), out.data(), bad).Ok());
}

} // namespace
