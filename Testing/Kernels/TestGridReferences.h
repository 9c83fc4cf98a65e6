// The reference computations and grids shared by the grid kernel's step tests
// (TestGridSteps.cxx: each step against the paper; TestGridFastPaths.cxx: each
// fast path against the plain one). Each test file gets its own copy (an
// unnamed namespace).
#ifndef TestGridReferences_h
#define TestGridReferences_h

#include "GridAdvect.h"
#include "GridShockAdvection.h"
#include "GridFlow.h"
#include "GridLattice.h"
#include "GridTrace.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

namespace
{
using namespace shock;
using namespace shock::grid;

/// A small 3D-indexed grid (flat axes have one sample) with its own l-bar.
struct RefGrid
{
  std::array<int, 3> n;
  std::array<double, 3> spacing;

  GridShape Shape() const
  {
    GridShape s;
    s.dimensions = n;
    s.spacing = spacing;
    return s;
  }
  int Samples() const { return n[0] * n[1] * n[2]; }
  int Index(int i, int j, int k) const { return (k * n[1] + j) * n[0] + i; }
  /// l-bar: the mean length over all grid edges, counted one by one.
  double MeanEdge() const
  {
    double sum = 0.0;
    int count = 0;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          if (i + 1 < n[0]) { sum += spacing[0]; ++count; }
          if (j + 1 < n[1]) { sum += spacing[1]; ++count; }
          if (k + 1 < n[2]) { sum += spacing[2]; ++count; }
        }
    return sum / count;
  }
  std::vector<int> ActiveAxes() const
  {
    std::vector<int> axes;
    for (int a = 0; a < 3; ++a)
      if (n[a] > 1)
        axes.push_back(a);
    return axes;
  }
};

/// A writer of AdvectVertices' results into `out` (C values per sample).
SampleWriter Into(std::vector<double>& out, int C)
{
  return [&out, C](std::int64_t first, std::int64_t count, const double* values) {
    std::copy(values, values + count * C, out.begin() + first * C);
  };
}

std::vector<double> Random(size_t count, unsigned seed, double low = 0.0, double high = 1.0)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(low, high);
  std::vector<double> v(count);
  for (double& x : v)
    x = u(random);
  return v;
}

/// Appendix A umbrella smoothing: (I[v] + sum a_vw I[w]) / (1 + sum a_vw),
/// a_vw = exp(-|(v - w)/l|^2), over the grid neighbours of v.
std::vector<double> RefSmooth(const RefGrid& g, int C, const std::vector<double>& in,
  const std::vector<unsigned char>* valid = nullptr)
{
  const double l = g.MeanEdge();
  std::vector<double> out(in.size());
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
      {
        const int v = g.Index(i, j, k);
        double total = 1.0;
        std::vector<double> sum(in.begin() + v * C, in.begin() + (v + 1) * C);
        const bool self = !valid || (*valid)[v];
        const int offsets[6][3] = { { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 },
          { 0, 0, -1 }, { 0, 0, 1 } };
        for (const auto& o : offsets)
        {
          const int a = i + o[0], b = j + o[1], c = k + o[2];
          if (!self || a < 0 || b < 0 || c < 0 || a >= g.n[0] || b >= g.n[1] || c >= g.n[2])
            continue;
          const int w = g.Index(a, b, c);
          if (valid && !(*valid)[w])
            continue;
          const double d = std::abs(o[0]) * g.spacing[0] + std::abs(o[1]) * g.spacing[1] +
            std::abs(o[2]) * g.spacing[2];
          const double alpha = std::exp(-(d / l) * (d / l));
          total += alpha;
          for (int ch = 0; ch < C; ++ch)
            sum[ch] += alpha * in[w * C + ch];
        }
        for (int ch = 0; ch < C; ++ch)
          out[v * C + ch] = sum[ch] / total;
      }
  return out;
}

/// The faces of the grid (cells spanned by the active axes), by lower corner.
std::vector<std::array<int, 3>> RefFaces(const RefGrid& g)
{
  std::vector<std::array<int, 3>> faces;
  const auto m = [&](int a) { return g.n[a] > 1 ? g.n[a] - 1 : 1; };
  for (int k = 0; k < m(2); ++k)
    for (int j = 0; j < m(1); ++j)
      for (int i = 0; i < m(0); ++i)
        faces.push_back({ i, j, k });
  return faces;
}

/// Appendix A face gradient: per active axis, the average finite difference over the
/// face's parallel edges, divided by the edge length in units of l-bar.
std::vector<double> RefFaceGradient(
  const RefGrid& g, int C, int ch, const std::vector<double>& values, std::array<int, 3> f)
{
  const double l = g.MeanEdge();
  std::vector<double> grad;
  const auto axes = g.ActiveAxes();
  for (int a : axes)
  {
    double sum = 0.0;
    int edges = 0;
    // Every corner of the face whose coordinate along a is the lower one.
    for (int corner = 0; corner < (1 << axes.size()); ++corner)
    {
      std::array<int, 3> p = f;
      bool lower = true;
      for (size_t q = 0; q < axes.size(); ++q)
      {
        const int bit = (corner >> q) & 1;
        p[axes[q]] += bit;
        lower = lower && !(axes[q] == a && bit);
      }
      if (!lower)
        continue;
      std::array<int, 3> up = p;
      up[a] += 1;
      sum += values[g.Index(up[0], up[1], up[2]) * C + ch] - values[g.Index(p[0], p[1], p[2]) * C + ch];
      ++edges;
    }
    grad.push_back(sum / edges / (g.spacing[a] / l));
  }
  return grad;
}

double RefEnergy(const RefGrid& g, int C, const std::vector<double>& values, std::array<int, 3> f)
{
  double e = 0.0;
  for (int ch = 0; ch < C; ++ch)
    for (double x : RefFaceGradient(g, C, ch, values, f))
      e += x * x;
  return e;
}

/// Potential: at each sample the average of the energies of its adjacent faces
/// (faces of a grid have equal areas, so the area weights are equal).
std::vector<double> RefPotential(const RefGrid& g, const std::vector<double>& faceEnergy)
{
  const auto faces = RefFaces(g);
  std::vector<double> sum(g.Samples(), 0.0);
  std::vector<int> count(g.Samples(), 0);
  const auto axes = g.ActiveAxes();
  for (size_t f = 0; f < faces.size(); ++f)
    for (int corner = 0; corner < (1 << axes.size()); ++corner)
    {
      std::array<int, 3> p = faces[f];
      for (size_t q = 0; q < axes.size(); ++q)
        p[axes[q]] += (corner >> q) & 1;
      sum[g.Index(p[0], p[1], p[2])] += faceEnergy[f];
      count[g.Index(p[0], p[1], p[2])] += 1;
    }
  for (int s = 0; s < g.Samples(); ++s)
    sum[s] /= count[s];
  return sum;
}

/// The whole flow of section 3.3 / Appendix A: smooth, energy per face, potential,
/// smooth, u = 1/2 grad P (per face, active axes, normalised units).
void RefFlow(const RefGrid& g, int C, const std::vector<double>& input, double range, int passes,
  std::vector<double>& potential, std::vector<std::vector<double>>& flow)
{
  std::vector<double> s(input);
  for (double& x : s)
    x /= range;
  for (int k = 0; k < passes; ++k)
    s = RefSmooth(g, C, s);
  std::vector<double> energy;
  for (const auto& f : RefFaces(g))
    energy.push_back(RefEnergy(g, C, s, f));
  potential = RefPotential(g, energy);
  for (int k = 0; k < passes; ++k)
    potential = RefSmooth(g, 1, potential);
  flow.clear();
  for (const auto& f : RefFaces(g))
  {
    auto u = RefFaceGradient(g, 1, 0, potential, f);
    for (double& x : u)
      x *= 0.5;
    flow.push_back(u);
  }
}

} // namespace

#endif
