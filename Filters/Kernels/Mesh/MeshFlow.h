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
 * Not the paper's, optional (MeshSignal::potentialContrast; geometry sharpening's
 * default): between 3 and 4, RingMinimum and CurvatureContrast keep of the
 * potential only what rises above `contrast` times its minimum over the
 * surrounding rings, so that a surface whose |grad N|^2 (k1^2 + k2^2) varies
 * little, a sphere or a torus however coarsely tessellated, has no flow, while
 * a blurred crease (a peak over flat sides) keeps it.
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
ValueVector TriangleFlow(const TriangleMesh& mesh, const std::vector<double>& potential,
  const std::vector<unsigned char>& validTriangle, double length, int threads);

/**
 * The minimum of a per-point `values` over the points within `rings` one-rings
 * (an erosion on the mesh graph: `rings` passes of the one-ring minimum);
 * invalid points neither give nor take a value (theirs is kept).
 */
std::vector<double> RingMinimum(const TriangleMesh& mesh, const std::vector<unsigned char>& validPoint,
  const std::vector<double>& values, int rings, int threads);

/**
 * The potential's contrast: P <- max(0, P - contrast * RingMinimum(P, rings)).
 * 0 leaves P as it is (the paper). Where P varies by less than a factor
 * `contrast` over the rings (a uniformly or slowly curved surface) the result
 * is 0 and there is no flow; on a blurred crease the minimum is that of the
 * flat sides (near 0) and the peak stays.
 */
void CurvatureContrast(const TriangleMesh& mesh, const std::vector<unsigned char>& validPoint,
  std::vector<double>& potential, double contrast, int rings, int threads);

} // namespace shock

#endif
