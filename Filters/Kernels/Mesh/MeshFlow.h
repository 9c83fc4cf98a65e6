/**
 * @file MeshFlow.h
 * @brief The steps of the shock-filter flow on a triangle mesh (sections 3.2-3.3,
 * 4 and Appendix A of Prada and Kazhdan 2015), each a function one can call
 * and test alone:
 *
 *  1. UmbrellaWeights, UmbrellaSmooth: umbrella smoothing with Gaussian weights
 *     exp(-|(v-w)/l|^2) over the one-ring;
 *  2. TriangleGradient: gradient of the linear interpolant on a triangle;
 *     TriangleEnergy: |grad I|^2 summed over the channels;
 *  3. TrianglesToPoints: the potential per point, the area-weighted average over
 *     the adjacent triangles (also how cell signals become point signals);
 *  4. UmbrellaSmooth again on the potential; TriangleFlow: u = 1/2 grad P.
 *
 * Lengths are in units of `length` (the mean edge length l-bar in a run);
 * `valid*` arrays are per point or per triangle, 1 where the element takes part.
 */
#ifndef MeshFlow_h
#define MeshFlow_h

#include "TriangleMesh.h"
#include "Vec3.h"

#include <cstdint>
#include <vector>

namespace shock
{

/// Umbrella weight exp(-|(v-w)/l|^2) of each entry of mesh.OneRing().
ValueVector UmbrellaWeights(const TriangleMesh& mesh, double length, int threads);

/**
 * `passes` passes of Appendix A umbrella smoothing of a point signal (C values
 * per point): each point becomes (v + sum_w a_w w) / (1 + sum_w a_w) over its
 * valid one-ring neighbours w, with `weights` from UmbrellaWeights. Invalid
 * points neither change nor contribute.
 */
void UmbrellaSmooth(const TriangleMesh& mesh, const ValueVector& weights,
  const std::vector<unsigned char>& validPoint, int C, std::vector<double>& values, int passes,
  int threads);

/// Gradient of channel c of a point signal (C values per point) on triangle f, lengths in `length`.
Vec3 TriangleGradient(
  const TriangleMesh& mesh, const double* values, int C, int c, std::int64_t f, double length);

/// |grad I|^2 per triangle summed over the C channels (section 3.3); 0 on invalid triangles.
ValueVector TriangleEnergy(const TriangleMesh& mesh, const double* values, int C,
  const std::vector<unsigned char>& validTriangle, double length, int threads);

/**
 * Average a per-triangle signal (C values per triangle) to the points, weighted
 * by area, over the valid triangles around each point; points without any get zeros.
 */
void TrianglesToPoints(const TriangleMesh& mesh, int C, const double* cells,
  const std::vector<unsigned char>& cellValid, std::vector<double>& points, int threads);

/// The flow u = 1/2 grad P per triangle (3 values, mesh axes); 0 on invalid triangles.
std::vector<double> TriangleFlow(const TriangleMesh& mesh, const std::vector<double>& potential,
  const std::vector<unsigned char>& validTriangle, double length, int threads);

} // namespace shock

#endif
