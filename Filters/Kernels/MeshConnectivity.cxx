#include "MeshConnectivity.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace shock
{

namespace
{
/// Offsets from per-entry counts (a prefix sum); items sized to the total.
void SetOffsets(const std::vector<std::int64_t>& counts, CompressedLists& lists)
{
  lists.offsets.resize(counts.size() + 1);
  lists.offsets[0] = 0;
  std::partial_sum(counts.begin(), counts.end(), lists.offsets.begin() + 1);
  lists.items.resize(static_cast<size_t>(lists.offsets.back()));
}

/// The first counts[i] items of each list of `lists` (whose lists may be longer).
CompressedLists Compact(
  const CompressedLists& lists, const std::vector<std::int64_t>& counts, int threads)
{
  CompressedLists compact;
  SetOffsets(counts, compact);
  const auto n = static_cast<std::int64_t>(counts.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
  {
    std::copy(lists.items.begin() + lists.Begin(i), lists.items.begin() + lists.Begin(i) + counts[i],
      compact.items.begin() + compact.Begin(i));
  }
  return compact;
}

/// Sort the range and drop repeated items; returns the new length.
std::int64_t SortUnique(std::int64_t* begin, std::int64_t* end)
{
  std::sort(begin, end);
  return std::unique(begin, end) - begin;
}
} // namespace

/// Triangles around each point: counted and placed in parallel (atomics), then
/// each list sorted, so it is in triangle order whatever the threads did.
void MeshConnectivity::BuildPointTriangles(int threads)
{
  const std::int64_t np = this->numberOfPoints;
  const auto corners = static_cast<std::int64_t>(this->triangles.size());
  const std::int64_t* ids = this->triangles.data();
  std::vector<std::int64_t> counts(static_cast<size_t>(np), 0);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < corners; ++i)
  {
#pragma omp atomic
    ++counts[static_cast<size_t>(ids[i])];
  }
  CompressedLists lists;
  SetOffsets(counts, lists);
  std::vector<std::int64_t> cursor(lists.offsets.begin(), lists.offsets.end() - 1);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < corners; ++i)
  {
    std::int64_t slot;
#pragma omp atomic capture
    slot = cursor[static_cast<size_t>(ids[i])]++;
    lists.items[static_cast<size_t>(slot)] = i / 3;
  }
  // Sorted; a triangle with a repeated id is listed once per point.
  bool repeated = false;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(|| : repeated)
  for (std::int64_t p = 0; p < np; ++p)
  {
    std::int64_t* items = lists.items.data();
    const std::int64_t kept = SortUnique(items + lists.Begin(p), items + lists.End(p));
    repeated = repeated || kept != counts[static_cast<size_t>(p)];
    counts[static_cast<size_t>(p)] = kept;
  }
  this->pointTriangles = repeated ? Compact(lists, counts, threads) : std::move(lists);
}

/// An edge of a triangle around a point: its other end, the triangle, the edge's index in it.
struct MeshConnectivity::EdgeEnd
{
  std::int64_t other;
  std::int64_t triangle;
  int edge;
  bool operator<(const EdgeEnd& e) const
  {
    return this->other != e.other ? this->other < e.other : this->triangle < e.triangle;
  }
};

/**
 * One pass over the points: the edges of the triangles around p, sorted by their
 * other end, give p's one-ring (the distinct other ends) and, for the edges
 * whose other end is larger (each edge is seen once there), the edge
 * neighbours: the triangles that have both ends join when they are exactly two.
 */
void MeshConnectivity::BuildOneRingAndNeighbours(int threads)
{
  const std::int64_t np = this->numberOfPoints;
  const CompressedLists& around = this->pointTriangles;
  std::vector<std::int64_t> counts(static_cast<size_t>(np));
  for (std::int64_t p = 0; p < np; ++p)
  {
    counts[static_cast<size_t>(p)] = 2 * (around.End(p) - around.Begin(p)); // an upper bound
  }
  CompressedLists bound;
  SetOffsets(counts, bound);
  this->neighbour.resize(this->triangles.size());
  std::int64_t edges = 0;
#pragma omp parallel num_threads(threads) reduction(+ : edges)
  {
    std::vector<EdgeEnd> ends;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      this->CollectEdgeEnds(p, ends);
      std::int64_t* ring = bound.items.data() + bound.Begin(p);
      std::int64_t size = 0;
      for (size_t i = 0; i < ends.size();)
      {
        size_t j = i + 1; // [i, j): the edges from p to ends[i].other
        std::int64_t sharing = 1;
        for (; j < ends.size() && ends[j].other == ends[i].other; ++j)
        {
          sharing += ends[j].triangle != ends[j - 1].triangle ? 1 : 0;
        }
        if (ends[i].other != p)
        {
          ring[size++] = ends[i].other;
        }
        if (ends[i].other >= p) // an edge from p to p (a repeated id) joins nothing
        {
          edges += ends[i].other > p ? 1 : 0;
          this->JoinAcross(ends.data() + i, ends.data() + j, ends[i].other > p && sharing == 2);
        }
        i = j;
      }
      counts[static_cast<size_t>(p)] = size;
    }
  }
  this->oneRing = Compact(bound, counts, threads);
  this->numberOfEdges = edges;
}

void MeshConnectivity::CollectEdgeEnds(std::int64_t p, std::vector<EdgeEnd>& ends) const
{
  ends.clear();
  for (std::int64_t k = this->pointTriangles.Begin(p); k < this->pointTriangles.End(p); ++k)
  {
    const std::int64_t f = this->pointTriangles.items[static_cast<size_t>(k)];
    const std::int64_t* t = this->Corners(f);
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = t[e];
      const std::int64_t b = t[(e + 1) % 3];
      if (a == p || b == p)
      {
        ends.push_back({ a == p ? b : a, f, e });
      }
    }
  }
  std::sort(ends.begin(), ends.end());
}

void MeshConnectivity::JoinAcross(const EdgeEnd* begin, const EdgeEnd* end, bool join)
{
  const std::int64_t first = begin->triangle;
  const std::int64_t last = (end - 1)->triangle;
  for (const EdgeEnd* e = begin; e != end; ++e)
  {
    this->neighbour[static_cast<size_t>(3 * e->triangle + e->edge)] =
      join ? (e->triangle == first ? last : first) : -1;
  }
}

Status MeshConnectivity::Build(
  std::int64_t numberOfPoints, std::vector<std::int64_t> ids, int threads)
{
  if (numberOfPoints < 0 || ids.size() % 3 != 0)
  {
    return { "invalid mesh arrays" };
  }
  if (ids.size() / 3 > static_cast<size_t>(std::numeric_limits<std::int64_t>::max() / 9))
  {
    return { "too many triangles" };
  }
  const auto corners = static_cast<std::int64_t>(ids.size());
  const int team = ThreadsForWork(threads, corners);
  bool valid = true;
#pragma omp parallel for num_threads(team) reduction(&& : valid) schedule(static)
  for (std::int64_t i = 0; i < corners; ++i)
  {
    valid = valid && ids[static_cast<size_t>(i)] >= 0 && ids[static_cast<size_t>(i)] < numberOfPoints;
  }
  if (!valid)
  {
    return { "a triangle refers to a point id outside [0, number of points)" };
  }
  this->numberOfPoints = numberOfPoints;
  this->triangles = std::move(ids);
  this->BuildPointTriangles(team);
  this->BuildOneRingAndNeighbours(team);
  return {};
}

} // namespace shock
