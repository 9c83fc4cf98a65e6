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

/// One-ring of each point, sorted once, from its triangles' corners (at most
/// two per triangle), and the number of unique edges.
void MeshConnectivity::BuildOneRing(int threads)
{
  const std::int64_t np = this->numberOfPoints;
  const CompressedLists& around = this->pointTriangles;
  std::vector<std::int64_t> counts(static_cast<size_t>(np));
  for (std::int64_t p = 0; p < np; ++p)
  {
    counts[static_cast<size_t>(p)] = 2 * (around.End(p) - around.Begin(p));
  }
  CompressedLists bound;
  SetOffsets(counts, bound);
  std::int64_t edges = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : edges)
  for (std::int64_t p = 0; p < np; ++p)
  {
    std::int64_t* ring = bound.items.data() + bound.Begin(p);
    std::int64_t size = 0;
    for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
    {
      const std::int64_t* t = this->Corners(around.items[static_cast<size_t>(k)]);
      for (int c = 0; c < 3; ++c)
      {
        if (t[c] != p && size < counts[static_cast<size_t>(p)])
        {
          ring[size++] = t[c];
        }
      }
    }
    size = SortUnique(ring, ring + size);
    counts[static_cast<size_t>(p)] = size;
    edges += std::count_if(ring, ring + size, [p](std::int64_t w) { return w > p; });
  }
  this->oneRing = Compact(bound, counts, threads);
  this->numberOfEdges = edges;
}

/// Edge neighbours: the other triangle that has both end points, if it is the only one.
void MeshConnectivity::BuildNeighbours(int threads)
{
  const std::int64_t nt = this->NumberOfTriangles();
  this->neighbour.resize(static_cast<size_t>(3 * nt));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
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
      this->neighbour[static_cast<size_t>(3 * f + e)] = sharing == 1 ? other : -1;
    }
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
  this->BuildOneRing(team);
  this->BuildNeighbours(team);
  return {};
}

} // namespace shock
