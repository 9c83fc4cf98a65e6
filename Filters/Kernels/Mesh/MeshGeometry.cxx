#include "MeshGeometry.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shock
{

namespace
{
/// A copy of the first n items of `from` (null when it is null).
template <typename T>
std::unique_ptr<T[]> CopyOf(const std::unique_ptr<T[]>& from, std::int64_t n)
{
  std::unique_ptr<T[]> to(from ? new T[static_cast<size_t>(n)] : nullptr);
  std::copy(from.get(), from.get() + (from ? n : 0), to.get());
  return to;
}

/// A copy of the first n items of `from` (null when it is null).
template <typename T>
std::shared_ptr<T[]> CopyOf(const std::shared_ptr<T[]>& from, std::int64_t n)
{
  std::shared_ptr<T[]> to(from ? new T[static_cast<size_t>(n)] : nullptr);
  std::copy(from.get(), from.get() + (from ? n : 0), to.get());
  return to;
}

/// Below this area (relative to l-bar^2) a triangle has no reliable normal or gradient.
constexpr double DegenerateAreaFraction = 1e-12;
} // namespace

MeshGeometry& MeshGeometry::operator=(const MeshGeometry& other)
{
  const std::int64_t np = other.numberOfPoints;
  const std::int64_t nt = other.numberOfTriangles;
  this->numberOfPoints = np;
  this->numberOfTriangles = nt;
  this->meanEdgeLength = other.meanEdgeLength;
  this->points = CopyOf(other.points, 3 * np);
  this->area = CopyOf(other.area, nt);
  this->degenerate = CopyOf(other.degenerate, nt);
  this->normal = CopyOf(other.normal, 3 * nt);
  this->hatGradient = CopyOf(other.hatGradient, 9 * nt);
  return *this;
}

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
      TrianglePerimeter(this->points.get(), connectivity.Corners(f));
  }
  const double total = std::accumulate(perimeter.begin(), perimeter.end(), 0.0);
  this->meanEdgeLength = nt > 0 ? total / (3.0 * static_cast<double>(nt)) : 0.0;
}

/// Per-triangle area, degeneracy, normal and hat gradients:
/// grad(phi_c) = N x (edge opposite c, counter-clockwise) / (2A).
void MeshGeometry::ComputeTriangles(const MeshConnectivity& connectivity, int threads)
{
  const std::int64_t nt = connectivity.NumberOfTriangles();
  this->area.reset(new double[static_cast<size_t>(nt)]);
  this->degenerate.reset(new unsigned char[static_cast<size_t>(nt)]);
  this->normal.reset(new double[static_cast<size_t>(3 * nt)]);
  this->hatGradient.reset(new double[static_cast<size_t>(9 * nt)]);
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
    }
    const Vec3 n = Cross(e1, e2);
    const double twiceArea = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated || !(0.5 * twiceArea > minArea) || this->meanEdgeLength <= 0.0)
    {
      // Degenerate: no area, normal or gradients.
      this->area[f] = 0.0;
      this->degenerate[f] = 1;
      std::fill(&this->normal[3 * f], &this->normal[3 * f] + 3, 0.0);
      std::fill(&this->hatGradient[9 * f], &this->hatGradient[9 * f] + 9, 0.0);
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

void MeshGeometry::ComputeFromCopies(
  const MeshGeometry& source, const std::vector<std::int64_t>& original, int threads)
{
  const auto np = static_cast<std::int64_t>(original.size());
  this->numberOfPoints = np;
  this->numberOfTriangles = source.numberOfTriangles;
  this->meanEdgeLength = source.meanEdgeLength; // the same perimeters, summed in the same order
  this->points.reset(new double[static_cast<size_t>(3 * np)]);
  const int team = ThreadsForWork(threads, np);
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::int64_t q = 0; q < np; ++q)
  {
    std::copy(source.Point(original[static_cast<size_t>(q)]),
      source.Point(original[static_cast<size_t>(q)]) + 3, &this->points[static_cast<size_t>(3 * q)]);
  }
  this->area = source.area;
  this->degenerate = source.degenerate;
  this->normal = source.normal;
  this->hatGradient = source.hatGradient;
}

Status MeshGeometry::Compute(const MeshConnectivity& connectivity, const double* points, int threads)
{
  const std::int64_t np = connectivity.NumberOfPoints();
  if (np > 0 && !points)
  {
    return { "invalid mesh arrays" };
  }
  const int team = ThreadsForWork(threads, std::max(np, connectivity.NumberOfTriangles()));
  this->numberOfPoints = np;
  this->numberOfTriangles = connectivity.NumberOfTriangles();
  this->points.reset(new double[static_cast<size_t>(3 * np)]);
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
