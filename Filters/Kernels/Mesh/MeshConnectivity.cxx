#include "MeshConnectivity.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace shock
{

namespace
{
/**
 * Contiguous ranges that split [0, n) into `parts` pieces (as even as possible):
 * piece i is [PartBegin(n, parts, i), PartBegin(n, parts, i + 1)).
 */
std::int64_t PartBegin(std::int64_t n, int parts, int i)
{
  return n / parts * i + std::min<std::int64_t>(i, n % parts);
}

/// Whether corner c of a triangle repeats one of its earlier corners (then it is not listed again).
bool RepeatsEarlierCorner(const std::int64_t* t, int c)
{
  return (c >= 1 && t[c] == t[0]) || (c == 2 && t[2] == t[1]);
}
} // namespace

/**
 * Triangles around each point, by a counting sort over contiguous chunks of the
 * triangles: each chunk counts its corners per point, the counts give every
 * chunk its own slots in every point's list, and each chunk fills its slots in
 * triangle order. The lists are then in increasing order whatever the chunks,
 * and a triangle with a repeated id is listed once per point.
 */
void MeshConnectivity::BuildPointTriangles(int threads)
{
  const std::int64_t np = this->numberOfPoints;
  const std::int64_t nt = this->NumberOfTriangles();
  const std::int64_t* ids = this->triangles.data();
  // Per-chunk counts fit 32 bits: a chunk holds fewer than 2^31 / 3 triangles.
  const std::int64_t maxChunk = std::numeric_limits<std::int32_t>::max() / 3;
  const int chunks = static_cast<int>(std::max<std::int64_t>(
    std::max(1, threads), (nt + maxChunk - 1) / maxChunk));
  std::vector<std::int32_t, UninitialisedAllocator<std::int32_t>> counts(
    static_cast<size_t>(chunks) * static_cast<size_t>(np)); // each chunk zeroes its counts
  CompressedLists& lists = this->pointTriangles;
  lists.offsets.resize(static_cast<size_t>(np) + 1);
#pragma omp parallel num_threads(threads)
  {
#pragma omp for schedule(static)
    for (int chunk = 0; chunk < chunks; ++chunk)
    {
      std::int32_t* count = counts.data() + static_cast<size_t>(chunk) * static_cast<size_t>(np);
      std::fill(count, count + np, 0);
      for (std::int64_t f = PartBegin(nt, chunks, chunk); f < PartBegin(nt, chunks, chunk + 1); ++f)
      {
        const std::int64_t* t = ids + 3 * f;
        for (int c = 0; c < 3; ++c)
        {
          count[t[c]] += RepeatsEarlierCorner(t, c) ? 0 : 1;
        }
      }
    }
    // Per point: the total (into offsets, shifted by one), and each chunk's first slot
    // relative to the point's list.
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      std::int64_t total = 0;
      for (int chunk = 0; chunk < chunks; ++chunk)
      {
        std::int32_t& count = counts[static_cast<size_t>(chunk) * static_cast<size_t>(np) + static_cast<size_t>(p)];
        const std::int64_t mine = count;
        count = static_cast<std::int32_t>(total); // below 2^31: a point's triangles are distinct
        total += mine;
      }
      lists.offsets[static_cast<size_t>(p) + 1] = total;
    }
#pragma omp single
    {
      lists.offsets[0] = 0;
      std::partial_sum(lists.offsets.begin(), lists.offsets.end(), lists.offsets.begin());
      lists.items.resize(static_cast<size_t>(lists.offsets.back()));
    }
#pragma omp for schedule(static)
    for (int chunk = 0; chunk < chunks; ++chunk)
    {
      std::int32_t* slot = counts.data() + static_cast<size_t>(chunk) * static_cast<size_t>(np);
      for (std::int64_t f = PartBegin(nt, chunks, chunk); f < PartBegin(nt, chunks, chunk + 1); ++f)
      {
        const std::int64_t* t = ids + 3 * f;
        for (int c = 0; c < 3; ++c)
        {
          if (!RepeatsEarlierCorner(t, c))
          {
            lists.items[static_cast<size_t>(lists.offsets[static_cast<size_t>(t[c])] + slot[t[c]]++)] = f;
          }
        }
      }
    }
  }
}

namespace
{
/// Prefetch the corners of the triangles around point p (their loads, scattered over the
/// triangle array, dominate the pass).
SHOCK_ALWAYS_INLINE void PrefetchCorners(
  const std::int64_t* corners, const std::int64_t* items, const std::int64_t* offsets, std::int64_t p)
{
  for (std::int64_t k = offsets[p]; k < offsets[p + 1]; ++k)
  {
    __builtin_prefetch(corners + 3 * items[k]);
  }
}

/**
 * The edges of the triangles around p that end at p: their other ends, and
 * 4 x triangle + edge index (two arrays of single words: a 16-byte load of a
 * just stored pair would not be forwarded from the store buffer).
 */
SHOCK_ALWAYS_INLINE void EdgesEndingAt(const std::int64_t* corners, const std::int64_t* items,
  const std::int64_t* offsets, std::int64_t p, std::vector<std::int64_t>& other,
  std::vector<std::int64_t>& slot)
{
  other.clear();
  slot.clear();
  for (std::int64_t k = offsets[p]; k < offsets[p + 1]; ++k)
  {
    const std::int64_t f = items[k];
    const std::int64_t* t = corners + 3 * f;
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = t[e];
      const std::int64_t b = t[e == 2 ? 0 : e + 1];
      if (a == p || b == p)
      {
        other.push_back(a == p ? b : a);
        slot.push_back(4 * f + e);
      }
    }
  }
}

/// Insertion sort of the edges by (other end, slot): a few edges per point.
SHOCK_ALWAYS_INLINE void SortByOtherEnd(std::vector<std::int64_t>& other, std::vector<std::int64_t>& slot)
{
  const size_t n = other.size();
  for (size_t i = 1; i < n; ++i)
  {
    const std::int64_t o = other[i];
    const std::int64_t s = slot[i];
    size_t j = i;
    for (; j > 0 && (o < other[j - 1] || (o == other[j - 1] && s < slot[j - 1])); --j)
    {
      other[j] = other[j - 1];
      slot[j] = slot[j - 1];
    }
    other[j] = o;
    slot[j] = s;
  }
}

/**
 * The sorted edges at p, in runs of one other end q: each q but p itself joins
 * p's one-ring (appended to `ring`; returns how many). An edge to a larger q
 * is seen here first: it counts in `edges`, and its triangles are joined
 * across it when they are exactly two (else -1 in `neighbours`).
 */
SHOCK_ALWAYS_INLINE std::int64_t RingAndNeighboursAt(std::int64_t p,
  const std::vector<std::int64_t>& other, const std::vector<std::int64_t>& slot,
  std::vector<std::int64_t>& ring, std::int64_t* neighbours, std::int64_t& edges)
{
  const size_t n = other.size();
  std::int64_t count = 0;
  for (size_t i = 0; i < n;)
  {
    const std::int64_t q = other[i];
    size_t j = i + 1; // [i, j): the edges from p to q
    std::int64_t sharing = 1;
    for (; j < n && other[j] == q; ++j)
    {
      sharing += (slot[j] >> 2) != (slot[j - 1] >> 2) ? 1 : 0;
    }
    if (q != p)
    {
      ring.push_back(q);
      ++count;
    }
    if (q >= p) // an edge from p to p (a repeated id) joins nothing
    {
      edges += q > p ? 1 : 0;
      const bool join = q > p && sharing == 2;
      const std::int64_t low = slot[i] >> 2;
      const std::int64_t high = slot[j - 1] >> 2;
      for (size_t k = i; k < j; ++k)
      {
        const std::int64_t f = slot[k] >> 2;
        neighbours[3 * f + (slot[k] & 3)] = join ? (f == low ? high : low) : -1;
      }
    }
    i = j;
  }
  return count;
}
} // namespace

/**
 * One pass over the points, each thread over a contiguous range: the edges of
 * the triangles around p that end at p, sorted by their other end (then
 * triangle), give p's one-ring (the distinct other ends, collected per thread
 * and then copied to their place) and, for the edges whose other end is larger
 * (each edge is seen once there), the edge neighbours: the triangles that have
 * both ends join when they are exactly two. The corners of the triangles a few
 * points ahead are prefetched.
 */
void MeshConnectivity::BuildOneRingAndNeighbours(int threads)
{
  const std::int64_t np = this->numberOfPoints;
  const CompressedLists& around = this->pointTriangles;
  CompressedLists& ring = this->oneRing;
  ring.offsets.resize(static_cast<size_t>(np) + 1);
  ring.offsets[0] = 0;
  this->neighbour.resize(this->triangles.size());
  const int team = std::max(1, threads);
  std::vector<std::vector<std::int64_t>> local(static_cast<size_t>(team));
  const std::int64_t* corners = this->triangles.data();
  const std::int64_t* items = around.items.data();
  const std::int64_t* offsets = around.offsets.data();
  std::int64_t* neighbours = this->neighbour.data();
  std::int64_t edges = 0;
#pragma omp parallel num_threads(team) reduction(+ : edges)
  {
#ifdef _OPENMP
    const int me = omp_get_thread_num();
    const int size = omp_get_num_threads();
#else
    const int me = 0;
    const int size = 1;
#endif
    std::vector<std::int64_t>& mine = local[static_cast<size_t>(me)];
    const std::int64_t first = PartBegin(np, size, me);
    const std::int64_t last = PartBegin(np, size, me + 1);
    mine.reserve(static_cast<size_t>(2 * (offsets[last] - offsets[first])));
    std::int64_t* sizes = ring.offsets.data() + 1;
    std::vector<std::int64_t> other; // the edges at p (EdgesEndingAt)
    std::vector<std::int64_t> slot;
    constexpr std::int64_t Ahead = 4;
    for (std::int64_t p = first; p < last; ++p)
    {
      if (p + Ahead < last)
      {
        PrefetchCorners(corners, items, offsets, p + Ahead);
      }
      EdgesEndingAt(corners, items, offsets, p, other, slot);
      SortByOtherEnd(other, slot);
      sizes[p] = RingAndNeighboursAt(p, other, slot, mine, neighbours, edges);
    }
#pragma omp barrier
#pragma omp single
    {
      std::partial_sum(ring.offsets.begin(), ring.offsets.end(), ring.offsets.begin());
      ring.items.resize(static_cast<size_t>(ring.offsets.back()));
    }
    if (first < last)
    {
      std::copy(mine.begin(), mine.end(), ring.items.begin() + ring.offsets[static_cast<size_t>(first)]);
    }
    std::vector<std::int64_t>().swap(mine);
  }
  this->numberOfEdges = edges;
}

Status MeshConnectivity::Build(
  std::int64_t numberOfPoints, IdVector ids, int threads)
{
  this->derived = false;
  this->pendingRings.reset(); // the one-rings are built below
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
