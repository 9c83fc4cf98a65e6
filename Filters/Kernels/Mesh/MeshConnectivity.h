/**
 * @file MeshConnectivity.h
 * @brief The connectivity of a triangle mesh, built once from its point ids
 * alone (no coordinates): the triangles, the triangles around each point, the
 * one-ring of each point and the triangle across each edge.
 *
 * Geometry (areas, normals, gradients, the mean edge length) is computed from
 * the positions over it (MeshGeometry.h), so a mesh whose points move keeps its
 * connectivity (the split of geometry-central's SurfaceMesh and Geometry).
 *
 * Conventions:
 *  - An edge shared by exactly two triangles (by point ids) joins them; an edge
 *    with one triangle (boundary) or more (non-manifold) joins nothing.
 *    Duplicate points are distinct vertices: a seam of duplicates is a boundary.
 *  - A triangle with a repeated id is listed once around each of its points.
 *  - Points used by no triangle have no neighbours and no adjacent triangles.
 *
 * Every list is in increasing order, so nothing depends on the thread count.
 */
#ifndef MeshConnectivity_h
#define MeshConnectivity_h

#include "ShockTypes.h"

#include <cstdint>
#include <memory>
#include <mutex>
#include <type_traits>
#include <utility>
#include <vector>

namespace shock
{

/**
 * An allocator whose value-initialisation leaves plain values uninitialised, so
 * that resize() writes nothing: the parallel loops that fill a large array then
 * touch its pages first, each thread its own part, instead of one thread
 * zero-filling it all before.
 */
template <typename T>
struct UninitialisedAllocator : std::allocator<T>
{
  template <typename U>
  struct rebind
  {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <typename U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U; // default-initialised: nothing written for plain values
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A vector of ids whose resize() leaves the new ids unwritten (see UninitialisedAllocator).
using IdVector = std::vector<std::int64_t, UninitialisedAllocator<std::int64_t>>;

/// A vector of values whose resize() leaves the new values unwritten (see UninitialisedAllocator).
using ValueVector = std::vector<double, UninitialisedAllocator<double>>;

/// Compressed lists: the items of entry i are items[offsets[i] .. offsets[i+1]).
struct CompressedLists
{
  IdVector offsets;
  IdVector items;
  std::int64_t Begin(std::int64_t i) const { return this->offsets[static_cast<size_t>(i)]; }
  std::int64_t End(std::int64_t i) const { return this->offsets[static_cast<size_t>(i) + 1]; }
};

/// Triangles, point-to-triangle lists, one-rings and edge neighbours (see the file comment).
class MeshConnectivity
{
public:
  /**
   * Build from `triangles` (3 point ids per triangle, taken over) on
   * `numberOfPoints` points. Fails when an id is outside [0, numberOfPoints)
   * or the mesh is too large for the index types.
   * @param threads OpenMP threads (0 = all cores; fewer for small meshes).
   */
  Status Build(std::int64_t numberOfPoints, IdVector triangles, int threads);
  /// Build from a copy of `triangles`.
  Status Build(std::int64_t numberOfPoints, const std::vector<std::int64_t>& triangles, int threads)
  {
    return this->Build(numberOfPoints, IdVector(triangles.begin(), triangles.end()), threads);
  }

  /**
   * The connectivity of `source` with its points split into copies: point q of
   * the result copies point original[q] (every source point has at least one
   * copy, the copies of a point are consecutive and in the order of the points
   * they copy), and `triangles` are the source's, in the same order, with each
   * corner replaced by a copy of it (equal corners by the same copy). The
   * result is what Build(original.size(), triangles) gives; only the lists
   * around split points and their neighbours are recomputed. The one-rings
   * (and the number of edges) are collected from the triangles around each
   * point when first asked for: the advection on a split mesh reads its
   * triangles, its lists of triangles around points and its neighbours, while
   * the one-rings serve the flow, which a sharpening computes on the
   * unsplit mesh. Falls back to Build when the arguments are not such a split.
   */
  Status BuildSplit(const MeshConnectivity& source, const std::vector<std::int64_t>& original,
    IdVector triangles, int threads);
  /// Whether the last BuildSplit derived the lists from its source (not the fallback).
  bool DerivedFromSource() const { return this->derived; }

  std::int64_t NumberOfPoints() const { return this->numberOfPoints; }
  std::int64_t NumberOfTriangles() const
  {
    return static_cast<std::int64_t>(this->triangles.size() / 3);
  }
  const std::int64_t* Corners(std::int64_t f) const
  {
    return &this->triangles[static_cast<size_t>(3 * f)];
  }
  /// Triangles that use point p, in increasing order.
  const CompressedLists& PointTriangles() const { return this->pointTriangles; }
  /// Points joined to p by an edge, each once, in increasing order.
  const CompressedLists& OneRing() const
  {
    this->CollectPendingOneRings();
    return this->oneRing;
  }
  /// Whether the one-rings are there (false after BuildSplit until OneRing or NumberOfEdges is called).
  bool OneRingsBuilt() const { return !this->pendingRings || !this->oneRing.offsets.empty(); }
  /**
   * Triangle across edge e of triangle f (from corner e to corner (e+1)%3) when
   * exactly one other triangle has both its end points; -1 otherwise, and for
   * an edge whose end points are the same point (a repeated id).
   */
  std::int64_t Neighbour(std::int64_t f, int e) const
  {
    return this->neighbour[static_cast<size_t>(3 * f + e)];
  }
  /// Number of unique edges.
  std::int64_t NumberOfEdges() const
  {
    this->CollectPendingOneRings();
    return this->numberOfEdges;
  }
  /// Neighbour(f, e) for all f and e, 3 per triangle.
  const std::int64_t* Neighbours() const { return this->neighbour.data(); }

private:
  // The steps of Build, in order.
  void BuildPointTriangles(int threads);
  void BuildOneRingAndNeighbours(int threads);

  // The steps of BuildSplit, in order: the check (else it falls back to
  // Build), then the lists of the copies from those of the source.
  static bool IsSplitOf(const MeshConnectivity& source, const std::vector<std::int64_t>& original,
    const IdVector& triangles, int team);
  struct SplitCopies; // the source and its points' copies (MeshConnectivity.cxx)
  void SplitPointTriangles(const SplitCopies& split);
  void SplitNeighbours(const SplitCopies& split);
  /// After BuildSplit, on first use: the one-rings from the triangles around each point (once, thread-safe).
  void CollectPendingOneRings() const;

  std::int64_t numberOfPoints = 0;
  bool derived = false;
  IdVector triangles;
  CompressedLists pointTriangles;
  IdVector neighbour;
  // Built by Build; after BuildSplit collected on first use (CollectPendingOneRings).
  mutable std::int64_t numberOfEdges = 0;
  mutable CompressedLists oneRing;
  std::unique_ptr<std::once_flag> pendingRings; ///< set by BuildSplit: the one-rings are collected on first use
  int ringThreads = 1;
};

} // namespace shock

#endif
