#include "MeshGeometry.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shock
{

namespace
{
/// Below this area (relative to l-bar^2) a triangle has no reliable normal or gradient.
constexpr double DegenerateAreaFraction = 1e-12;
} // namespace

double TrianglePerimeter(const double* points, const std::int64_t* corners)
{
  double sum = 0.0;
  for (int e = 0; e < 3; ++e)
  {
    const double* x = points + 3 * corners[e];
    const double* y = points + 3 * corners[(e + 1) % 3];
    sum += std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
      (x[2] - y[2]) * (x[2] - y[2]));
  }
  return sum;
}

/// Mean length of the triangles' edges, each triangle's three (see the header);
/// per-triangle sums added in order, so it does not depend on the thread count.
void MeshGeometry::ComputeMeanEdgeLength(const MeshConnectivity& connectivity, int threads)
{
  const std::int64_t nt = connectivity.NumberOfTriangles();
  std::vector<double> perimeter(static_cast<size_t>(nt));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    perimeter[static_cast<size_t>(f)] =
      TrianglePerimeter(this->points.data(), connectivity.Corners(f));
  }
  const double total = std::accumulate(perimeter.begin(), perimeter.end(), 0.0);
  this->meanEdgeLength = nt > 0 ? total / (3.0 * static_cast<double>(nt)) : 0.0;
}

/// Per-triangle area, degeneracy, normal, centroid and hat gradients:
/// grad(phi_c) = N x (edge opposite c, counter-clockwise) / (2A).
void MeshGeometry::ComputeTriangles(const MeshConnectivity& connectivity, int threads)
{
  const std::int64_t nt = connectivity.NumberOfTriangles();
  this->area.assign(static_cast<size_t>(nt), 0.0);
  this->degenerate.assign(static_cast<size_t>(nt), 1);
  this->normal.assign(static_cast<size_t>(3 * nt), 0.0);
  this->centroid.assign(static_cast<size_t>(3 * nt), 0.0);
  this->hatGradient.assign(static_cast<size_t>(9 * nt), 0.0);
  const double minArea = DegenerateAreaFraction * this->meanEdgeLength * this->meanEdgeLength;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t* t = connectivity.Corners(f);
    const double* x[3] = { this->Point(t[0]), this->Point(t[1]), this->Point(t[2]) };
    Vec3 e1, e2;
    for (int k = 0; k < 3; ++k)
    {
      e1[k] = x[1][k] - x[0][k];
      e2[k] = x[2][k] - x[0][k];
      this->centroid[3 * f + k] = (x[0][k] + x[1][k] + x[2][k]) / 3.0;
    }
    const Vec3 n = Cross(e1, e2);
    const double twiceArea = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated || !(0.5 * twiceArea > minArea) || this->meanEdgeLength <= 0.0)
    {
      continue;
    }
    this->area[f] = 0.5 * twiceArea;
    this->degenerate[f] = 0;
    Vec3 unit;
    for (int k = 0; k < 3; ++k)
    {
      unit[k] = n[k] / twiceArea;
      this->normal[3 * f + k] = unit[k];
    }
    for (int c = 0; c < 3; ++c)
    {
      const double* a = x[(c + 1) % 3];
      const double* b = x[(c + 2) % 3];
      const Vec3 edge = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const Vec3 g = Cross(unit, edge);
      for (int k = 0; k < 3; ++k)
      {
        this->hatGradient[9 * f + 3 * c + k] = g[k] / twiceArea;
      }
    }
  }
}

Status MeshGeometry::Compute(const MeshConnectivity& connectivity, const double* points, int threads)
{
  const std::int64_t np = connectivity.NumberOfPoints();
  if (np > 0 && !points)
  {
    return { "invalid mesh arrays" };
  }
  const int team = ThreadsForWork(threads, std::max(np, connectivity.NumberOfTriangles()));
  this->points.resize(static_cast<size_t>(3 * np));
  bool finite = true;
#pragma omp parallel for num_threads(team) reduction(&& : finite) schedule(static)
  for (std::int64_t i = 0; i < 3 * np; ++i)
  {
    this->points[static_cast<size_t>(i)] = points[i];
    finite = finite && std::isfinite(points[i]);
  }
  if (!finite)
  {
    return { "a point coordinate is not finite (NaN or infinity)" };
  }
  this->ComputeMeanEdgeLength(connectivity, team);
  this->ComputeTriangles(connectivity, team);
  return {};
}

} // namespace shock
