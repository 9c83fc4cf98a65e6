/**
 * @file SharpFeatures.h
 * @brief What geometry sharpening leaves alone: repeated triangles and creases that are already sharp.
 *
 * Two preparations of a mesh before its normals are sharpened
 * (MeshSharpening):
 *
 *  - Repeated triangles. A triangle whose vertex set equals that of an earlier
 *    triangle (in either orientation) is a copy: what AppendDatasets of a mesh
 *    with itself followed by Clean gives, or pieces gathered from processes that
 *    each held the whole mesh. A copy makes its three edges non-manifold (traces
 *    stop there) and counts its area twice, so it would change the result;
 *    FindRepeatedTriangles finds the copies so that they can be removed.
 *
 *  - Feature edges. The paper's Linear sampling averages the face normals to
 *    the points, which rounds every crease the mesh already has: on a coarse
 *    cube the point normals are the diagonals, and the fit moves the corners by
 *    a third of the diagonal. An edge between two triangles whose normals differ
 *    by more than a feature angle is a feature edge, as in vtkPolyDataNormals.
 *    SplitAtFeatureEdges gives every point on a feature edge one copy per group
 *    of its triangles joined by non-feature edges, so the per-point normals are
 *    averaged on each side of a sharp crease separately (they become per-corner
 *    normals), and the crease is a boundary for the advection: a sharp crease
 *    carries no flow and keeps its normals, while a blurred crease, whose edges
 *    each turn by a small angle, is sharpened as the paper does.
 */
#ifndef SharpFeatures_h
#define SharpFeatures_h

#include "ShockTypes.h"
#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace shock
{

/**
 * Triangles that repeat the vertex set of an earlier triangle.
 * @return one entry per triangle: -1 for the first occurrence of a vertex set
 *         (and for every triangle that is not repeated), otherwise the index of
 *         that first occurrence.
 */
std::vector<std::int64_t> FindRepeatedTriangles(const TriangleMesh& mesh, int threads);

/// A mesh whose points are split along feature edges (see SplitAtFeatureEdges).
struct FeatureSplitMesh
{
  TriangleMesh mesh;                   ///< same triangles, in the same order, with split points
  std::vector<std::int64_t> original;  ///< for each point of `mesh`, the point it copies
  std::int64_t featureEdges = 0;       ///< number of feature edges found
};

/**
 * Split the points of `mesh` along its feature edges: the edges shared by two
 * triangles (Neighbour) whose unit normals, given per triangle in `normals`,
 * make an angle larger than featureAngleDegrees. Each point touched by a
 * feature edge gets one copy per group of its triangles joined through
 * non-feature edges; other points are not split. With no feature edge (in
 * particular for an angle >= 180), `split.mesh` is left empty and
 * `split.featureEdges` is 0: use `mesh` itself.
 * @return an error when featureAngleDegrees is not in [0, 180] or the split mesh cannot be built.
 */
Status SplitAtFeatureEdges(const TriangleMesh& mesh, const double* normals,
  double featureAngleDegrees, int threads, FeatureSplitMesh& split);

} // namespace shock

#endif
