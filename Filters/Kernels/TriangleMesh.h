/**
 * @file TriangleMesh.h
 * @brief Geometry and adjacency of a triangle mesh, shared by the surface shock filters.
 *
 * The mesh is given as plain arrays (TriangleMeshView). TriangleMesh precomputes
 * what the shock filters and the screened Poisson fit need: per-triangle area,
 * unit normal, centroid and the gradients of the three linear "hat" basis
 * functions; the triangles around each vertex; the one-ring of each vertex; the
 * triangle across each edge; and the mean edge length (the paper's l-bar),
 * taken over the triangles' edges: each triangle contributes its three edges,
 * so an interior edge counts twice and a boundary edge once (on a closed
 * surface this is the mean over unique edges). This definition can be summed
 * piece by piece, which lets a parallel run use exactly the serial unit.
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

#include "ShockTypes.h"

#include <array>
#include <cstdint>
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

/// Compressed lists: the items of entry i are items[offsets[i] .. offsets[i+1]).
struct CompressedLists
{
  std::vector<std::int64_t> offsets;
  std::vector<std::int64_t> items;
  std::int64_t Begin(std::int64_t i) const { return this->offsets[static_cast<size_t>(i)]; }
  std::int64_t End(std::int64_t i) const { return this->offsets[static_cast<size_t>(i) + 1]; }
};

/// Sum of the three edge lengths of the triangle with these corners (3 coordinates per point).
double TrianglePerimeter(const double* points, const std::int64_t* corners);

/// Precomputed geometry and adjacency of a triangle mesh (see the file comment).
class TriangleMesh
{
public:
  /**
   * Build from a view (copied). Fails when a point id is out of range, a
   * coordinate is not finite, or the mesh is too large for the index types.
   * @param threads OpenMP threads (0 = all cores).
   */
  Status Build(const TriangleMeshView& view, int threads);

  std::int64_t NumberOfPoints() const { return this->numberOfPoints; }
  std::int64_t NumberOfTriangles() const { return this->numberOfTriangles; }

  const double* Point(std::int64_t p) const { return &this->points[static_cast<size_t>(3 * p)]; }
  const std::int64_t* Corners(std::int64_t f) const
  {
    return &this->triangles[static_cast<size_t>(3 * f)];
  }
  double Area(std::int64_t f) const { return this->area[static_cast<size_t>(f)]; }
  bool Degenerate(std::int64_t f) const { return this->degenerate[static_cast<size_t>(f)] != 0; }
  /// Unit normal (zero for degenerate triangles), counter-clockwise orientation.
  const double* Normal(std::int64_t f) const { return &this->normal[static_cast<size_t>(3 * f)]; }
  const double* Centroid(std::int64_t f) const
  {
    return &this->centroid[static_cast<size_t>(3 * f)];
  }
  /// Gradient of the hat function of corner c (0..2) on triangle f (zero when degenerate).
  const double* HatGradient(std::int64_t f, int c) const
  {
    return &this->hatGradient[static_cast<size_t>(9 * f + 3 * c)];
  }
  /**
   * Triangle across edge e of triangle f, the edge from corner e to corner (e+1)%3;
   * -1 on boundary and non-manifold edges and next to degenerate triangles.
   */
  std::int64_t Neighbour(std::int64_t f, int e) const
  {
    return this->neighbour[static_cast<size_t>(3 * f + e)];
  }
  /// Triangles that use point p.
  const CompressedLists& PointTriangles() const { return this->pointTriangles; }
  /// Points joined to p by an edge (each once).
  const CompressedLists& OneRing() const { return this->oneRing; }
  /// Mean length of the triangles' edges (l-bar, see the file comment); 0 without triangles.
  double MeanEdgeLength() const { return this->meanEdgeLength; }
  /// Number of unique edges.
  std::int64_t NumberOfEdges() const { return this->numberOfEdges; }

private:
  // The steps of Build, in order.
  void BuildPointTriangles(int threads); // sequential: ordered lists
  void BuildOneRing(int threads);
  void ComputeMeanEdgeLength(int threads);
  void ComputeGeometry(int threads);
  void BuildNeighbours(int threads);

  std::int64_t numberOfPoints = 0;
  std::int64_t numberOfTriangles = 0;
  std::int64_t numberOfEdges = 0;
  double meanEdgeLength = 0.0;
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  std::vector<double> area;
  std::vector<unsigned char> degenerate;
  std::vector<double> normal;
  std::vector<double> centroid;
  std::vector<double> hatGradient;
  std::vector<std::int64_t> neighbour;
  CompressedLists pointTriangles;
  CompressedLists oneRing;
};

} // namespace shock

#endif
