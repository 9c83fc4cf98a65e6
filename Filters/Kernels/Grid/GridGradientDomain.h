/**
 * @file GridGradientDomain.h
 * @brief Gradient-domain shock filtering of images and volumes: the future work
 * of section 6 of Prada and Kazhdan (2015), "flow signal gradients, rather than
 * values".
 *
 * The signal's gradients are carried along the shock filter's own flow (the
 * flow of the values, steps 1-3 of GridShockAdvection.h, traced with the same
 * unconditionally stable trace-and-sample of Appendix A), and integrated back
 * into a signal with a screened Poisson solve. Four named steps
 * (GridGradientDomain.cxx), in normalised units (lengths in mean edge lengths):
 *
 *  1. CarriedDifferences: every sample carries its value and, per axis, its
 *     forward and backward differences F_a(s) = I(s + e_a) - I(s),
 *     B_a(s) = I(s) - I(s - e_a) (0 past the border).
 *  2. The carried signal is advected along the flow of I
 *     (AdvectCarriedGridSignal): V = I o Phi, and F_a o Phi, B_a o Phi, where
 *     Phi is the back-trace of Appendix A (its samples averaged over the
 *     traces from each adjacent face).
 *  3. TargetGradients, per grid edge (s, s + e_a). Two transforms of a
 *     gradient under the advection map compete:
 *       - covariant, grad(I o Phi) = DPhi^T (grad I o Phi): the difference of V
 *         across the edge. Where the map stretches (across the edges the flow
 *         converges on) this is the shock's sharpening; where it compresses
 *         (between edges) it flattens the signal: the posterised look;
 *       - transported, grad I o Phi without the Jacobian: the mean of the
 *         edge's two carried differences, F_a(Phi(s)) and B_a(Phi(s + e_a)).
 *         It never exceeds the input's gradients and keeps the shading that
 *         the compression removes.
 *     The target is the longer of the two (summed over channels): the map's
 *     stretch is kept, its compression is not. At t = 0 both equal the
 *     input's difference, so the result is the input.
 *  4. ScreenedPoisson: the signal J minimising
 *       sum over edges |J(s + e_a) - J(s) - g|^2 / h_a^2 + lambda sum over samples |J - I|^2
 *     (h_a the spacing in mean edge lengths, lambda the screening weight),
 *     solved exactly with the discrete cosine transform (through Eigen's
 *     FFT), which diagonalises the grid Laplacian with Neumann borders:
 *     O(N log N).
 */
#ifndef GridGradientDomain_h
#define GridGradientDomain_h

#include "GridShockAdvection.h"

namespace shock
{

/// The gradient domain's own parameter.
struct GradientDomainParameters
{
  /// Screening weight lambda of step 4 (> 0, finite), per squared mean edge
  /// length: the input's structure longer than about 1/sqrt(lambda) edges is kept.
  double screening = 0.01;
};

/**
 * Gradient-domain shock filter of a grid signal (steps 1-4 above).
 *
 * @param shape, components, input  as AdvectGridSignal; every value must be
 *                  finite (the Poisson solve couples every sample).
 * @param output    receives the filtered signal (see SampleWriter).
 * @param parameters  as AdvectGridSignal; the flow must be FlowMode::Fixed.
 * @param domain    the screening weight.
 * @param report    optional: timings (the solve in integrationSeconds).
 * @return an error message for invalid arguments; when aborted, output holds the input.
 * T is double, float or unsigned char.
 */
template <typename T>
Status AdvectGridGradients(const GridShape& shape, int components, const T* input,
  const SampleWriter& output, const AdvectionParameters& parameters,
  const GradientDomainParameters& domain, AdvectionReport* report = nullptr,
  GridFlowFields* fields = nullptr, const ProgressFunction& progress = ProgressFunction());

/**
 * Step 4 alone, for one channel: overwrites `rhs` (sample-major, x fastest)
 * with the solution J of (lambda + sum_a D_a^T D_a / h_a^2) J = rhs, where D_a
 * is the forward difference along axis a with Neumann borders and h_a =
 * `axisLength[a]` (axes of one sample are skipped). Exposed for its tests.
 */
Status SolveScreenedPoisson(const GridShape& shape, const double axisLength[3], double lambda,
  double* rhs, int threads);

} // namespace shock

#endif
