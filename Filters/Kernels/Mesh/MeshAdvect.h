/**
 * @file MeshAdvect.h
 * @brief Appendix A AdvectVertices and AdvectFaces on a triangle mesh, and the
 * sampling of a signal at a traced surface point (Sampling::Linear or Nearest).
 *
 * AdvectVertices traces each point from an offset of 0.001 towards the centre of
 * each adjacent triangle, samples the source at the traced points and averages;
 * AdvectFaces traces each triangle from its centre and samples there.
 */
#ifndef MeshAdvect_h
#define MeshAdvect_h

#include "MeshTrace.h"
#include "ShockTypes.h"
#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace shock
{

/// True when the C values at v are all finite.
bool AllFinite(const double* v, int C);

/// The signal that advection reads.
struct MeshSource
{
  int components = 1;
  /// Per-point values (C per point): the point signal, or a cell signal's per-point averages.
  const double* points = nullptr;
  /// Per-triangle values (C per triangle) of a cell signal; null for a point signal.
  const double* cells = nullptr;
  /// Per point: 1 when its values may be read (see MeshShockAdvection's validity rules).
  const unsigned char* validPoint = nullptr;
  /**
   * Cell signals, per point, or null: 1 where the point's average does not
   * stand for its triangles (MeshSignal::cornerDeviation, a cone's apex):
   * Linear sampling in a triangle reads the triangle's own value for that corner.
   */
  const unsigned char* ownCorner = nullptr;
};

/**
 * Add the source's value at q to `acc` (C values). Linear: the barycentric
 * interpolation of the valid corners' point values (renormalised, clamped to
 * their range; at an ownCorner, the triangle's own value). Nearest: the
 * triangle's own value for a cell signal, else the value of the nearest valid
 * corner. Returns false, adding nothing, when no valid value is there.
 */
bool SampleSurface(const TriangleMesh& mesh, const SurfacePoint& q, Sampling sampling,
  const MeshSource& source, double* acc);

/// Start of the vertex-advection trace of point p into triangle f (the Appendix's offset 0.001).
SurfacePoint VertexStart(const TriangleMesh& mesh, std::int64_t p, std::int64_t f);

/// Start of the face-advection trace of triangle f: its centre.
SurfacePoint FaceStart(std::int64_t f);

/// One advection pass: traces along a tracer's velocity for `time`, in parallel
/// (ParallelItems: no barrier between parts, progress reported as it goes),
/// counting steps into `report`.
struct AdvectionPass
{
  const TriangleMesh& mesh;
  const SurfaceTracer& tracer;
  double time;
  Sampling sampling;
  int threads;
  const ProgressFunction& progress;
  double progressStart;
  double progressSpan;
  AdvectionReport& report;
  /**
   * A piece of a distributed mesh: each triangle's ghost ring (MeshSignal::
   * triangleRing), or null. The traces of the own samples (points of a ring-0
   * triangle; ring-0 triangles) record how deep they went: report.deepestRing.
   */
  const unsigned char* triangleRing = nullptr;

  /// Run body(i, steps, truncated, deepest) for i in [0, n) in parallel; false when aborted.
  template <typename Body>
  bool ForEach(std::int64_t n, Body&& body);

  /// Trace q for `time`; returns the steps, counts a truncated trace. With `reach`, records its rings.
  std::uint64_t Trace(SurfacePoint& q, std::uint64_t& truncated, RingReach* reach = nullptr) const;
};

/**
 * Appendix A AdvectVertices of a point signal into `out` (C per point). With
 * `positions` (Composed flow; one per entry of mesh.PointTriangles()), traces
 * resume from and update stored positions. Returns false when aborted.
 */
bool AdvectVertices(
  AdvectionPass& pass, const MeshSource& source, double* out, std::vector<SurfacePoint>* positions);

/**
 * Appendix A AdvectFaces of a cell signal into `out` (C per triangle). With
 * `positions` (one per triangle), traces resume from and update stored
 * positions. Returns false when aborted.
 */
bool AdvectFaces(
  AdvectionPass& pass, const MeshSource& source, double* out, std::vector<SurfacePoint>* positions);

/// Composed-flow start positions, as AdvectVertices (cells = false) or AdvectFaces would start.
std::vector<SurfacePoint> InitialPositions(const TriangleMesh& mesh, bool cells);

} // namespace shock

#endif
