// Tests of the gradient domain (GridGradientDomain.h; beyond the paper, its
// section 6 future work): each step against an independent computation written
// from the method's definition (docs/gradient-domain.md), on small irregular
// grids in 1D, 2D and 3D.
#include "GridGradientDomain.h"
#include "GridShockAdvection.h"
#include "TestSignals.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
using namespace shock;
using namespace shocktest;

/// A grid with anisotropic spacing.
GridShape Shape(int nx, int ny, int nz, double hx, double hy, double hz)
{
  GridShape shape = Grid(nx, ny, nz);
  shape.spacing = { hx, hy, hz };
  return shape;
}

/// The axes with more than one sample, and each one's index step.
struct Axes
{
  std::vector<int> axis;
  std::vector<std::int64_t> step;
  explicit Axes(const GridShape& shape)
  {
    std::int64_t stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      if (shape.dimensions[a] > 1)
      {
        this->axis.push_back(a);
        this->step.push_back(stride);
      }
      stride *= shape.dimensions[a];
    }
  }
};

std::array<int, 3> Index(const GridShape& shape, std::int64_t s)
{
  const auto& n = shape.dimensions;
  return { static_cast<int>(s % n[0]), static_cast<int>((s / n[0]) % n[1]),
    static_cast<int>(s / (static_cast<std::int64_t>(n[0]) * n[1])) };
}

/**
 * The dense matrix lambda Id + sum_a D_a^T D_a / h_a^2, D_a the forward
 * difference over each edge along a, h_a the spacing in mean edge lengths:
 * the energy of step 4 (sum over edges of (dJ - g)^2 / h^2 + lambda (J - I)^2)
 * written edge by edge.
 */
Eigen::MatrixXd ScreenedMatrix(const GridShape& shape, double lambda, std::vector<double>& weight)
{
  const std::int64_t N = shape.NumberOfSamples();
  Eigen::MatrixXd A = lambda * Eigen::MatrixXd::Identity(N, N);
  const Axes axes(shape);
  weight.clear();
  for (size_t k = 0; k < axes.axis.size(); ++k)
  {
    const double h = shape.spacing[axes.axis[k]] / shape.MeanEdgeLength();
    weight.push_back(1.0 / (h * h));
  }
  for (std::int64_t s = 0; s < N; ++s)
  {
    for (size_t k = 0; k < axes.axis.size(); ++k)
    {
      if (Index(shape, s)[axes.axis[k]] + 1 >= shape.dimensions[axes.axis[k]])
      {
        continue;
      }
      const std::int64_t t = s + axes.step[k];
      A(s, s) += weight[k];
      A(t, t) += weight[k];
      A(s, t) -= weight[k];
      A(t, s) -= weight[k];
    }
  }
  return A;
}

const std::vector<GridShape>& IrregularShapes()
{
  static const std::vector<GridShape> shapes = { Shape(13, 1, 1, 0.7, 1.0, 1.0),
    Shape(9, 7, 1, 1.3, 0.8, 1.0), Shape(1, 6, 5, 1.0, 0.9, 1.7), Shape(5, 4, 3, 1.0, 0.5, 2.3) };
  return shapes;
}

TEST(GridGradientDomain, PoissonSolveEqualsADenseSolve)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const GridShape& shape : IrregularShapes())
  {
    for (double lambda : { 1e-3, 0.37, 20.0 })
    {
      std::vector<double> weight;
      const Eigen::MatrixXd A = ScreenedMatrix(shape, lambda, weight);
      Eigen::VectorXd b(shape.NumberOfSamples());
      for (Eigen::Index s = 0; s < b.size(); ++s)
      {
        b(s) = uniform(random);
      }
      const Eigen::VectorXd expected = A.ldlt().solve(b);
      std::vector<double> rhs(b.data(), b.data() + b.size());
      double lengths[3];
      for (int a = 0; a < 3; ++a)
      {
        lengths[a] = shape.spacing[a] / shape.MeanEdgeLength();
      }
      ASSERT_TRUE(SolveScreenedPoisson(shape, lengths, lambda, rhs.data(), 1).Ok());
      for (Eigen::Index s = 0; s < b.size(); ++s)
      {
        EXPECT_NEAR(rhs[static_cast<size_t>(s)], expected(s), 1e-9 * (1.0 + std::abs(expected(s))))
          << "sample " << s << ", lambda " << lambda;
      }
    }
  }
}

TEST(GridGradientDomain, PoissonRecoversASignalFromItsExactGradients)
{
  // J from (lambda + L) J = lambda u + D^T (D u): u itself, whatever lambda.
  for (const GridShape& shape : IrregularShapes())
  {
    const std::vector<double> u = Bumps(shape, 1, 0.4);
    std::vector<double> weight;
    const Eigen::MatrixXd A = ScreenedMatrix(shape, 0.05, weight);
    const Eigen::VectorXd b = A * Eigen::Map<const Eigen::VectorXd>(u.data(), static_cast<Eigen::Index>(u.size()));
    std::vector<double> rhs(b.data(), b.data() + b.size());
    double lengths[3];
    for (int a = 0; a < 3; ++a)
    {
      lengths[a] = shape.spacing[a] / shape.MeanEdgeLength();
    }
    ASSERT_TRUE(SolveScreenedPoisson(shape, lengths, 0.05, rhs.data(), 2).Ok());
    EXPECT_LT(MaxAbsDifference(rhs, u), 1e-10);
  }
}

/// The gradient domain's result, asserting success.
std::vector<double> Gradients(const GridShape& shape, int C, const std::vector<double>& input,
  const AdvectionParameters& p, double lambda = 0.01, AdvectionReport* report = nullptr)
{
  std::vector<double> out(input.size(), std::numeric_limits<double>::quiet_NaN());
  GradientDomainParameters domain;
  domain.screening = lambda;
  const SampleWriter writer = [&out, C](std::int64_t first, std::int64_t count, const double* v) {
    std::copy(v, v + count * C, out.begin() + first * C);
  };
  const Status status = AdvectGridGradients(shape, C, input.data(), writer, p, domain, report);
  EXPECT_TRUE(status.Ok()) << status.error;
  return out;
}

/// AdvectCarriedGridSignal into doubles, asserting success.
std::vector<double> Carried(const GridShape& shape, int C, const std::vector<double>& input,
  const std::vector<float>& carried, int carriedC, const AdvectionParameters& p)
{
  std::vector<double> out(static_cast<size_t>(shape.NumberOfSamples() * carriedC));
  const SampleWriter writer = [&out, carriedC](std::int64_t first, std::int64_t count, const double* v) {
    std::copy(v, v + count * carriedC, out.begin() + first * carriedC);
  };
  const Status status = AdvectCarriedGridSignal(
    shape, C, input.data(), CarriedSignal{ carried.data(), carriedC }, writer, p);
  EXPECT_TRUE(status.Ok()) << status.error;
  return out;
}

TEST(GridGradientDomain, CarriedSignalFollowsTheValuesFlow)
{
  // Carrying the values themselves gives value advection; carrying the sample
  // coordinates gives the traces' mean end points, and any affine function of
  // the coordinates comes out as that function of the end points (the
  // interpolation reproduces it): the carried channels share the values' traces.
  for (const GridShape& shape : IrregularShapes())
  {
    const int C = 2;
    const std::vector<double> input = Noisy(Bumps(shape, C, 0.2), 0.03, 3);
    AdvectionParameters p;
    p.time = 300.0;
    const std::vector<double> values = Filter(shape, C, input, p);
    const int carriedC = C + 4;
    std::vector<float> carried;
    for (std::int64_t s = 0; s < shape.NumberOfSamples(); ++s)
    {
      const auto i = Index(shape, s);
      carried.push_back(static_cast<float>(input[s * C]));
      carried.push_back(static_cast<float>(input[s * C + 1]));
      carried.push_back(static_cast<float>(i[0]));
      carried.push_back(static_cast<float>(i[1]));
      carried.push_back(static_cast<float>(i[2]));
      carried.push_back(static_cast<float>(0.5 * i[0] - 2.0 * i[1] + 3.0 * i[2] + 1.25));
    }
    const std::vector<double> out = Carried(shape, C, input, carried, carriedC, p);
    double moved = 0.0;
    for (std::int64_t s = 0; s < shape.NumberOfSamples(); ++s)
    {
      const double* o = out.data() + s * carriedC;
      for (int c = 0; c < C; ++c)
      {
        EXPECT_NEAR(o[c], values[s * C + c], 1e-6);
      }
      EXPECT_NEAR(o[5], 0.5 * o[2] - 2.0 * o[3] + 3.0 * o[4] + 1.25, 1e-5);
      const auto i = Index(shape, s);
      moved = std::max({ moved, std::abs(o[2] - i[0]), std::abs(o[3] - i[1]), std::abs(o[4] - i[2]) });
    }
    EXPECT_GT(moved, 0.2) << "the traces should move";
  }
}

TEST(GridGradientDomain, CarriedSignalFollowsTheValuesFlowThroughCoarseLevels)
{
  // With coarse-to-fine tracing (HierarchyLevels), the coarse levels' flows are
  // the input's (C components), whatever the carried signal holds: carrying
  // the values (and more channels) gives the values' own advection with the
  // same levels, which differs from the single-level one.
  for (const GridShape& shape : { Shape(41, 37, 1, 1.0, 1.2, 1.0), Shape(19, 17, 15, 0.9, 1.0, 1.1) })
  {
    const int C = 2;
    const std::vector<double> input = Noisy(Bumps(shape, C, 0.2), 0.03, 5);
    AdvectionParameters p;
    p.time = 2000.0;
    const std::vector<double> single = Filter(shape, C, input, p);
    p.hierarchyLevels = 3;
    const std::vector<double> values = Filter(shape, C, input, p);
    const int carriedC = C + 5; // more channels than the input: the levels must read the input's C
    std::vector<float> carried;
    for (std::int64_t s = 0; s < shape.NumberOfSamples(); ++s)
    {
      carried.push_back(static_cast<float>(input[s * C]));
      carried.push_back(static_cast<float>(input[s * C + 1]));
      for (int k = 0; k < carriedC - C; ++k)
      {
        carried.push_back(static_cast<float>(k + 1));
      }
    }
    const std::vector<double> out = Carried(shape, C, input, carried, carriedC, p);
    double levelsChange = 0.0;
    for (std::int64_t s = 0; s < shape.NumberOfSamples(); ++s)
    {
      for (int c = 0; c < C; ++c)
      {
        EXPECT_NEAR(out[s * carriedC + c], values[s * C + c], 1e-6);
        levelsChange = std::max(levelsChange, std::abs(values[s * C + c] - single[s * C + c]));
      }
      for (int k = C; k < carriedC; ++k)
      {
        EXPECT_NEAR(out[s * carriedC + k], k - C + 1, 1e-6); // a constant stays constant
      }
    }
    EXPECT_GT(levelsChange, 1e-3) << "the coarse levels should change the traces";
  }
}

TEST(GridGradientDomain, StepsEqualAnIndependentComputation)
{
  for (const GridShape& shape : IrregularShapes())
  {
    const int C = 2;
    const std::int64_t N = shape.NumberOfSamples();
    const std::vector<double> input = Noisy(Bumps(shape, C, 1.1), 0.02, 5);
    AdvectionParameters p;
    p.time = 300.0;
    const double lambda = 0.07;
    const Axes axes(shape);
    const int A = static_cast<int>(axes.axis.size());

    // Step 1: values, forward and backward differences per axis.
    const int carriedC = C * (1 + 2 * A);
    std::vector<float> carried(static_cast<size_t>(N * carriedC));
    for (std::int64_t s = 0; s < N; ++s)
    {
      const auto i = Index(shape, s);
      for (int c = 0; c < C; ++c)
      {
        carried[s * carriedC + c] = static_cast<float>(input[s * C + c]);
        for (int k = 0; k < A; ++k)
        {
          const int a = axes.axis[k];
          const std::int64_t t = axes.step[k];
          const double forward = i[a] + 1 < shape.dimensions[a] ? input[(s + t) * C + c] - input[s * C + c] : 0.0;
          const double backward = i[a] > 0 ? input[s * C + c] - input[(s - t) * C + c] : 0.0;
          carried[s * carriedC + C * (1 + 2 * k) + c] = static_cast<float>(forward);
          carried[s * carriedC + C * (2 + 2 * k) + c] = static_cast<float>(backward);
        }
      }
    }
    // Step 2: along the values' flow.
    const std::vector<double> advected = Carried(shape, C, input, carried, carriedC, p);
    // Step 3: per edge, the longer of the covariant and the transported difference.
    std::vector<double> g(static_cast<size_t>(N * A * C), 0.0);
    int covariantEdges = 0;
    int transportedEdges = 0;
    for (std::int64_t s = 0; s < N; ++s)
    {
      const auto i = Index(shape, s);
      for (int k = 0; k < A; ++k)
      {
        const int a = axes.axis[k];
        if (i[a] + 1 >= shape.dimensions[a])
        {
          continue;
        }
        const std::int64_t t = s + axes.step[k];
        double lengthV = 0.0, lengthT = 0.0;
        std::vector<double> dv(C), tv(C);
        for (int c = 0; c < C; ++c)
        {
          dv[c] = advected[t * carriedC + c] - advected[s * carriedC + c];
          tv[c] = 0.5 * (advected[s * carriedC + C * (1 + 2 * k) + c] + advected[t * carriedC + C * (2 + 2 * k) + c]);
          lengthV += dv[c] * dv[c];
          lengthT += tv[c] * tv[c];
        }
        (lengthV >= lengthT ? covariantEdges : transportedEdges)++;
        for (int c = 0; c < C; ++c)
        {
          g[(s * A + k) * C + c] = lengthV >= lengthT ? dv[c] : tv[c];
        }
      }
    }
    EXPECT_GT(covariantEdges, 0);
    EXPECT_GT(transportedEdges, 0) << "both transforms should occur on this signal";
    // Step 4: the dense normal equations, per channel.
    std::vector<double> weight;
    const Eigen::MatrixXd M = ScreenedMatrix(shape, lambda, weight);
    const auto solver = M.ldlt();
    std::vector<double> expected(input.size());
    for (int c = 0; c < C; ++c)
    {
      Eigen::VectorXd b(N);
      for (std::int64_t s = 0; s < N; ++s)
      {
        b(s) = lambda * input[s * C + c];
      }
      for (std::int64_t s = 0; s < N; ++s)
      {
        for (int k = 0; k < A; ++k)
        {
          const auto i = Index(shape, s);
          if (i[axes.axis[k]] + 1 < shape.dimensions[axes.axis[k]])
          {
            const double edge = weight[k] * g[(s * A + k) * C + c];
            b(s) -= edge;
            b(s + axes.step[k]) += edge;
          }
        }
      }
      const Eigen::VectorXd x = solver.solve(b);
      for (std::int64_t s = 0; s < N; ++s)
      {
        expected[s * C + c] = x(s);
      }
    }
    const std::vector<double> result = Gradients(shape, C, input, p, lambda);
    // The kernel carries its values in floats less the channel's mid-range: float rounding.
    EXPECT_LT(MaxAbsDifference(result, expected), 2e-6 * Range(input));
    EXPECT_GT(MaxAbsDifference(result, input), 0.02 * Range(input)) << "the filter should change the signal";
  }
}

TEST(GridGradientDomain, ZeroTimeReturnsTheInput)
{
  for (const GridShape& shape : IrregularShapes())
  {
    const std::vector<double> input = Noisy(Bumps(shape, 3, 0.7), 0.05, 11);
    AdvectionParameters p;
    p.time = 0.0;
    EXPECT_EQ(Gradients(shape, 3, input, p), input);
    p.time = 300.0;
    EXPECT_GT(MaxAbsDifference(Gradients(shape, 3, input, p), input), 0.01);
  }
}

TEST(GridGradientDomain, InvariantToRangeOffsetAndSpacingScale)
{
  for (const GridShape& shape : IrregularShapes())
  {
    const std::vector<double> input = Noisy(Bumps(shape, 1, 0.3), 0.02, 13);
    AdvectionParameters p;
    p.time = 300.0;
    const std::vector<double> base = Gradients(shape, 1, input, p);
    EXPECT_GT(MaxAbsDifference(base, input), 0.01);
    // Values a x + b: the result a R + b (float rounding of the carried
    // values), down to denormal-float scales and up to beyond a float's range.
    for (const double a : { 1000.0, 1e-40, 1e39, 1e300 })
    {
      const double b = -7.0 * a;
      std::vector<double> scaled(input);
      for (double& v : scaled)
      {
        v = a * v + b;
      }
      const std::vector<double> scaledOut = Gradients(shape, 1, scaled, p);
      for (size_t s = 0; s < base.size(); ++s)
      {
        ASSERT_NEAR(scaledOut[s] / a, base[s] - 7.0, 2e-6) << "scale " << a << ", sample " << s;
      }
    }
    // Every spacing times 3.7: lengths are in mean edge lengths.
    GridShape stretched = shape;
    for (double& h : stretched.spacing)
    {
      h *= 3.7;
    }
    EXPECT_LT(MaxAbsDifference(Gradients(stretched, 1, input, p), base), 1e-9);
  }
}

TEST(GridGradientDomain, SharpensABlurredEdge)
{
  const GridShape shape = Grid(48, 6);
  std::vector<double> input;
  for (int j = 0; j < 6; ++j)
  {
    for (int i = 0; i < 48; ++i)
    {
      input.push_back(SmoothStep(i, 23.5 + 0.3 * j, 3.0));
    }
  }
  AdvectionParameters p;
  p.time = 2000.0;
  const std::vector<double> out = Gradients(shape, 1, input, p);
  for (int j = 0; j < 6; ++j)
  {
    // The edge's width shrinks (the covariant differences win across it).
    EXPECT_LT(RiseWidth(out.data() + j * 48, 48), 0.75 * RiseWidth(input.data() + j * 48, 48)) << "row " << j;
  }
}

TEST(GridGradientDomain, ConstantAndSingleSampleSignalsComeBackUnchanged)
{
  AdvectionParameters p;
  p.time = 500.0;
  const std::vector<double> constant(7 * 5 * 2, 0.25);
  EXPECT_EQ(Gradients(Grid(7, 5), 2, constant, p), constant);
  const std::vector<double> one = { 3.5, -1.0 };
  EXPECT_EQ(Gradients(Grid(1, 1), 2, one, p), one);
}

TEST(GridGradientDomain, SameResultOnAnyNumberOfThreads)
{
  // Large enough for two threads (ThreadsForWork: one per 16384 samples).
  const GridShape shape = Shape(64, 64, 9, 1.0, 1.2, 0.8);
  const std::vector<double> input = Noisy(Bumps(shape, 2, 0.1), 0.02, 17);
  AdvectionParameters p;
  p.time = 40.0;
  p.numberOfThreads = 1;
  const std::vector<double> one = Gradients(shape, 2, input, p);
  p.numberOfThreads = 2;
  EXPECT_EQ(Gradients(shape, 2, input, p), one);
}

TEST(GridGradientDomain, RefusesWhatItCannotDo)
{
  const GridShape shape = Grid(8, 8);
  std::vector<double> input = Bumps(shape, 1);
  std::vector<double> out(input.size());
  const SampleWriter writer = [&out](std::int64_t first, std::int64_t count, const double* v) {
    std::copy(v, v + count, out.begin() + first);
  };
  AdvectionParameters p;
  p.time = 10.0;
  GradientDomainParameters domain;
  domain.screening = 0.0;
  EXPECT_NE(AdvectGridGradients(shape, 1, input.data(), writer, p, domain).error.find("screening"), std::string::npos);
  domain.screening = 0.01;
  p.flowMode = FlowMode::Composed;
  EXPECT_NE(AdvectGridGradients(shape, 1, input.data(), writer, p, domain).error.find("fixed flow"), std::string::npos);
  p.flowMode = FlowMode::Fixed;
  input[20] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(AdvectGridGradients(shape, 1, input.data(), writer, p, domain).error.find("finite"), std::string::npos);
}

} // namespace
