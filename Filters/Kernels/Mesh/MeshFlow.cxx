#include "MeshFlow.h"

#include <algorithm>
#include <cmath>

namespace shock
{

ValueVector UmbrellaWeights(const TriangleMesh& mesh, double length, int threads)
{
  const CompressedLists& ring = mesh.OneRing();
  const double l = length;
  const std::int64_t np = mesh.NumberOfPoints();
  ValueVector weights(ring.items.size()); // every entry written below
  auto weight = [&](std::int64_t p, std::int64_t q) {
    const Vec3 d = Combine(1.0, Load(mesh.Point(p)), -1.0, Load(mesh.Point(q)));
    return std::exp(-Dot(d, d) / (l * l));
  };
  // An edge's weight once, from its lower end; the upper end finds the same
  // value in the lower end's (sorted) ring: x_p - x_q = -(x_q - x_p) exactly,
  // so the weight is the same number either way.
#pragma omp parallel num_threads(threads)
  {
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      for (std::int64_t k = ring.Begin(p); k < ring.End(p); ++k)
      {
        const std::int64_t q = ring.items[static_cast<size_t>(k)];
        if (q > p)
        {
          weights[static_cast<size_t>(k)] = weight(p, q);
        }
      }
    }
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      for (std::int64_t k = ring.Begin(p); k < ring.End(p); ++k)
      {
        const std::int64_t q = ring.items[static_cast<size_t>(k)];
        if (q < p)
        {
          const auto first = ring.items.begin() + ring.Begin(q);
          const auto last = ring.items.begin() + ring.End(q);
          const auto at = std::lower_bound(first, last, p);
          weights[static_cast<size_t>(k)] =
            at != last && *at == p ? weights[static_cast<size_t>(at - ring.items.begin())] : weight(p, q);
        }
      }
    }
  }
  return weights;
}

void UmbrellaSmooth(const TriangleMesh& mesh, const ValueVector& weights,
  const std::vector<unsigned char>& validPoint, int C, std::vector<double>& values, int passes,
  int threads)
{
  const CompressedLists& ring = mesh.OneRing();
  std::vector<double> smoothed(values.size());
  for (int pass = 0; pass < passes; ++pass)
  {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
    {
      double* out = &smoothed[static_cast<size_t>(p * C)];
      const double* self = &values[static_cast<size_t>(p * C)];
      for (int c = 0; c < C; ++c)
      {
        out[c] = self[c]; // a loop: a copy of C values (C known at run time) would call memmove
      }
      if (!validPoint[static_cast<size_t>(p)])
      {
        continue;
      }
      double weight = 1.0;
      for (std::int64_t k = ring.Begin(p); k < ring.End(p); ++k)
      {
        const std::int64_t w = ring.items[static_cast<size_t>(k)];
        if (!validPoint[static_cast<size_t>(w)])
        {
          continue;
        }
        const double a = weights[static_cast<size_t>(k)];
        weight += a;
        for (int c = 0; c < C; ++c)
        {
          out[c] += a * values[static_cast<size_t>(w * C + c)];
        }
      }
      for (int c = 0; c < C; ++c)
      {
        out[c] /= weight;
      }
    }
    values.swap(smoothed);
  }
}

Vec3 TriangleGradient(
  const TriangleMesh& mesh, const double* values, int C, int c, std::int64_t f, double length)
{
  const std::int64_t* t = mesh.Corners(f);
  Vec3 g{ 0.0, 0.0, 0.0 };
  for (int k = 0; k < 3; ++k)
  {
    g = Combine(1.0, g, values[t[k] * C + c], Load(mesh.HatGradient(f, k)));
  }
  const double l = length;
  return { g[0] * l, g[1] * l, g[2] * l };
}

ValueVector TriangleEnergy(const TriangleMesh& mesh, const double* values, int C,
  const std::vector<unsigned char>& validTriangle, double length, int threads)
{
  ValueVector energy(static_cast<size_t>(mesh.NumberOfTriangles())); // every entry written below
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    if (!validTriangle[static_cast<size_t>(f)])
    {
      energy[static_cast<size_t>(f)] = 0.0;
      continue;
    }
    double e = 0.0;
    for (int c = 0; c < C; ++c)
    {
      const Vec3 g = TriangleGradient(mesh, values, C, c, f, length);
      e += Dot(g, g);
    }
    energy[static_cast<size_t>(f)] = e;
  }
  return energy;
}

void TrianglesToPoints(const TriangleMesh& mesh, int C, const double* cells,
  const std::vector<unsigned char>& cellValid, std::vector<double>& points, int threads)
{
  const CompressedLists& around = mesh.PointTriangles();
  points.assign(static_cast<size_t>(mesh.NumberOfPoints() * C), 0.0);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    double total = 0.0;
    double* out = &points[static_cast<size_t>(p * C)];
    for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
    {
      const std::int64_t f = around.items[static_cast<size_t>(k)];
      const double a = mesh.Area(f);
      if (a > 0.0 && cellValid[static_cast<size_t>(f)])
      {
        total += a;
        for (int c = 0; c < C; ++c)
        {
          out[c] += a * cells[f * C + c];
        }
      }
    }
    for (int c = 0; c < C; ++c)
    {
      out[c] = total > 0.0 ? out[c] / total : 0.0;
    }
  }
}

ValueVector TriangleFlow(const TriangleMesh& mesh, const std::vector<double>& potential,
  const std::vector<unsigned char>& validTriangle, double length, int threads)
{
  ValueVector flow(static_cast<size_t>(3 * mesh.NumberOfTriangles())); // every value written below
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const Vec3 g = validTriangle[static_cast<size_t>(f)]
      ? TriangleGradient(mesh, potential.data(), 1, 0, f, length)
      : Vec3{ 0.0, 0.0, 0.0 };
    for (int k = 0; k < 3; ++k)
    {
      flow[static_cast<size_t>(3 * f + k)] = 0.5 * g[k];
    }
  }
  return flow;
}

std::vector<double> RingMinimum(const TriangleMesh& mesh, const std::vector<unsigned char>& validPoint,
  const std::vector<double>& values, int rings, int threads)
{
  const CompressedLists& ring = mesh.OneRing();
  std::vector<double> low = values;
  std::vector<double> next(values.size());
  for (int r = 0; r < rings; ++r)
  {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
    {
      double m = low[static_cast<size_t>(p)];
      if (validPoint[static_cast<size_t>(p)])
      {
        for (std::int64_t k = ring.Begin(p); k < ring.End(p); ++k)
        {
          const std::int64_t w = ring.items[static_cast<size_t>(k)];
          if (validPoint[static_cast<size_t>(w)])
          {
            m = std::min(m, low[static_cast<size_t>(w)]);
          }
        }
      }
      next[static_cast<size_t>(p)] = m;
    }
    low.swap(next);
  }
  return low;
}

void CurvatureContrast(const TriangleMesh& mesh, const std::vector<unsigned char>& validPoint,
  std::vector<double>& potential, double contrast, int rings, int threads)
{
  if (!(contrast > 0.0))
  {
    return; // the paper: the potential as it is
  }
  const std::vector<double> low = RingMinimum(mesh, validPoint, potential, rings, threads);
  const auto n = static_cast<std::int64_t>(potential.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < n; ++p)
  {
    const size_t i = static_cast<size_t>(p);
    potential[i] = std::max(0.0, potential[i] - contrast * low[i]);
  }
}

} // namespace shock
