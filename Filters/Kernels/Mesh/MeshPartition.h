/**
 * @file MeshPartition.h
 * @brief One piece of a mesh distributed over processes, as the kernels see it.
 *
 * A piece holds the triangles it owns plus ghost layers of its neighbours'
 * triangles. Every point and every triangle of the whole mesh is owned by
 * exactly one piece. A kernel that sums over the mesh sums what its piece
 * owns and adds the pieces' sums with globalSum; a kernel that needs values
 * of points owned elsewhere (the halo of an owned point's one-ring) gets them
 * with exchangePoints. The callbacks hide the transport (MPI through a
 * vtkMultiProcessController in the VTK layer), so the kernels stay VTK-free.
 */
#ifndef MeshPartition_h
#define MeshPartition_h

#include <functional>
#include <vector>

namespace shock
{

struct MeshPartition
{
  /// Per point of the piece: 1 when this piece owns it (its matrix row, its terms of sums).
  std::vector<char> ownedPoints;
  /// Per triangle of the piece: 1 when this piece owns it (its area and centroid).
  std::vector<char> ownedTriangles;
  /// Per point of the piece: 1 when this piece owns it and another piece reads
  /// its values (exchangePoints sends them). The fit's solver updates these
  /// points' directions before each exchange and the others in the pass of its
  /// products. Empty when not known: every owned point counts as read elsewhere.
  std::vector<char> sharedPoints;
  /// Replace values[0..count) by their sums over all pieces (collective).
  std::function<void(double* values, int count)> globalSum;
  /// values holds 3 doubles per point of the piece: overwrite those of the points
  /// this piece does not own but needs (the one-rings of its owned points) with
  /// the owners' values (collective).
  std::function<void(double* values)> exchangePoints;
  /// Whether any piece stops before the fit (collective): every piece calls it
  /// once, after its advection, with whether it stopped (aborted or failed), so
  /// that no piece waits in the fit's sums for one that has left, and with the
  /// deepest ghost ring its own triangles' traces read (AdvectionReport::deepestRing,
  /// -1 when not recorded), so that the pieces can stop to grow their rings first.
  std::function<bool(bool stopped, int deepestRing)> anyStopped;
};

} // namespace shock

#endif
