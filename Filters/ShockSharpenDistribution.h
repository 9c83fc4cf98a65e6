/**
 * @file ShockSharpenDistribution.h
 * @brief The fit's view of a piece of a distributed mesh (private to the
 * module): which points and triangles it owns, which values it exchanges, and
 * the whole mesh's mean edge length.
 */
#ifndef ShockSharpenDistribution_h
#define ShockSharpenDistribution_h

#include "MeshPartition.h"
#include "ShockParallel.h"
#include "ShockPolyDataInternals.h"

class vtkMultiProcessController;
class vtkPolyData;

namespace ShockParallel
{
/// A piece of a distributed mesh as the fit sees it, and the exchange behind it.
struct Distribution
{
  Distribution() = default;
  Distribution(const Distribution&) = delete; // the partition's functions point at this one
  Distribution& operator=(const Distribution&) = delete;
  shock::MeshPartition partition;
  ShockParallel::PointExchange exchange;
  double meanEdgeLength = 0.0;
  double wholeTriangles = 0.0; ///< the triangles all pieces own (the traces' step cap)
};

/**
 * Ownership from the ghost marks (each point and triangle owned by one
 * process), the points whose owners' values this piece needs (corners of the
 * triangles around its owned points and of its owned triangles), the exchange
 * keyed by global point ids, and the mean edge length and triangle count over all pieces.
 * Collective.
 */
void Distribute(vtkMultiProcessController* controller, vtkPolyData* piece,
  const ShockPolyDataInternals::PreparedMesh& prepared, Distribution& out);
}

#endif
