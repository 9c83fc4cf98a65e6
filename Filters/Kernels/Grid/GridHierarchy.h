/**
 * @file GridHierarchy.h
 * @brief Coarse-to-fine tracing for the grid kernel: beyond the paper, after the
 * hierarchical extension its section 6 proposes.
 *
 * The paper's conclusion suggests, after coarse-to-fine optical flow [LK81],
 * "estimating the flow at coarser resolutions and using the low-resolution flow
 * for advecting at higher resolutions", so that traces may "jump over" the small
 * edges of the fine resolution and converge at larger silhouettes. On a grid:
 *
 *  1. A pyramid of the signal: level l+1 halves every active axis of level l
 *     (n' = ceil((n - 1) / 2) + 1 samples spanning the same extent) and its
 *     samples are read, multilinearly, from level l after umbrella smoothing
 *     (the paper's smoothing, as many passes as give a variance of about one
 *     sample squared, the anti-aliasing of a Burt-Adelson pyramid). What the
 *     flow needs comes along: the validity of the samples (non-finite values
 *     stay out), and the input's intensity range, which normalises every level.
 *  2. Every level computes its flow with the grid kernel's own FlowComputation
 *     (smoothing, potential, flow), lengths in that level's mean edge length, as
 *     the paper defines them on any mesh.
 *  3. Every back-trace of the finest level (a sample's offsets into its adjacent
 *     faces) starts at the coarsest level, is traced there with the grid
 *     kernel's tracer, and continues from where it arrived at each finer level;
 *     the finest level ends the trace and samples the input there, once.
 *
 * Flow time. Every level traces for the same flow time t in the input's units
 * (lengths in the input's mean edge length). The equation dI/dt = -<u, grad I>
 * with u = 1/2 grad |grad I|^2 is invariant under x -> lambda x, t -> lambda^4 t,
 * so a level whose edges are lambda times longer runs t / lambda^4 in its own
 * units. An edge blurred over sigma input samples then needs the same t (about
 * 10 sigma^4) at every level, with one level or many.
 */
#ifndef GridHierarchy_h
#define GridHierarchy_h

#include "GridShockAdvection.h"
#include "ShockTypes.h"

#include <vector>

namespace shock
{
namespace grid
{

/// The shapes of levels 0 (the input) to `requested` - 1, fewer when an active axis
/// would drop below 2 samples: a level is built while every active axis has >= 3.
std::vector<GridShape> PyramidShapes(const GridShape& fine, int requested);

/**
 * Steps 1-3 above for the levels coarser than shapes[0] (from PyramidShapes):
 * trace the stored positions of shapes[0] (D floats per sample and corner, in
 * its index coordinates: the layout of InitialTracePositions, GridAdvect.h)
 * through the levels shapes.size() - 1 down to 1, for flow time `time` (input
 * units) each. Only the finest level samples (AdvectVertices from the positions). `signal` is
 * the signal whose flow is wanted, `range` its intensity scale, `validSample`
 * null when every sample is finite; T is float, double or 8-bit. Returns false when
 * `progress` asks to stop.
 */
template <int D, typename T>
bool TraceThroughCoarseLevels(const std::vector<GridShape>& shapes, int C, const T* signal,
  double range, const unsigned char* validSample, const AdvectionParameters& p, double time,
  float* positions, AdvectionReport& report, const ProgressFunction& progress, double progressAt);

} // namespace grid
} // namespace shock

#endif
