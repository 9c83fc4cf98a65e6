/**
 * @file MeshShockAdvection.h
 * @brief Shock-filter advection of multi-channel signals on triangle meshes.
 *
 * Implements section 4 and Appendix A of Prada and Kazhdan (2015) on a
 * TriangleMesh:
 *
 * The steps are public functions: MeshFlow.h (smoothing, gradients, potential,
 * flow), MeshTrace.h (Trace), MeshAdvect.h (sampling, AdvectVertices/AdvectFaces).
 *
 *  1. per-point signal (cell signals are first averaged to points, area-weighted),
 *     umbrella-smoothed with Gaussian weights exp(-|(v-w)/l|^2) over the one-ring;
 *  2. per-triangle gradient of the linear interpolant; |grad I|^2 summed over
 *     channels (section 3.3 coupling); potential per point = area-weighted average
 *     over the adjacent triangles;
 *  3. umbrella-smooth the potential; flow per triangle u = 1/2 grad P (in the
 *     triangle's plane);
 *  4. back-trace along -u over the surface: straight inside a triangle, unfolding
 *     the next triangle across an edge (Shi and Yu 2004); traces stop at boundary
 *     and non-manifold edges, at degenerate triangles, when the flow reverses, or
 *     when the time is used up;
 *  5. sample the input at the traced points: point signals are advected per vertex
 *     (an offset of 0.001 towards each adjacent face centre, traced and averaged,
 *     the Appendix's AdvectVertices), cell signals per face (from the face centre,
 *     AdvectFaces).
 *
 * Intensities are normalised by the data range (or a caller-given scale) and
 * lengths by the mean edge length, so the same time t gives the same result for
 * any value scale and any uniform mesh scale. Non-finite values keep their value
 * and do not spread: triangles touching them carry no flow and are not sampled.
 */
#ifndef MeshShockAdvection_h
#define MeshShockAdvection_h

#include "MeshTrace.h"
#include "ShockTypes.h"
#include "TriangleMesh.h"

#include <vector>

namespace shock
{

/// Where a mesh signal lives.
enum class MeshLocation : int
{
  Points = 0,   ///< one value per point: vertex advection
  Triangles = 1 ///< one value per triangle: face advection
};

/// Optional outputs describing the flow of the last flow computation.
struct MeshFlowFields
{
  /// Potential P per point (normalised units: range-normalised intensities, lengths in l-bar).
  std::vector<double> potential;
  /// Flow u = 1/2 grad P per triangle, 3 components in the mesh's axes, normalised units.
  std::vector<double> flow;
};

/// Signal to filter on a mesh.
struct MeshSignal
{
  MeshLocation location = MeshLocation::Points;
  int components = 1;             ///< channels (>= 1), coupled through one flow
  const double* values = nullptr; ///< (points or triangles) x components, interleaved
  /**
   * Intensity scale used to normalise values; 0 (the default) uses the data
   * range over all finite values and channels. Geometry sharpening passes 2
   * (unit normals) so that t does not depend on how curved the mesh is.
   */
  double valueScale = 0.0;
  /**
   * Sample at the trace starts even when t = 0. Off (the default), t = 0 returns
   * the input exactly. On, a cell signal with Sampling::Linear is read from its
   * per-point averages at the face centres, which smooths it: geometry
   * sharpening does this, as the paper does (its Figure 7).
   */
  bool sampleAtTimeZero = false;
  /**
   * Cell signals, Sampling::Linear: a point whose per-point average differs
   * from the value of one of its valid triangles by more than this (Euclidean
   * distance over the channels, in the signal's units) does not stand for its
   * triangles, and a sample in a triangle reads that triangle's own value for
   * the corner. Geometry sharpening passes the distance of two unit normals
   * FeatureAngle apart, so that the apex of a cone (where the averaged normal
   * is the axis) does not tilt the normals of its faces. 0 (the default): every
   * corner reads its point's average, as the paper does.
   */
  double cornerDeviation = 0.0;
  /**
   * Length unit used to normalise lengths; 0 (the default) uses the mesh's mean
   * edge length. A piece of a parallel run passes the mean over all pieces so
   * that every piece uses the serial unit.
   */
  double lengthScale = 0.0;
  /**
   * The potential's contrast (MeshFlow.h, CurvatureContrast): the potential
   * keeps only what exceeds this many times its minimum over `contrastRings`
   * rings, before its smoothing. 0 (the default) is the paper's potential.
   */
  double potentialContrast = 0.0;
  int contrastRings = 6; ///< rings of the contrast's minimum (>= 1)
  /**
   * A piece of a distributed mesh with ghost rings: each triangle's ring (0:
   * the piece's own, k: the k-th ring of its neighbours' triangles around
   * them), or null. The run then reports in AdvectionReport::deepestRing the
   * deepest ring the traces of the own samples read (see MeshStencilRings).
   */
  const unsigned char* triangleRing = nullptr;
  /**
   * The triangles of the whole mesh a piece is cut from (0: this mesh's): a
   * trace's steps are capped at a few diameters of the whole mesh, as in a
   * serial run, not of the piece.
   */
  std::int64_t wholeTriangles = 0;
  /**
   * A mesh with the same triangles, in the same order, to compute the flow on
   * (null: this mesh). Surface Shock Sharpen traces and samples the normals on
   * the mesh split along its feature edges, and computes their potential and
   * flow on the connected mesh, where a crease that is still sharper than the
   * feature angle is part of the potential's peak. Fixed flow only; the
   * potential in MeshFlowFields is then per point of this mesh.
   */
  const TriangleMesh* flowMesh = nullptr;
};

/**
 * How many rings around a triangle the flow on it depends on: one per step
 * before the traces that reads a point's one-ring (a cell signal's average to
 * the points, each umbrella smoothing pass of the signal and of the potential,
 * the potential's average over the adjacent triangles, each contrast ring).
 * On a piece with R ghost rings the flow of every triangle of ring at most
 * R - MeshStencilRings is the whole mesh's, and so is the result of every own
 * sample whose traces stayed within those triangles
 * (AdvectionReport::deepestRing <= R - MeshStencilRings). -1 when the flow is
 * recomputed from advected values (FlowMode Composed or Naive with more than
 * one update): that spreads further at every update.
 */
int MeshStencilRings(const MeshSignal& signal, const AdvectionParameters& parameters);

/**
 * Run the shock filter on a mesh signal.
 *
 * @param mesh       built TriangleMesh.
 * @param signal     the signal; see MeshSignal.
 * @param output     same size as signal.values, written (must not alias it).
 * @param parameters see AdvectionParameters.
 * @param report     optional: timings and counters.
 * @param fields     optional: potential and flow of the last flow computation.
 * @param progress   optional: progress/abort callback.
 * @return an error message for invalid arguments; when aborted, output holds the input.
 */
Status AdvectMeshSignal(const TriangleMesh& mesh, const MeshSignal& signal, double* output,
  const AdvectionParameters& parameters, AdvectionReport* report = nullptr,
  MeshFlowFields* fields = nullptr, const ProgressFunction& progress = ProgressFunction());

} // namespace shock

#endif
