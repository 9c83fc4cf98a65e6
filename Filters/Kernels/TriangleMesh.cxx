#include "TriangleMesh.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace shock
{

namespace
{
/// Below this area (relative to l-bar^2) a triangle has no reliable normal or gradient.
constexpr double DegenerateAreaFraction = 1e-12;

/// Fill compressed lists from per-entry counts (prefix sum).
void SetOffsets(const std::vector<std::int64_t>& counts, CompressedLists& lists)
{
  lists.offsets.assign(counts.size() + 1, 0);
  for (size_t i = 0; i < counts.size(); ++i)
  {
    lists.offsets[i + 1] = lists.offsets[i] + counts[i];
  }
  lists.items.resize(static_cast<size_t>(lists.offsets.back()));
}
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

/// Triangles around each point, in triangle order (deterministic); a triangle
/// with a repeated id is listed once per point.
void TriangleMesh::BuildPointTriangles(int)
{
  const std::int64_t np = this->numberOfPoints;
  const std::int64_t nt = this->numberOfTriangles;
  std::vector<std::int64_t> counts(static_cast<size_t>(np), 0);
  for (std::int64_t id : this->triangles)
  {
    ++counts[static_cast<size_t>(id)];
  }
  SetOffsets(counts, this->pointTriangles);
  std::vector<std::int64_t> cursor(this->pointTriangles.offsets.begin(),
    this->pointTriangles.offsets.end() - 1);
  for (std::int64_t f = 0; f < nt; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const auto p = static_cast<size_t>(this->triangles[3 * f + c]);
      // A triangle with a repeated id is listed once per point.
      if (cursor[p] > this->pointTriangles.offsets[p] &&
        this->pointTriangles.items[static_cast<size_t>(cursor[p] - 1)] == f)
      {
        continue;
      }
      this->pointTriangles.items[static_cast<size_t>(cursor[p]++)] = f;
    }
  }
  // Shrink lists that held repeated ids: recount from the cursors.
  for (std::int64_t p = 0; p < np; ++p)
  {
    counts[static_cast<size_t>(p)] = cursor[static_cast<size_t>(p)] - this->pointTriangles.Begin(p);
  }
  CompressedLists compact;
  SetOffsets(counts, compact);
  for (std::int64_t p = 0; p < np; ++p)
  {
    std::copy(this->pointTriangles.items.begin() + this->pointTriangles.Begin(p),
      this->pointTriangles.items.begin() + cursor[static_cast<size_t>(p)],
      compact.items.begin() + compact.Begin(p));
  }
  this->pointTriangles = std::move(compact);
}

/// One-ring neighbours and the number of unique edges, built per point from its triangles.
void TriangleMesh::BuildOneRing(int nthreads)
{
  const std::int64_t np = this->numberOfPoints;
  const std::int64_t nt = this->numberOfTriangles;
  std::vector<std::int64_t> counts(static_cast<size_t>(np), 0);
  std::vector<std::int64_t> edges(static_cast<size_t>(np), 0);
  auto collect = [this](std::int64_t p, std::vector<std::int64_t>& ring) {
    ring.clear();
    for (std::int64_t k = this->pointTriangles.Begin(p); k < this->pointTriangles.End(p); ++k)
    {
      const std::int64_t* t = this->Corners(this->pointTriangles.items[static_cast<size_t>(k)]);
      for (int c = 0; c < 3; ++c)
      {
        if (t[c] != p)
        {
          ring.push_back(t[c]);
        }
      }
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  };
#pragma omp parallel num_threads(nthreads)
  {
    std::vector<std::int64_t> ring;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      collect(p, ring);
      counts[static_cast<size_t>(p)] = static_cast<std::int64_t>(ring.size());
      edges[static_cast<size_t>(p)] =
        std::count_if(ring.begin(), ring.end(), [p](std::int64_t w) { return w > p; });
    }
  }
  SetOffsets(counts, this->oneRing);
#pragma omp parallel num_threads(nthreads)
  {
    std::vector<std::int64_t> ring;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      collect(p, ring);
      std::copy(ring.begin(), ring.end(), this->oneRing.items.begin() + this->oneRing.Begin(p));
    }
  }
  this->numberOfEdges = std::accumulate(edges.begin(), edges.end(), std::int64_t{ 0 });
}

/// Mean length of the triangles' edges, each triangle's three (see the header);
/// per-triangle sums added in order, so it does not depend on the thread count.
void TriangleMesh::ComputeMeanEdgeLength(int nthreads)
{
  const std::int64_t nt = this->numberOfTriangles;
  std::vector<double> perimeter(static_cast<size_t>(nt));
#pragma omp parallel for num_threads(nthreads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    perimeter[static_cast<size_t>(f)] = TrianglePerimeter(this->points.data(), this->Corners(f));
  }
  const double total = std::accumulate(perimeter.begin(), perimeter.end(), 0.0);
  this->meanEdgeLength = nt > 0 ? total / (3.0 * static_cast<double>(nt)) : 0.0;
}

/// Per-triangle area, degeneracy, normal, centroid and hat gradients:
/// grad(phi_c) = N x (edge opposite c, counter-clockwise) / (2A).
void TriangleMesh::ComputeGeometry(int nthreads)
{
  const std::int64_t nt = this->numberOfTriangles;
  this->area.assign(static_cast<size_t>(nt), 0.0);
  this->degenerate.assign(static_cast<size_t>(nt), 1);
  this->normal.assign(static_cast<size_t>(3 * nt), 0.0);
  this->centroid.assign(static_cast<size_t>(3 * nt), 0.0);
  this->hatGradient.assign(static_cast<size_t>(9 * nt), 0.0);
  const double minArea = DegenerateAreaFraction * this->meanEdgeLength * this->meanEdgeLength;
#pragma omp parallel for num_threads(nthreads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t* t = this->Corners(f);
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

/// Edge neighbours: the other triangle that has both end points, if it is the only one.
void TriangleMesh::BuildNeighbours(int nthreads)
{
  const std::int64_t nt = this->numberOfTriangles;
  this->neighbour.assign(static_cast<size_t>(3 * nt), -1);
#pragma omp parallel for num_threads(nthreads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    if (this->degenerate[f])
    {
      continue;
    }
    const std::int64_t* t = this->Corners(f);
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = t[e];
      const std::int64_t b = t[(e + 1) % 3];
      std::int64_t other = -1;
      int sharing = 0;
      for (std::int64_t k = this->pointTriangles.Begin(a); k < this->pointTriangles.End(a); ++k)
      {
        const std::int64_t g = this->pointTriangles.items[static_cast<size_t>(k)];
        const std::int64_t* s = this->Corners(g);
        if (g != f && (s[0] == b || s[1] == b || s[2] == b))
        {
          other = g;
          ++sharing;
        }
      }
      if (sharing == 1 && !this->degenerate[static_cast<size_t>(other)])
      {
        this->neighbour[3 * f + e] = other;
      }
    }
  }
}

Status TriangleMesh::Build(const TriangleMeshView& view, int threads)
{
  const int nthreads = ResolveThreadCount(threads);
  if (view.numberOfPoints < 0 || view.numberOfTriangles < 0 ||
    (view.numberOfPoints > 0 && !view.points) || (view.numberOfTriangles > 0 && !view.triangles))
  {
    return { "invalid mesh arrays" };
  }
  if (view.numberOfTriangles > std::numeric_limits<std::int64_t>::max() / 9)
  {
    return { "too many triangles" };
  }
  const std::int64_t np = view.numberOfPoints;
  const std::int64_t nt = view.numberOfTriangles;
  this->numberOfPoints = np;
  this->numberOfTriangles = nt;
  this->points.assign(view.points, view.points + 3 * np);
  this->triangles.assign(view.triangles, view.triangles + 3 * nt);

  bool idsValid = true;
  bool finite = true;
#pragma omp parallel for num_threads(nthreads) reduction(&& : idsValid) schedule(static)
  for (std::int64_t i = 0; i < 3 * nt; ++i)
  {
    idsValid = idsValid && this->triangles[i] >= 0 && this->triangles[i] < np;
  }
#pragma omp parallel for num_threads(nthreads) reduction(&& : finite) schedule(static)
  for (std::int64_t i = 0; i < 3 * np; ++i)
  {
    finite = finite && std::isfinite(this->points[i]);
  }
  if (!idsValid)
  {
    return { "a triangle refers to a point id outside [0, number of points)" };
  }
  if (!finite)
  {
    return { "a point coordinate is not finite (NaN or infinity)" };
  }

  // Connectivity first (it depends on the ids only), then geometry.
  this->BuildPointTriangles(nthreads);
  this->BuildOneRing(nthreads);
  this->ComputeMeanEdgeLength(nthreads);
  this->ComputeGeometry(nthreads);
  // Neighbours last: degenerate triangles join nothing.
  this->BuildNeighbours(nthreads);
  return {};
}

} // namespace shock
