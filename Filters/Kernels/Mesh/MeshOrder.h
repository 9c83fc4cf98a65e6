/**
 * @file MeshOrder.h
 * @brief A numbering of a mesh's points and triangles that keeps neighbours near
 * in memory.
 *
 * The kernels visit points and triangles in their numbering and read their
 * neighbours' data: one-rings, the triangles a trace crosses, the corners it
 * samples. A mesh numbered in the order of a subdivision or a scan's merge
 * puts neighbours far apart, and these reads then wait on memory. Points
 * sorted along a Morton (Z-order) curve of their positions, and triangles by
 * their first corner in that order, put them close: the surface filter runs on
 * the renumbered mesh and maps its results back. The numbering changes no result beyond the rounding of sums
 * taken in another order.
 */
#ifndef ShockMeshOrder_h
#define ShockMeshOrder_h

#include "MeshConnectivity.h"

#include <cstdint>
#include <vector>

namespace shock
{

using CodeVector = std::vector<std::uint32_t, UninitialisedAllocator<std::uint32_t>>;

/// A renumbering of points and triangles.
struct MeshNumbering
{
  IdVector points;    ///< new index -> old index
  IdVector rank;      ///< the inverse: old point index -> new index
  IdVector triangles; ///< new index -> old index
  CodeVector codes;   ///< each point's Morton code (by old index)
};

/**
 * The points in the order of their cells on a Morton curve through a grid of
 * 1024^3 cells over their bounding box (equal cells in their old order): fills
 * points, rank and codes (triangles stays empty). `points`: 3 finite
 * coordinates per point.
 */
MeshNumbering MortonOrder(std::int64_t numberOfPoints, const double* points, int threads,
  const double* box = nullptr);

/**
 * For each point, the first point (smallest index) with exactly the same
 * coordinates, itself when unique, read from a MortonOrder of the same points:
 * coincident points share a cell, so only points of a run of equal codes are
 * compared.
 */
std::vector<std::int64_t> CoincidentPoints(const MeshNumbering& numbering, const double* points, int threads);

/**
 * Fill numbering.triangles: the triangles by their smallest corner in the
 * order of numbering.rank (equal ones in their old order). `ids`: 3 point ids
 * in [0, number of points) per triangle.
 */
void OrderTriangles(MeshNumbering& numbering, std::int64_t numberOfTriangles, const std::int64_t* ids, int threads);

/**
 * MortonOrder then OrderTriangles. Deterministic: no result of this file
 * depends on `threads` (OpenMP threads of every function here; 0 = all cores,
 * fewer for small inputs).
 */
MeshNumbering LocalityNumbering(std::int64_t numberOfPoints, const double* points,
  std::int64_t numberOfTriangles, const std::int64_t* ids, int threads);

/**
 * The Morton code of a point's cell in the grid of 1024^3 cells over the box
 * [lower, lower + side]: the cell index along axis a, floor(1024 (x_a - lower_a)
 * / side_a) clamped to [0, 1023] (0 when side_a is 0), gives bits a, a + 3,
 * a + 6, ... of the code.
 */
std::uint32_t MortonCode(const double* point, const double lower[3], const double side[3]);

} // namespace shock

#endif
