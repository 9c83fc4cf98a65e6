/**
 * @file MeshGeometry.h
 * @brief The geometry of a triangle mesh, computed from point positions over
 * its connectivity (MeshConnectivity.h): per-triangle area, unit normal
 * and the gradients of the three linear "hat" basis functions, and
 * the mean edge length (the paper's l-bar).
 *
 * l-bar is taken over the triangles' edges: each triangle contributes its
 * three edges, so an interior edge counts twice and a boundary edge once (on a
 * closed surface this is the mean over unique edges). This definition can be
 * summed piece by piece, which lets a parallel run use exactly the serial unit.
 *
 * A triangle is degenerate when its area is below 1e-12 x l-bar^2 (repeated
 * ids, collinear corners). It has no normal and zero hat gradients.
 */
#ifndef MeshGeometry_h
#define MeshGeometry_h

#include "MeshConnectivity.h"
#include "ShockTypes.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace shock
{

/// Sum of the three edge lengths of the triangle with these corners (3 coordinates per point).
double TrianglePerimeter(const double* points, const std::int64_t* corners);

/// Positions and per-triangle geometry over a MeshConnectivity (see the file comment).
class MeshGeometry
{
public:
  MeshGeometry() = default;
  MeshGeometry(MeshGeometry&&) = default;
  MeshGeometry& operator=(MeshGeometry&&) = default;
  MeshGeometry(const MeshGeometry& other) { *this = other; }
  MeshGeometry& operator=(const MeshGeometry& other);

  /**
   * Compute from `points` (3 coordinates per point of `connectivity`, copied).
   * Fails when a coordinate is not finite.
   * @param threads OpenMP threads (0 = all cores; fewer for small meshes).
   */
  Status Compute(const MeshConnectivity& connectivity, const double* points, int threads);

  /**
   * The geometry of a mesh whose points copy those of `source`'s mesh (point q
   * copies original[q]) and whose triangles are the source's with each corner
   * replaced by one of its copies: what Compute would give, without computing
   * it. The points are copied; the per-triangle arrays (which depend only on
   * the corners' positions) are shared with `source`.
   */
  void ComputeFromCopies(const MeshGeometry& source, const std::vector<std::int64_t>& original, int threads);

  const double* Point(std::int64_t p) const { return &this->points[static_cast<size_t>(3 * p)]; }
  double Area(std::int64_t f) const { return this->area[static_cast<size_t>(f)]; }
  bool Degenerate(std::int64_t f) const { return this->degenerate[static_cast<size_t>(f)] != 0; }
  /// Unit normal (zero for degenerate triangles), counter-clockwise orientation.
  const double* Normal(std::int64_t f) const { return &this->normal[static_cast<size_t>(3 * f)]; }
  /// Gradient of the hat function of corner c (0..2) on triangle f (zero when degenerate).
  const double* HatGradient(std::int64_t f, int c) const
  {
    return &this->hatGradient[static_cast<size_t>(9 * f + 3 * c)];
  }
  /// Mean length of the triangles' edges (l-bar, see the file comment); 0 without triangles.
  double MeanEdgeLength() const { return this->meanEdgeLength; }

private:
  // The steps of Compute, in order.
  void ComputeMeanEdgeLength(const MeshConnectivity& connectivity, int threads);
  void ComputeTriangles(const MeshConnectivity& connectivity, int threads);

  // Arrays allocated without zero-filling: the parallel loops write (first touch) them all.
  // The per-triangle arrays are never written after Compute: meshes whose
  // triangles have the same corner positions share them (ComputeFromCopies).
  std::int64_t numberOfPoints = 0;
  std::int64_t numberOfTriangles = 0;
  double meanEdgeLength = 0.0;
  std::unique_ptr<double[]> points;
  std::shared_ptr<double[]> area;
  std::shared_ptr<unsigned char[]> degenerate;
  std::shared_ptr<double[]> normal;
  std::shared_ptr<double[]> hatGradient;
};

} // namespace shock

#endif
