// Synthetic signals and measurements shared by the shock-filter tests.
#ifndef TestSignals_h
#define TestSignals_h

#include "GridShockAdvection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace shocktest
{

inline shock::GridShape Grid(int nx, int ny, int nz = 1)
{
  shock::GridShape shape;
  shape.dimensions = { nx, ny, nz };
  return shape;
}

/// Blurred unit step at x0 with Gaussian blur sigma (an error-function profile).
inline double SmoothStep(double x, double x0, double sigma)
{
  return 0.5 * (1.0 + std::erf((x - x0) / (std::sqrt(2.0) * sigma)));
}

/**
 * A smooth multi-feature signal per channel (bumps, a blurred step, a ramp),
 * each channel rescaled to exactly [0, 1]; `phase` varies the features.
 */
inline std::vector<double> Bumps(const shock::GridShape& shape, int components, double phase = 0.0)
{
  const auto& n = shape.dimensions;
  std::vector<double> values(static_cast<size_t>(shape.NumberOfSamples() * components));
  for (int c = 0; c < components; ++c)
  {
    const double p = phase + 0.9 * c;
    for (int k = 0; k < n[2]; ++k)
    {
      for (int j = 0; j < n[1]; ++j)
      {
        for (int i = 0; i < n[0]; ++i)
        {
          const double x = i / std::max(1.0, n[0] - 1.0), y = j / std::max(1.0, n[1] - 1.0),
                       z = k / std::max(1.0, n[2] - 1.0);
          // On a grid with one z layer (or one row) the bumps lie in it: their
          // centres along a flat axis would otherwise put them out of reach.
          auto bump = [&](double cx, double cy, double cz, double r) {
            const double dy = n[1] > 1 ? y - cy : 0.0;
            const double dz = n[2] > 1 ? z - cz : 0.0;
            const double d2 = (x - cx) * (x - cx) + dy * dy + dz * dz;
            return std::exp(-d2 / (r * r));
          };
          const double v = bump(0.3 + 0.1 * std::sin(p), 0.35, 0.4, 0.18) -
            0.8 * bump(0.7, 0.6 + 0.1 * std::cos(p), 0.6, 0.12) +
            SmoothStep(x + 0.3 * y, 0.55 + 0.05 * p, 0.06) + 0.3 * z;
          values[static_cast<size_t>(((k * n[1] + j) * n[0] + i) * components + c)] = v;
        }
      }
    }
    double lo = 1e300, hi = -1e300;
    for (size_t s = c; s < values.size(); s += components)
    {
      lo = std::min(lo, values[s]);
      hi = std::max(hi, values[s]);
    }
    for (size_t s = c; s < values.size(); s += components)
    {
      values[s] = (values[s] - lo) / (hi - lo);
    }
  }
  return values;
}

/// values + uniform noise in [-amplitude, amplitude] (deterministic).
inline std::vector<double> Noisy(std::vector<double> values, double amplitude, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> noise(-amplitude, amplitude);
  for (double& v : values)
  {
    v += noise(random);
  }
  return values;
}

inline double Range(const std::vector<double>& v)
{
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi - *lo;
}

inline double MeanAbsDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    sum += std::abs(a[i] - b[i]);
  }
  return sum / static_cast<double>(a.size());
}

inline double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst;
}

inline double TotalVariation(const std::vector<double>& v)
{
  double tv = 0.0;
  for (size_t i = 1; i < v.size(); ++i)
  {
    tv += std::abs(v[i] - v[i - 1]);
  }
  return tv;
}

/// Distance between the 10% and 90% level crossings of a monotone-ish profile.
inline double RiseWidth(const double* profile, int n)
{
  const auto [lo, hi] = std::minmax_element(profile, profile + n);
  auto crossing = [&](double level) {
    for (int i = 0; i + 1 < n; ++i)
    {
      const double a = profile[i] - level, b = profile[i + 1] - level;
      if (a == 0.0)
      {
        return static_cast<double>(i);
      }
      if ((a < 0.0) != (b < 0.0))
      {
        return i + a / (a - b);
      }
    }
    return static_cast<double>(n - 1);
  };
  return std::abs(crossing(*lo + 0.9 * (*hi - *lo)) - crossing(*lo + 0.1 * (*hi - *lo)));
}

/// Run the kernel, asserting success.
inline std::vector<double> Filter(const shock::GridShape& shape, int components,
  const std::vector<double>& input, const shock::AdvectionParameters& parameters,
  shock::AdvectionReport* report = nullptr, shock::GridFlowFields* fields = nullptr)
{
  std::vector<double> output(input.size());
  shock::AdvectionReport local;
  shock::AdvectionReport& r = report ? *report : local;
  const shock::Status status =
    shock::AdvectGridSignal(shape, components, input.data(), output.data(), parameters, &r, fields);
  if (!status.Ok())
  {
    output.clear();
  }
  // The guard against discrete cycles never cuts a trace in these tests (README).
  EXPECT_EQ(r.truncatedTraces, 0u);
  return output;
}

} // namespace shocktest

#endif
