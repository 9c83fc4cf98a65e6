/**
 * @file TriangleMesh.h
 * @brief A triangle mesh as the surface shock filters use it: its connectivity
 * (MeshConnectivity.h, built from the point ids alone, shareable between meshes
 * whose points differ) and its geometry (MeshGeometry.h, from the positions).
 *
 * TriangleMesh answers both kinds of question through one interface and adds
 * the one rule that needs both: traces cross an edge only between two
 * non-degenerate triangles (Neighbour).
 *
 * Conventions that define the behaviour on meshes as users have them:
 *  - A triangle is degenerate when its area is below 1e-12 x l-bar^2 (repeated
 *    ids, collinear corners). It has no normal and zero hat gradients, carries
 *    no flow, and traces stop at it.
 *  - An edge shared by exactly two triangles (by point ids) joins them; edges with
 *    one triangle (boundary) or more than two (non-manifold) join nothing, so
 *    traces stop there. Duplicate points are distinct vertices: a seam of
 *    duplicates behaves as a boundary.
 *  - Points used by no triangle have no neighbours and no adjacent triangles.
 */
#ifndef TriangleMesh_h
#define TriangleMesh_h

#include "MeshConnectivity.h"
#include "MeshGeometry.h"
#include "ShockTypes.h"
#include "Vec3.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace shock
{

/// A triangle mesh as plain arrays; the memory is owned by the caller.
struct TriangleMeshView
{
  std::int64_t numberOfPoints = 0;
  const double* points = nullptr; ///< 3 coordinates per point
  std::int64_t numberOfTriangles = 0;
  const std::int64_t* triangles = nullptr; ///< 3 point ids per triangle
};

/// Connectivity and geometry of a triangle mesh (see the file comment).
class TriangleMesh
{
public:
  TriangleMesh();

  /**
   * Build from a view (copied): the connectivity, then the geometry. Fails
   * when a point id is out of range, a coordinate is not finite, or the mesh
   * is too large for the index types.
   * @param threads OpenMP threads (0 = all cores; fewer for small meshes).
   */
  Status Build(const TriangleMeshView& view, int threads);

  /**
   * Build as from a view, taking the triangles' ids over instead of copying
   * them (3 per triangle; read them back with Corners).
   */
  Status Build(std::int64_t numberOfPoints, const double* points, IdVector triangles, int threads);
  /// Build as from a view, from a copy of `triangles`.
  Status Build(std::int64_t numberOfPoints, const double* points,
    const std::vector<std::int64_t>& triangles, int threads)
  {
    return this->Build(numberOfPoints, points, IdVector(triangles.begin(), triangles.end()), threads);
  }

  /**
   * Build over an existing connectivity (shared, not copied) with new point
   * positions (3 per point of the connectivity, copied): only the geometry is
   * computed. Fails when a coordinate is not finite.
   */
  Status Build(std::shared_ptr<const MeshConnectivity> connectivity, const double* points,
    int threads);

  /**
   * Build the mesh of `source` with its points split into copies (see
   * MeshConnectivity::BuildSplit: point q copies original[q], `triangles` are
   * the source's with each corner replaced by a copy of it): the same mesh as
   * Build with those points and triangles, derived from the source's lists and
   * sharing its per-triangle geometry.
   */
  Status BuildSplit(const TriangleMesh& source, const std::vector<std::int64_t>& original,
    IdVector triangles, int threads);

  const MeshConnectivity& Connectivity() const { return *this->connectivity; }
  /// The connectivity, to build another mesh over it.
  std::shared_ptr<const MeshConnectivity> SharedConnectivity() const { return this->connectivity; }
  const MeshGeometry& Geometry() const { return this->geometry; }

  std::int64_t NumberOfPoints() const { return this->connectivity->NumberOfPoints(); }
  std::int64_t NumberOfTriangles() const { return this->connectivity->NumberOfTriangles(); }
  const std::int64_t* Corners(std::int64_t f) const { return this->corners + 3 * f; }
  const double* Point(std::int64_t p) const { return this->geometry.Point(p); }
  double Area(std::int64_t f) const { return this->geometry.Area(f); }
  bool Degenerate(std::int64_t f) const { return this->geometry.Degenerate(f); }
  /// Unit normal (zero for degenerate triangles), counter-clockwise orientation.
  const double* Normal(std::int64_t f) const { return this->geometry.Normal(f); }
  /// Centroid (x0 + x1 + x2) / 3 of the corners (computed when asked: nothing stored).
  Vec3 Centroid(std::int64_t f) const
  {
    const std::int64_t* t = this->Corners(f);
    const double* x[3] = { this->Point(t[0]), this->Point(t[1]), this->Point(t[2]) };
    return { (x[0][0] + x[1][0] + x[2][0]) / 3.0, (x[0][1] + x[1][1] + x[2][1]) / 3.0,
      (x[0][2] + x[1][2] + x[2][2]) / 3.0 };
  }
  /// Gradient of the hat function of corner c (0..2) on triangle f (zero when degenerate).
  const double* HatGradient(std::int64_t f, int c) const
  {
    return this->geometry.HatGradient(f, c);
  }
  /**
   * Triangle across edge e of triangle f, the edge from corner e to corner (e+1)%3;
   * -1 on boundary and non-manifold edges and next to degenerate triangles.
   */
  std::int64_t Neighbour(std::int64_t f, int e) const
  {
    const std::int64_t g = this->neighbours[3 * f + e];
    return g >= 0 && !this->Degenerate(f) && !this->Degenerate(g) ? g : -1;
  }
  /// Neighbour(f, e) before the degeneracy test: -1 only on boundary and non-manifold edges.
  std::int64_t RawNeighbour(std::int64_t f, int e) const { return this->neighbours[3 * f + e]; }
  /// Triangles that use point p.
  const CompressedLists& PointTriangles() const { return this->connectivity->PointTriangles(); }
  /// Points joined to p by an edge (each once).
  const CompressedLists& OneRing() const { return this->connectivity->OneRing(); }
  /// Mean length of the triangles' edges (l-bar, see MeshGeometry.h); 0 without triangles.
  double MeanEdgeLength() const { return this->geometry.MeanEdgeLength(); }
  /// Number of unique edges.
  std::int64_t NumberOfEdges() const { return this->connectivity->NumberOfEdges(); }

private:
  std::shared_ptr<const MeshConnectivity> connectivity;
  // The connectivity's arrays read in every loop (tracing above all).
  const std::int64_t* corners = nullptr;    ///< connectivity->Corners(0)
  const std::int64_t* neighbours = nullptr; ///< the raw edge neighbours of triangle 0, 1, ...
  MeshGeometry geometry;
};

} // namespace shock

#endif
