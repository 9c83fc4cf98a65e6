/**
 * @file FitSystem.h
 * @brief The screened Poisson system of the fit as far as it depends on the
 * mesh and the screening weight only: kept between fits of the same mesh.
 *
 * FitPositionsToNormals (ScreenedPoissonFit.h) solves
 * (eps M + S) c1 = eps M c0 + D w. The matrix eps M + S, the mass term
 * eps M c0 and the normalisation to unit area depend on the positions, the
 * triangles and eps, not on the target normals: a FitSystem holds them, so a
 * second fit of the same mesh (another flow time in ParaView, other normals)
 * assembles only D w. The anchor of the points the normals did not turn
 * (ScreenedPoissonFit.h, step 4) depends on the normals: each fit writes its
 * own into the kept diagonal, from the diagonal as assembled.
 *
 * The rows are numbered breadth-first over the one-rings (a renumbering that keeps each row's neighbours close in memory:
 * meshes made by subdivision number new points far from their neighbours, and
 * the conjugate gradients' products then wait on memory), except for a piece
 * of a distributed mesh, whose rows are its points, and a mesh whose numbering
 * is already local (rowsInMeshOrder: renumbered by LocalityNumbering), whose
 * rows are its points too.
 */
#ifndef ShockFitSystem_h
#define ShockFitSystem_h

#include "MeshPartition.h"
#include "ShockTypes.h"
#include "TriangleMesh.h"

#include <cstdint>
#include <memory>

namespace shock
{

struct FitSystemData; // FitSolve.h: the matrix, the mass term, the row order

/// A built system and what it was built for (see the file comment).
struct FitSystem
{
  /// Empty until built. Each fit writes its anchor (FitParameters::anchorWeight) into the diagonal.
  std::shared_ptr<FitSystemData> data;
  const TriangleMesh* mesh = nullptr;        ///< the mesh it was built for
  std::int64_t points = 0;                   ///< that mesh's size when built
  std::int64_t triangles = 0;
  double screeningWeight = 0.0;
  bool rowsInMeshOrder = false; ///< rows in the mesh's numbering (FitParameters::rowsInMeshOrder), not breadth-first
  /// The system of the drift's removal (ScreenedPoissonFit.h, step 5): the same
  /// mesh and row order, screening weight driftWeight; empty until a fit removes drift.
  std::shared_ptr<FitSystemData> drift;
  double driftWeight = 0.0;

  /// Built for `mesh` (the same object, unchanged since: the caller's promise), eps and row order.
  bool Matches(const TriangleMesh& target, double eps, bool meshOrder = false) const
  {
    return this->data && this->mesh == &target && this->points == target.NumberOfPoints() &&
      this->triangles == target.NumberOfTriangles() && this->screeningWeight == eps &&
      this->rowsInMeshOrder == meshOrder;
  }
  void Clear() { *this = FitSystem(); }
};

/**
 * Build the system of `mesh` for the screening weight eps (finite, > 0) on
 * `threads` threads (the result does not depend on their number). With a
 * partition, the normalisation sums run over all pieces and the rows keep the
 * points' numbering. A mesh without area gives an empty system (data null).
 */
Status BuildFitSystem(const TriangleMesh& mesh, double screeningWeight,
  const MeshPartition* partition, int threads, FitSystem& system, bool rowsInMeshOrder = false);

} // namespace shock

#endif
