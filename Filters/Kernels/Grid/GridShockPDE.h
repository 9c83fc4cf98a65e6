/**
 * @file GridShockPDE.h
 * @brief The Osher-Rudin shock-filter PDE on regular grids: the explicit
 * upwind/minmod baseline that the advection of GridShockAdvection.h replaces.
 *
 * Solves equation (1) of Prada and Kazhdan (2015),
 *
 *     dI/dt = -|grad I| F(L(I)),
 *
 * with F the identity and L the second derivative along the gradient
 * direction, scaled as in the paper's derivation of equation (2):
 * L = <H grad I, grad I> / |grad I| = |grad I| I_nn. Then the PDE is exactly
 * equation (2), dI/dt = -1/2 <grad |grad I|^2, grad I>, whose solution the
 * advection approximates, so that both methods take the same flow time t for
 * the same result. H grad I = 1/2 grad P is the advection's flow u, computed by
 * the same code (umbrella smoothing, face gradients, potential P, smoothing of
 * P), so SmoothingPasses also means the same for both; with 0 passes this is
 * Osher and Rudin's scheme with F = identity. Several channels share u, as the
 * advection couples them: channel j moves with speed F_j = <u, grad I_j> / |grad I_j|.
 *
 * Discretisation (Osher and Rudin 1990): per step, |grad I_j| from the minmod
 * of the one-sided differences on every axis (zero at extrema, so extrema keep
 * their values), grad I_j for F_j from central differences, u at a sample the
 * mean of its adjacent faces' flows, and a forward Euler step
 * I <- I - dt |grad I_j|_minmod F_j with the CFL step
 * dt = courantNumber / (max_faces |u| x sum over axes of 1 / h). Grid
 * boundaries are reflecting (the difference across them is zero). The flow is
 * recomputed at every step, so the cost is linear in t; dt shrinks as edges
 * sharpen, which is why the PDE is slow to reach its steady state (paper
 * Figure 9).
 *
 * Units and normalisation are those of AdvectGridSignal: intensities divided by
 * the data range (or valueScale), lengths by the mean edge length. Non-finite
 * samples keep their value, carry no flow and act as boundaries.
 */
#ifndef GridShockPDE_h
#define GridShockPDE_h

#include "GridShockAdvection.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace shock
{

/// Parameters of one run of the shock-filter PDE.
struct PDEParameters
{
  /// Flow time t (>= 0, finite), normalised units as AdvectionParameters::time.
  double time = 0.0;
  /// Umbrella-smoothing passes before each of the two gradient computations of the flow (>= 0).
  int smoothingPasses = 1;
  /// Courant number of the explicit step, in (0, 1]; 0.5 is the classic safe choice.
  double courantNumber = 0.5;
  /// Step cap (>= 1): the run stops there, short of t, and says so in the report.
  std::int64_t maximumIterations = 100000;
  /// OpenMP threads; 0 uses all available cores.
  int numberOfThreads = 0;
  /// Intensity scale; 0 uses the data range (see AdvectionParameters::valueScale).
  double valueScale = 0.0;
  /// Optional increasing times in (0, time] at which `checkpoint` sees the solution;
  /// steps are shortened to land on them exactly.
  std::vector<double> checkpointTimes;
};

/// What a PDE run did.
struct PDEReport
{
  double flowSeconds = 0.0;     ///< smoothing, potential and flow, all steps
  double updateSeconds = 0.0;   ///< CFL bound and Euler updates, all steps
  std::int64_t iterations = 0;  ///< explicit steps taken
  double reachedTime = 0.0;     ///< flow time reached (== time unless stopped early)
  double smallestStep = 0.0;    ///< smallest CFL step (not counting steps cut at checkpoints)
  double largestStep = 0.0;     ///< largest CFL step
  bool steadyState = false;     ///< stopped early: a step changed no value by more than 1e-12 of the range
  bool iterationLimit = false;  ///< stopped at maximumIterations, short of time
  bool aborted = false;         ///< the progress callback asked to stop
};

/**
 * Called at each checkpoint time with the solution there (input units, layout of
 * the input) and the seconds of computation spent so far (callbacks excluded).
 */
using PDECheckpointFunction =
  std::function<void(double time, double computeSeconds, const double* values)>;

/// Check the ranges documented in PDEParameters; an empty Status when valid.
Status CheckPDEParameters(const PDEParameters& parameters);

/**
 * Integrate the shock-filter PDE for flow time parameters.time.
 *
 * Arguments as AdvectGridSignal. `fields`, when given, receives the potential
 * and flow of the last step. When aborted, output holds the input.
 */
Status SolveGridShockPDE(const GridShape& shape, int components, const double* input,
  double* output, const PDEParameters& parameters, PDEReport* report = nullptr,
  GridFlowFields* fields = nullptr, const ProgressFunction& progress = ProgressFunction(),
  const PDECheckpointFunction& checkpoint = PDECheckpointFunction());

} // namespace shock

#endif
