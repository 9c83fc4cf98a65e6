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

namespace
{
/// Whether the sorted lists [i, iEnd) and [j, jEnd) share exactly two items; `other` gets the one that is not f.
bool ExactlyTwoShared(const std::int64_t* i, const std::int64_t* iEnd, const std::int64_t* j,
  const std::int64_t* jEnd, std::int64_t f, std::int64_t& other)
{
  int sharing = 0;
  other = -1;
  while (i != iEnd && j != jEnd && sharing <= 2)
  {
    if (*i < *j)
    {
      ++i;
    }
    else if (*j < *i)
    {
      ++j;
    }
    else
    {
      ++sharing;
      other = *i != f ? *i : other;
      ++i;
      ++j;
    }
  }
  return sharing == 2;
}

/// Whether triangle t has corner p.
bool HasCorner(const std::int64_t* t, std::int64_t p)
{
  return t[0] == p || t[1] == p || t[2] == p;
}
} // namespace

/**
 * The check of BuildSplit: whether `ids` and `original` split `source`'s
 * points into copies. The copies are in order (steps of 0 or 1 from 0 to
 * np - 1), each corner is a copy of the source's, and equal corners of a
 * triangle are the same copy (the lists count a triangle once per point).
 */
bool MeshConnectivity::IsSplitOf(const MeshConnectivity& source,
  const std::vector<std::int64_t>& original, const IdVector& ids, int team)
{
  const std::int64_t np = source.numberOfPoints;
  const auto copies = static_cast<std::int64_t>(original.size());
  const auto corners = static_cast<std::int64_t>(ids.size());
  bool split = ids.size() == source.triangles.size() && copies >= np &&
    (copies == 0 || (original.front() == 0 && original.back() == np - 1));
#pragma omp parallel for num_threads(team) reduction(&& : split) schedule(static)
  for (std::int64_t q = 1; q < copies; ++q)
  {
    const std::int64_t step = original[static_cast<size_t>(q)] - original[static_cast<size_t>(q) - 1];
    split = split && (step == 0 || step == 1);
  }
#pragma omp parallel for num_threads(team) reduction(&& : split) schedule(static)
  for (std::int64_t i = 0; i < (split ? corners : 0); ++i)
  {
    const std::int64_t q = ids[static_cast<size_t>(i)];
    split = split && q >= 0 && q < copies && original[static_cast<size_t>(q)] == source.triangles[static_cast<size_t>(i)];
  }
#pragma omp parallel for num_threads(team) reduction(&& : split) schedule(static)
  for (std::int64_t f = 0; f < (split ? corners / 3 : 0); ++f)
  {
    const std::int64_t* t = source.triangles.data() + 3 * f;
    const std::int64_t* u = ids.data() + 3 * f;
    for (int c = 0; c < 3; ++c)
    {
      const int d = (c + 1) % 3;
      split = split && ((t[c] == t[d]) == (u[c] == u[d]));
    }
  }
  return split;
}

namespace
{
/// The first copy of each of the np points that `original` copies (np + 1 entries, the
/// last one the number of copies).
std::vector<std::int64_t> FirstCopies(
  const std::vector<std::int64_t>& original, std::int64_t np, int team)
{
  const auto copies = static_cast<std::int64_t>(original.size());
  std::vector<std::int64_t> firstCopy(static_cast<size_t>(np) + 1);
  firstCopy[static_cast<size_t>(np)] = copies;
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::int64_t q = 0; q < copies; ++q)
  {
    if (q == 0 || original[static_cast<size_t>(q)] != original[static_cast<size_t>(q) - 1])
    {
      firstCopy[static_cast<size_t>(original[static_cast<size_t>(q)])] = q;
    }
  }
  return firstCopy;
}

/// The one-ring of point q of `mesh` collected from its triangles (sorted, each point once).
void CollectOneRing(const MeshConnectivity& mesh, std::int64_t q, std::vector<std::int64_t>& ring)
{
  const CompressedLists& around = mesh.PointTriangles();
  ring.clear();
  for (std::int64_t k = around.Begin(q); k < around.End(q); ++k)
  {
    const std::int64_t* t = mesh.Corners(around.items[static_cast<size_t>(k)]);
    for (int c = 0; c < 3; ++c)
    {
      if (t[c] != q)
      {
        ring.push_back(t[c]);
      }
    }
  }
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
}
} // namespace

/// What the steps of BuildSplit share: the source, the copies of its points and the split's corners.
struct MeshConnectivity::SplitCopies
{
  const MeshConnectivity& source;
  const IdVector& triangles; ///< the split's corners
  const int team;
  /// Per source point p: its copies are [firstCopy[p], firstCopy[p + 1]).
  const std::vector<std::int64_t> firstCopy;

  SplitCopies(const MeshConnectivity& from, const std::vector<std::int64_t>& original,
    const IdVector& corners, int threads)
    : source(from)
    , triangles(corners)
    , team(threads)
    , firstCopy(FirstCopies(original, from.numberOfPoints, threads))
  {
  }
  std::int64_t CopiesOf(std::int64_t p) const
  {
    return this->firstCopy[static_cast<size_t>(p) + 1] - this->firstCopy[static_cast<size_t>(p)];
  }
  /// The copy of p that triangle f uses.
  std::int64_t CopyIn(std::int64_t f, std::int64_t p) const
  {
    const std::int64_t* t = this->source.Corners(f);
    return this->triangles[static_cast<size_t>(3 * f + (t[0] == p ? 0 : (t[1] == p ? 1 : 2)))];
  }
  /// Whether p's one-ring is the source's renumbered: p has one copy, and so has every point of its ring.
  bool KeepsOneRing(std::int64_t p) const
  {
    const CompressedLists& sourceRing = this->source.oneRing;
    if (this->CopiesOf(p) > 1)
    {
      return false;
    }
    for (std::int64_t k = sourceRing.Begin(p); k < sourceRing.End(p); ++k)
    {
      if (this->CopiesOf(sourceRing.items[static_cast<size_t>(k)]) > 1)
      {
        return false;
      }
    }
    return true;
  }
};

Status MeshConnectivity::BuildSplit(const MeshConnectivity& source,
  const std::vector<std::int64_t>& original, IdVector ids, int threads)
{
  const auto copies = static_cast<std::int64_t>(original.size());
  const auto corners = static_cast<std::int64_t>(ids.size());
  const int team = ThreadsForWork(threads, std::max(copies, corners));
  if (!IsSplitOf(source, original, ids, team))
  {
    this->derived = false;
    return this->Build(copies, std::move(ids), threads);
  }
  this->derived = true;
  this->numberOfPoints = copies;
  this->triangles = std::move(ids);
  const SplitCopies split(source, original, this->triangles, team);
  this->SplitPointTriangles(split);
  this->SplitNeighbours(split);
  // One-rings: the source's, renumbered, for a point with one copy and no split
  // point in its ring (renumbering keeps the order); else collected anew.
  CompressedLists& ring = this->oneRing;
  ring.offsets.assign(static_cast<size_t>(copies) + 1, 0);
  std::vector<unsigned char> same(static_cast<size_t>(source.numberOfPoints));
  this->CountSplitOneRings(split, same);
  std::partial_sum(ring.offsets.begin(), ring.offsets.end(), ring.offsets.begin());
  ring.items.resize(static_cast<size_t>(ring.offsets.back()));
  this->numberOfEdges = this->FillSplitOneRings(split, same);
  return {};
}

/// BuildSplit's triangles around each copy: its point's, those that use this copy (in order).
void MeshConnectivity::SplitPointTriangles(const SplitCopies& split)
{
  const std::int64_t np = split.source.numberOfPoints;
  const std::vector<std::int64_t>& firstCopy = split.firstCopy;
  const CompressedLists& around = split.source.pointTriangles;
  CompressedLists& lists = this->pointTriangles;
  lists.offsets.assign(static_cast<size_t>(this->numberOfPoints) + 1, 0);
#pragma omp parallel for num_threads(split.team) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    if (split.CopiesOf(p) == 1)
    {
      lists.offsets[static_cast<size_t>(firstCopy[static_cast<size_t>(p)]) + 1] = around.End(p) - around.Begin(p);
      continue;
    }
    for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
    {
      ++lists.offsets[static_cast<size_t>(split.CopyIn(around.items[static_cast<size_t>(k)], p)) + 1];
    }
  }
  std::partial_sum(lists.offsets.begin(), lists.offsets.end(), lists.offsets.begin());
  lists.items.resize(static_cast<size_t>(lists.offsets.back()));
#pragma omp parallel for num_threads(split.team) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    if (split.CopiesOf(p) == 1)
    {
      std::copy(around.items.begin() + around.Begin(p), around.items.begin() + around.End(p),
        lists.items.begin() + lists.Begin(firstCopy[static_cast<size_t>(p)]));
      continue;
    }
    std::vector<std::int64_t> cursor(static_cast<size_t>(split.CopiesOf(p)));
    for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
    {
      const std::int64_t f = around.items[static_cast<size_t>(k)];
      const std::int64_t q = split.CopyIn(f, p);
      const std::int64_t n = cursor[static_cast<size_t>(q - firstCopy[static_cast<size_t>(p)])]++;
      lists.items[static_cast<size_t>(lists.Begin(q) + n)] = f;
    }
  }
}

/**
 * BuildSplit's edge neighbours: those of the source between unsplit points;
 * across a split point, the source's neighbour if it still has both ends, else
 * (a non-manifold source edge) recomputed from the new lists.
 */
void MeshConnectivity::SplitNeighbours(const SplitCopies& split)
{
  const MeshConnectivity& source = split.source;
  const CompressedLists& lists = this->pointTriangles;
  const std::int64_t nt = this->NumberOfTriangles();
  this->neighbour.resize(this->triangles.size());
#pragma omp parallel for num_threads(split.team) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t* t = source.Corners(f);
    const std::int64_t* u = this->Corners(f);
    for (int e = 0; e < 3; ++e)
    {
      const int e1 = (e + 1) % 3;
      const std::int64_t g = source.Neighbour(f, e);
      std::int64_t joined = g;
      if (split.CopiesOf(t[e]) > 1 || split.CopiesOf(t[e1]) > 1)
      {
        if (g >= 0)
        {
          joined = HasCorner(this->Corners(g), u[e]) && HasCorner(this->Corners(g), u[e1]) ? g : -1;
        }
        else if (u[e] != u[e1])
        {
          const std::int64_t* items = lists.items.data();
          std::int64_t other = -1;
          joined = ExactlyTwoShared(items + lists.Begin(u[e]), items + lists.End(u[e]),
                     items + lists.Begin(u[e1]), items + lists.End(u[e1]), f, other)
            ? other
            : -1;
        }
      }
      this->neighbour[static_cast<size_t>(3 * f + e)] = joined;
    }
  }
}

/**
 * BuildSplit's one-ring sizes (into the offsets, shifted by one), and per
 * source point whether its ring is the source's renumbered (`same`).
 */
void MeshConnectivity::CountSplitOneRings(const SplitCopies& split, std::vector<unsigned char>& same)
{
  const std::int64_t np = split.source.numberOfPoints;
  const std::vector<std::int64_t>& firstCopy = split.firstCopy;
  const CompressedLists& sourceRing = split.source.oneRing;
  CompressedLists& ring = this->oneRing;
#pragma omp parallel num_threads(split.team)
  {
    std::vector<std::int64_t> scratch;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      same[static_cast<size_t>(p)] = split.KeepsOneRing(p) ? 1 : 0;
      if (same[static_cast<size_t>(p)])
      {
        ring.offsets[static_cast<size_t>(firstCopy[static_cast<size_t>(p)]) + 1] = sourceRing.End(p) - sourceRing.Begin(p);
        continue;
      }
      for (std::int64_t q = firstCopy[static_cast<size_t>(p)]; q < firstCopy[static_cast<size_t>(p) + 1]; ++q)
      {
        CollectOneRing(*this, q, scratch);
        ring.offsets[static_cast<size_t>(q) + 1] = static_cast<std::int64_t>(scratch.size());
      }
    }
  }
}

/// BuildSplit's one-rings into their places (CountSplitOneRings gave the offsets); returns
/// the number of edges.
std::int64_t MeshConnectivity::FillSplitOneRings(
  const SplitCopies& split, const std::vector<unsigned char>& same)
{
  const std::int64_t np = split.source.numberOfPoints;
  const std::vector<std::int64_t>& firstCopy = split.firstCopy;
  const CompressedLists& sourceRing = split.source.oneRing;
  CompressedLists& ring = this->oneRing;
  std::int64_t edges = 0;
#pragma omp parallel num_threads(split.team) reduction(+ : edges)
  {
    std::vector<std::int64_t> scratch;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      if (same[static_cast<size_t>(p)])
      {
        const std::int64_t q = firstCopy[static_cast<size_t>(p)];
        std::int64_t* out = ring.items.data() + ring.Begin(q);
        for (std::int64_t k = sourceRing.Begin(p); k < sourceRing.End(p); ++k)
        {
          const std::int64_t r = firstCopy[static_cast<size_t>(sourceRing.items[static_cast<size_t>(k)])];
          *out++ = r;
          edges += r > q ? 1 : 0;
        }
        continue;
      }
      for (std::int64_t q = firstCopy[static_cast<size_t>(p)]; q < firstCopy[static_cast<size_t>(p) + 1]; ++q)
      {
        CollectOneRing(*this, q, scratch);
        std::copy(scratch.begin(), scratch.end(), ring.items.begin() + ring.Begin(q));
        for (std::int64_t r : scratch)
        {
          edges += r > q ? 1 : 0;
        }
      }
    }
  }
  return edges;
}

Status MeshConnectivity::Build(
  std::int64_t numberOfPoints, IdVector ids, int threads)
{
  this->derived = false;
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
