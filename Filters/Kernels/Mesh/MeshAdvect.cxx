#include "MeshAdvect.h"

#include "ParallelItems.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shock
{

namespace
{
// Offset of a vertex-advection start towards the adjacent face centre (the paper's epsilon).
constexpr double VertexOffset = 0.001;

// Traces ahead whose first triangles are prefetched (SurfaceTracer::Prefetch).
constexpr std::int64_t PrefetchDistance = 4;

bool SampleNearest(const TriangleMesh& mesh, const SurfacePoint& q, const MeshSource& source,
  double* acc)
{
  const int C = source.components;
  const std::int64_t* t = mesh.Corners(q.triangle);
  if (source.cells)
  {
    if (!AllFinite(source.cells + q.triangle * C, C))
    {
      return false;
    }
    for (int c = 0; c < C; ++c)
    {
      acc[c] += source.cells[q.triangle * C + c];
    }
    return true;
  }
  Vec3 x{ 0.0, 0.0, 0.0 };
  for (int k = 0; k < 3; ++k)
  {
    x = Combine(1.0, x, q.barycentric[k], Load(mesh.Point(t[k])));
  }
  int nearest = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    const Vec3 d = Combine(1.0, x, -1.0, Load(mesh.Point(t[k])));
    if (source.validPoint[static_cast<size_t>(t[k])] && Dot(d, d) < best)
    {
      best = Dot(d, d);
      nearest = k;
    }
  }
  if (nearest < 0)
  {
    return false;
  }
  for (int c = 0; c < C; ++c)
  {
    acc[c] += source.points[t[nearest] * C + c];
  }
  return true;
}
} // namespace

bool AllFinite(const double* v, int C)
{
  for (int c = 0; c < C; ++c)
  {
    if (!std::isfinite(v[c]))
    {
      return false;
    }
  }
  return true;
}

bool SampleSurface(const TriangleMesh& mesh, const SurfacePoint& q, Sampling sampling,
  const MeshSource& source, double* acc)
{
  if (sampling == Sampling::Nearest)
  {
    return SampleNearest(mesh, q, source, acc);
  }
  const int C = source.components;
  const std::int64_t* t = mesh.Corners(q.triangle);
  bool valid[3];
  double total = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    valid[k] = source.validPoint[static_cast<size_t>(t[k])] != 0;
    total += valid[k] ? q.barycentric[k] : 0.0;
  }
  if (!(total > 0.0))
  {
    return false;
  }
  // The corners' weights, the same for every channel (computed once), and
  // where each corner's value is read: its point's, or the triangle's own.
  double weight[3];
  const double* from[3];
  // The triangle's own value is checked only when one of its corners asks for it.
  const unsigned char* ownCorner = source.cells ? source.ownCorner : nullptr;
  const bool anyOwn = ownCorner &&
    (ownCorner[static_cast<size_t>(t[0])] || ownCorner[static_cast<size_t>(t[1])] ||
      ownCorner[static_cast<size_t>(t[2])]);
  const double* own = anyOwn ? source.cells + q.triangle * C : nullptr;
  const bool ownValid = own && AllFinite(own, C);
  for (int k = 0; k < 3; ++k)
  {
    weight[k] = q.barycentric[k] / total;
    from[k] = ownValid && ownCorner[static_cast<size_t>(t[k])] ? own : source.points + t[k] * C;
  }
  for (int c = 0; c < C; ++c)
  {
    // A convex combination: clamp away rounding so outputs never leave the corners' range.
    double value = 0.0;
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (int k = 0; k < 3; ++k)
    {
      if (valid[k])
      {
        const double v = from[k][c];
        value += weight[k] * v;
        low = std::min(low, v);
        high = std::max(high, v);
      }
    }
    acc[c] += std::clamp(value, low, high);
  }
  return true;
}

SurfacePoint VertexStart(const TriangleMesh& mesh, std::int64_t p, std::int64_t f)
{
  SurfacePoint q;
  q.triangle = f;
  const std::int64_t* t = mesh.Corners(f);
  for (int k = 0; k < 3; ++k)
  {
    q.barycentric[k] = VertexOffset / 3.0 + (t[k] == p ? 1.0 - VertexOffset : 0.0);
  }
  return q;
}

SurfacePoint FaceStart(std::int64_t f)
{
  SurfacePoint q;
  q.triangle = f;
  return q;
}

template <typename Body>
bool AdvectionPass::ForEach(std::int64_t n, Body&& body)
{
  ParallelItems items(n, 256, this->progress, this->progressStart, this->progressSpan);
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;
  int deepest = this->report.deepestRing;
#pragma omp parallel num_threads(this->threads) reduction(+ : steps, truncated) reduction(max : deepest)
  for (std::int64_t begin, end; items.Next(begin, end); items.Done(begin, end))
  {
    for (std::int64_t i = begin; i < end; ++i)
    {
      body(i, steps, truncated, deepest);
    }
  }
  this->report.traceSteps += steps;
  this->report.truncatedTraces += truncated;
  this->report.deepestRing = deepest;
  return items.Finish();
}

std::uint64_t AdvectionPass::Trace(SurfacePoint& q, std::uint64_t& truncated, RingReach* reach) const
{
  bool cut = false;
  const std::int64_t steps = this->tracer.Trace(q, this->time, cut, reach);
  truncated += cut ? 1 : 0;
  return static_cast<std::uint64_t>(steps);
}

bool AdvectFaces(
  AdvectionPass& pass, const MeshSource& source, double* out, std::vector<SurfacePoint>* positions)
{
  const int C = source.components;
  const TriangleMesh& mesh = pass.mesh;
  const std::int64_t nt = mesh.NumberOfTriangles();
  return pass.ForEach(nt,
    [&](std::int64_t f, std::uint64_t& steps, std::uint64_t& cut, int& deepest) {
      if (f + PrefetchDistance < nt)
      {
        pass.tracer.PrefetchAcross(f + PrefetchDistance); // its own data streams in order
      }
      double* acc = out + f * C;
      const double* own = source.cells + f * C;
      if (mesh.Degenerate(f) || !AllFinite(own, C))
      {
        std::copy(own, own + C, acc);
        return;
      }
      SurfacePoint local = FaceStart(f);
      SurfacePoint& q = positions ? (*positions)[static_cast<size_t>(f)] : local;
      RingReach reach{ pass.triangleRing };
      const bool watched = pass.triangleRing && pass.triangleRing[f] == 0; // an own triangle of a piece
      steps += pass.Trace(q, cut, watched ? &reach : nullptr);
      deepest = std::max(deepest, reach.deepest);
      for (int c = 0; c < C; ++c)
      {
        acc[c] = 0.0;
      }
      if (!SampleSurface(mesh, q, pass.sampling, source, acc))
      {
        std::copy(own, own + C, acc);
      }
    });
}

bool AdvectVertices(
  AdvectionPass& pass, const MeshSource& source, double* out, std::vector<SurfacePoint>* positions)
{
  const int C = source.components;
  const TriangleMesh& mesh = pass.mesh;
  const CompressedLists& around = mesh.PointTriangles();
  const std::int64_t np = mesh.NumberOfPoints();
  return pass.ForEach(np, [&](std::int64_t p, std::uint64_t& steps, std::uint64_t& cut, int& deepest) {
    if (p + PrefetchDistance < np)
    {
      for (std::int64_t k = around.Begin(p + PrefetchDistance); k < around.End(p + PrefetchDistance); ++k)
      {
        pass.tracer.Prefetch(around.items[static_cast<size_t>(k)]);
      }
    }
    double* acc = out + p * C;
    const double* own = source.points + p * C;
    for (int c = 0; c < C; ++c)
    {
      acc[c] = 0.0; // a loop: std::fill of C values (C known at run time) would call memset
    }
    int samples = 0;
    // A point of a piece's own triangle (MeshSignal::triangleRing): its traces' rings are recorded.
    RingReach reach{ pass.triangleRing };
    bool watched = false;
    for (std::int64_t k = around.Begin(p); pass.triangleRing && k < around.End(p) && !watched; ++k)
    {
      watched = pass.triangleRing[around.items[static_cast<size_t>(k)]] == 0;
    }
    if (source.validPoint[static_cast<size_t>(p)])
    {
      for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
      {
        const std::int64_t f = around.items[static_cast<size_t>(k)];
        if (mesh.Degenerate(f))
        {
          continue;
        }
        SurfacePoint local = VertexStart(mesh, p, f);
        SurfacePoint& q = positions ? (*positions)[static_cast<size_t>(k)] : local;
        steps += pass.Trace(q, cut, watched ? &reach : nullptr);
        if (!SampleSurface(mesh, q, pass.sampling, source, acc))
        {
          for (int c = 0; c < C; ++c)
          {
            acc[c] += own[c]; // only non-finite values around q: keep the point's own value
          }
        }
        ++samples;
      }
    }
    deepest = std::max(deepest, reach.deepest);
    if (samples == 0)
    {
      std::copy(own, own + C, acc); // invalid, isolated or only on degenerate triangles
      return;
    }
    for (int c = 0; c < C; ++c)
    {
      acc[c] /= samples;
    }
  });
}

std::vector<SurfacePoint> InitialPositions(const TriangleMesh& mesh, bool cells)
{
  if (cells)
  {
    std::vector<SurfacePoint> positions(static_cast<size_t>(mesh.NumberOfTriangles()));
    for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
    {
      positions[static_cast<size_t>(f)] = FaceStart(f);
    }
    return positions;
  }
  const CompressedLists& around = mesh.PointTriangles();
  std::vector<SurfacePoint> positions(around.items.size());
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
    {
      positions[static_cast<size_t>(k)] = VertexStart(mesh, p, around.items[static_cast<size_t>(k)]);
    }
  }
  return positions;
}

} // namespace shock
