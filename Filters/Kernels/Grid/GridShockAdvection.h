/**
 * @file GridShockAdvection.h
 * @brief Shock-filter advection of multi-channel signals on regular 1D, 2D and 3D grids.
 *
 * Implements section 3 and Appendix A of Prada and Kazhdan (2015) on a grid whose
 * vertices are the samples and whose faces are the segments (1D), squares (2D) or
 * cubes (3D) between adjacent samples:
 *
 *  1. umbrella-smooth the signal with Gaussian weights exp(-|(v-w)/l|^2);
 *  2. face gradients = average of the finite differences on the face's parallel edges;
 *     the potential at a sample is the average of |grad I|^2 (summed over channels)
 *     over its adjacent faces;
 *  3. umbrella-smooth the potential, flow per face u = 1/2 grad P;
 *  4. back-trace every sample along -u (Appendix A Trace) from an offset into each
 *     adjacent face, sample the input there and average (Appendix A AdvectVertices).
 *
 * Intensities are normalised by the data range and lengths by the mean edge
 * length, so the same time t gives the same result whatever the value scale or
 * the (uniform) grid scale. Non-finite samples (NaN, inf) keep their value and do
 * not spread: faces touching them carry no flow and they are never interpolated.
 *
 * Samples are stored x-fastest (VTK order), components interleaved.
 */
#ifndef GridShockAdvection_h
#define GridShockAdvection_h

#include "GridShape.h"
#include "ShockTypes.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace shock
{


/**
 * Run the shock filter on a grid signal.
 *
 * @param shape     grid shape; every spacing must be > 0.
 * @param components number of channels (>= 1), coupled through one flow.
 * @param input     NumberOfSamples() x components values, x-fastest, interleaved.
 * @param output    same size as input, written (must not alias input).
 * @param parameters see AdvectionParameters.
 * @param report    optional: timings and counters.
 * @param fields    optional: filled with the potential and flow of the last flow computation.
 * @param progress  optional: progress/abort callback.
 * @return an error message for invalid arguments; when aborted, output holds the input.
 */
Status AdvectGridSignal(const GridShape& shape, int components, const double* input,
  double* output, const AdvectionParameters& parameters, AdvectionReport* report = nullptr,
  GridFlowFields* fields = nullptr, const ProgressFunction& progress = ProgressFunction());

/**
 * AdvectGridSignal on a signal stored as float or double (read in place; the
 * computation is in double, so a float signal gives the result of its exact
 * double copy), results handed to `output` (see SampleWriter).
 */
Status AdvectGridSignal(const GridShape& shape, int components, const float* input,
  const SampleWriter& output, const AdvectionParameters& parameters,
  AdvectionReport* report = nullptr, GridFlowFields* fields = nullptr,
  const ProgressFunction& progress = ProgressFunction());
Status AdvectGridSignal(const GridShape& shape, int components, const double* input,
  const SampleWriter& output, const AdvectionParameters& parameters,
  AdvectionReport* report = nullptr, GridFlowFields* fields = nullptr,
  const ProgressFunction& progress = ProgressFunction());

/**
 * AdvectGridSignal on 8-bit samples (photographs), read in place: the result is
 * that of their exact float (or double) copy, without the copy's memory (4 or 8
 * bytes per value instead of 1) and with fewer cache misses in the sampling.
 */
Status AdvectGridSignal(const GridShape& shape, int components, const unsigned char* input,
  const SampleWriter& output, const AdvectionParameters& parameters,
  AdvectionReport* report = nullptr, GridFlowFields* fields = nullptr,
  const ProgressFunction& progress = ProgressFunction());

/// The layers of a piece that each array of a LayeredSignal also holds beside its own.
constexpr std::int64_t LayeredSignalOverlap = 2;

/**
 * A grid signal held in up to three arrays along the grid's last axis of more
 * than one sample (its layers 0 .. n-1): a piece of a distributed image where
 * it lies (layers [pieceFirst, pieceEnd)), and the halo that other processes
 * sent, below and above it. `below` (non-null exactly when pieceFirst > 0)
 * holds layers [0, min(pieceFirst + LayeredSignalOverlap, n)); `above`
 * (non-null exactly when pieceEnd < n) holds layers
 * [max(pieceEnd - LayeredSignalOverlap, 0), n). Each side array repeats the
 * piece's layers beside it, so that any LayeredSignalOverlap + 1 consecutive
 * layers lie in one array: every read of the advection (a cell's corners, a
 * sample's 3^D neighbourhood) then addresses one array, and the piece is not
 * copied. Values as in AdvectGridSignal: x fastest, components interleaved.
 */
template <typename T>
struct LayeredSignal
{
  const T* below = nullptr;
  const T* piece = nullptr;
  const T* above = nullptr;
  std::int64_t pieceFirst = 0;
  std::int64_t pieceEnd = 0;
};

/**
 * AdvectGridSignal on a LayeredSignal (float, double or 8-bit): the same
 * results, to the last bit, as on one array holding the same values. Not with
 * coarser levels (hierarchyLevels > 1).
 */
Status AdvectGridSignal(const GridShape& shape, int components, const LayeredSignal<float>& input,
  const SampleWriter& output, const AdvectionParameters& parameters,
  AdvectionReport* report = nullptr, GridFlowFields* fields = nullptr,
  const ProgressFunction& progress = ProgressFunction());
Status AdvectGridSignal(const GridShape& shape, int components, const LayeredSignal<double>& input,
  const SampleWriter& output, const AdvectionParameters& parameters,
  AdvectionReport* report = nullptr, GridFlowFields* fields = nullptr,
  const ProgressFunction& progress = ProgressFunction());
Status AdvectGridSignal(const GridShape& shape, int components,
  const LayeredSignal<unsigned char>& input, const SampleWriter& output,
  const AdvectionParameters& parameters, AdvectionReport* report = nullptr,
  GridFlowFields* fields = nullptr, const ProgressFunction& progress = ProgressFunction());

/// A signal that follows another's flow: `components` floats per sample, interleaved.
struct CarriedSignal
{
  const float* values = nullptr;
  int components = 0;
};

/**
 * The advection of `carried` along the flow of `input`: the flow (steps 1-3) is
 * computed from `input` (C = `components` channels) exactly as AdvectGridSignal
 * does, and the traces (step 4) sample `carried` instead of `input`, handing
 * carried.components values per sample to `output`. Samples where `input` is
 * not finite keep their carried values. Only the fixed flow (FlowMode::Fixed):
 * the other modes recompute the flow from advected values the carried signal
 * does not hold. Used by the gradient domain (GridGradientDomain.h).
 * T is double, float or unsigned char.
 */
template <typename T>
Status AdvectCarriedGridSignal(const GridShape& shape, int components, const T* input,
  const CarriedSignal& carried, const SampleWriter& output, const AdvectionParameters& parameters,
  AdvectionReport* report = nullptr, GridFlowFields* fields = nullptr,
  const ProgressFunction& progress = ProgressFunction());

/**
 * How many sample layers beyond a face its flow depends on, plus one: the
 * flow of a face reads the signal 2 x smoothingPasses + 1 samples beyond its
 * own corners (the signal's smoothing passes, the face energy, the potential's
 * average over a sample's faces, the potential's smoothing passes, its
 * gradient). On a piece of a larger grid with `h` samples of halo beyond its
 * written samples on a side (AdvectionParameters::writtenSamples), the result
 * of every written sample is the whole grid's when, on every side whose halo
 * does not end at the whole grid's boundary,
 * AdvectionReport::haloReach + GridStencilLayers <= h. -1 where the flow does
 * not stay the one of the input (FlowMode Composed or Naive with more than one
 * update) or the traces also follow coarser grids (hierarchyLevels > 1).
 */
int GridStencilLayers(const AdvectionParameters& parameters);

} // namespace shock

#endif
