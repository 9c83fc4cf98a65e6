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
 * the renumbered mesh and maps its results back (Benchmarks/RESULTS.md, issue
 * 18, session 9). The numbering changes no result beyond the rounding of sums
 * taken in another order.
 */
#ifndef ShockMeshOrder_h
#define ShockMeshOrder_h

#include "MeshConnectivity.h"

#include <cstdint>
#include <vector>

namespace shock
{

/// A renumbering of points and triangles.
struct MeshNumbering
{
  IdVector points;    ///< new index -> old index
  IdVector rank;      ///< the inverse: old point index -> new index
  IdVector triangles; ///< new index -> old index
};

/**
 * The points in the order of their cells on a Morton curve through a grid of
 * 1024^3 cells over their bounding box (equal cells in their old order), and
 * the triangles by their smallest corner in that order (equal ones in their
 * old order). `points`: 3 finite coordinates per point; `ids`: 3 point ids in
 * [0, numberOfPoints) per triangle. Deterministic: it does not depend on the
 * number of threads.
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
