/**
 * @file MeshConnectivitySplit.cxx
 * @brief MeshConnectivity::BuildSplit: the connectivity of a mesh whose points
 * were split (copies of points at feature edges) read from the unsplit mesh's,
 * in its named steps.
 */
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
  // The one-rings wait until asked for (CollectPendingOneRings).
  this->oneRing = CompressedLists();
  this->numberOfEdges = 0;
  this->pendingRings.reset(new std::once_flag);
  this->ringThreads = team;
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
 * The one-rings of a split mesh, collected on first use from the triangles
 * around each point (what Build gives: the points joined by an edge, each
 * once, in increasing order), and the number of edges. Sizes first, then the
 * lists into their places; once, whatever the threads that ask.
 */
void MeshConnectivity::CollectPendingOneRings() const
{
  if (!this->pendingRings)
  {
    return; // built with the rest (Build)
  }
  std::call_once(*this->pendingRings, [this]() {
    const std::int64_t np = this->numberOfPoints;
    CompressedLists& ring = this->oneRing;
    ring.offsets.assign(static_cast<size_t>(np) + 1, 0);
#pragma omp parallel num_threads(this->ringThreads)
    {
      std::vector<std::int64_t> scratch;
#pragma omp for schedule(static)
      for (std::int64_t q = 0; q < np; ++q)
      {
        CollectOneRing(*this, q, scratch);
        ring.offsets[static_cast<size_t>(q) + 1] = static_cast<std::int64_t>(scratch.size());
      }
    }
    std::partial_sum(ring.offsets.begin(), ring.offsets.end(), ring.offsets.begin());
    ring.items.resize(static_cast<size_t>(ring.offsets.back()));
    std::int64_t edges = 0;
#pragma omp parallel num_threads(this->ringThreads) reduction(+ : edges)
    {
      std::vector<std::int64_t> scratch;
#pragma omp for schedule(static)
      for (std::int64_t q = 0; q < np; ++q)
      {
        CollectOneRing(*this, q, scratch);
        std::copy(scratch.begin(), scratch.end(), ring.items.begin() + ring.Begin(q));
        for (std::int64_t r : scratch)
        {
          edges += r > q ? 1 : 0;
        }
      }
    }
    this->numberOfEdges = edges;
  });
}

} // namespace shock
