#include "GridShockAdvection.h"
#include "GridAdvect.h"
#include "GridFlow.h"
#include "GridHierarchy.h"
#include "GridTrace.h"
#include "Timer.h"

#include <limits>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace shock
{

namespace
{

using namespace grid;

/// The flow of the current signal, on range-normalised intensities, timed into the
/// report. After the last update's flow, the fields are exported and the
/// workspace released (only the velocity is needed from there on).
template <int D, typename S>
void ComputeFlow(const Lattice<D>& L, FlowComputation<D>& flow, const S& signal, double range,
  bool last, GridFlowFields* fields, AdvectionReport& report)
{
  const auto flowStart = Clock::now();
  flow.Compute(signal, range);
  report.flowSeconds += SecondsSince(flowStart);
  if (last)
  {
    if (fields)
    {
      ExportFlowFields<D>(L, flow, *fields);
    }
    flow.ReleaseWorkspace();
  }
}

/// The advection of one flow update (Appendix A AdvectVertices), timed into the
/// report; false when aborted.
template <int D, typename S>
bool AdvectUpdate(const AdvectionContext<D>& ctx, const FlowComputation<D>& flow,
  const AdvectionParameters& p, double stepTime, const S& source, const SampleWriter& target,
  float* positions, const RowBlocks<D>& blocks, double progressStart, double progressSpan)
{
  const auto advectStart = Clock::now();
  const GridTracer<D> tracer(ctx.L, flow.Velocity(), p);
  const bool completed = AdvectVertices<D>(
    ctx, tracer, stepTime, source, target, positions, blocks, progressStart, progressSpan);
  ctx.report.advectionSeconds += SecondsSince(advectStart);
  return completed;
}

/// A writer into a double buffer of the whole signal.
SampleWriter BufferWriter(double* buffer, int C)
{
  return [buffer, C](std::int64_t first, std::int64_t count, const double* values) {
    std::copy(values, values + count * C, buffer + first * C);
  };
}

/**
 * The flow updates of one run (Appendix A: the flow, then AdvectVertices, per
 * update). A Fixed flow has one update; the Composed and Naive flows keep the
 * results of the updates before the last in double buffers (every sample), and
 * the last update hands the results of the written samples to the run's output.
 */
template <int D, typename S>
class FlowUpdates
{
public:
  FlowUpdates(const AdvectionContext<D>& ctx, FlowComputation<D>& flow, const GridShape& shape, int C,
    const S& input, const AdvectionParameters& p, double range, const CarriedSignal* carried, GridFlowFields* fields)
    : Ctx(ctx)
    , Flow(flow)
    , C(C)
    , Input(input)
    , P(p)
    , Range(range)
    , Carried(carried)
    , Fields(fields)
    , Naive(p.flowMode == FlowMode::Naive)
    , Updates(p.flowMode == FlowMode::Fixed ? 1 : std::max(1, p.flowUpdates))
    , StepTime(p.time / Updates)
    , Levels(PyramidShapes(shape, p.hierarchyLevels))
    , Everything(ctx.L.n)
    , Written(WrittenBlocks<D>(ctx.L, p.writtenSamples))
  {
    const std::int64_t count = ctx.L.numSamples * C;
    if (p.time > 0.0 && this->Updates > 1)
    {
      this->Work[0] = AllocateLargeArray<double>(count);
      if (this->Naive && this->Updates > 2)
      {
        this->Work[1] = AllocateLargeArray<double>(count);
      }
    }
    ctx.report.hierarchyLevels = static_cast<int>(this->Levels.size());
    // Stored trace positions: the Composed flow's, and the coarse-to-fine traces'.
    if (p.time > 0.0 && (p.flowMode == FlowMode::Composed || this->Levels.size() > 1))
    {
      this->Positions = InitialTracePositions<D>(ctx.L, ctx.threads);
    }
  }

  /// Every update in turn, the last into `output`; false when aborted.
  bool Run(const SampleWriter& output)
  {
    for (int k = 0; k < this->Updates; ++k)
    {
      const bool last = k == this->Updates - 1;
      this->WithSignal([&](const auto& signal) {
        ComputeFlow<D>(this->Ctx.L, this->Flow, signal, this->Range, last, this->Fields, this->Ctx.report);
      });
      const double progressStart = (k + 0.1) / this->Updates;
      if (this->Ctx.progress && !this->Ctx.progress(progressStart))
      {
        return false;
      }
      if (!(this->P.time > 0.0))
      {
        continue; // t = 0 gives the input, exactly (the flow fields may still be wanted)
      }
      if (this->Levels.size() > 1 && !this->TraceCoarseLevels(k, progressStart))
      {
        return false;
      }
      // Fixed and Composed flows sample the input (Composed from the composed
      // positions, its result feeding the next flow); Naive resamples the last result.
      double* buffer = last ? nullptr : this->Work[this->Naive ? k % 2 : 0].get();
      if (!this->Advect(buffer ? BufferWriter(buffer, this->C) : output, last ? this->Written : this->Everything,
            progressStart))
      {
        return false;
      }
      this->Previous = buffer;
    }
    return true;
  }

private:
  /// Calls `step` with the signal of this update: the input (T) or the last result (double).
  template <typename Step>
  void WithSignal(Step&& step)
  {
    if (this->Previous)
    {
      step(this->Previous);
    }
    else
    {
      step(this->Input);
    }
  }

  /// Coarse-to-fine (GridHierarchy.h): the traces cross the coarser levels first;
  /// a Naive step starts them afresh, as it does without levels.
  bool TraceCoarseLevels(int k, double progressStart)
  {
    if (this->Naive && k > 0)
    {
      this->Positions = InitialTracePositions<D>(this->Ctx.L, this->Ctx.threads);
    }
    bool completed = false;
    this->WithSignal([&](const auto& signal) {
      if constexpr (IsOneArray<decltype(signal)>) // a layered signal has no coarser levels (AdvectLayered)
      {
        completed = TraceThroughCoarseLevels<D>(this->Levels, this->C, signal, this->Range, this->Ctx.valid,
          this->P, this->StepTime, this->Positions.get(), this->Ctx.report, this->Ctx.progress, progressStart);
      }
    });
    return completed;
  }

  /// The advection of this update's source (the input, the carried signal, or the Naive flow's last result).
  bool Advect(const SampleWriter& target, const RowBlocks<D>& blocks, double progressStart)
  {
    const double span = 0.9 / this->Updates;
    float* positions = this->Positions.get();
    if (this->Carried)
    {
      return AdvectUpdate<D>(this->Ctx, this->Flow, this->P, this->StepTime, this->Carried->values, target,
        positions, blocks, progressStart, span);
    }
    if (this->Naive && this->Previous)
    {
      return AdvectUpdate<D>(this->Ctx, this->Flow, this->P, this->StepTime, this->Previous, target, positions,
        blocks, progressStart, span);
    }
    return AdvectUpdate<D>(
      this->Ctx, this->Flow, this->P, this->StepTime, this->Input, target, positions, blocks, progressStart, span);
  }

  const AdvectionContext<D>& Ctx; ///< its C: the advected signal's components (the carried signal's, if any)
  FlowComputation<D>& Flow;
  const int C; ///< the input signal's components, which the flow and the coarse levels read
  const S Input; ///< one array, or LayeredValues (GridLayered.h)
  const AdvectionParameters& P;
  const double Range;
  const CarriedSignal* Carried;
  GridFlowFields* Fields;
  const bool Naive;
  const int Updates;
  const double StepTime;
  const std::vector<GridShape> Levels;
  const RowBlocks<D> Everything;
  const RowBlocks<D> Written; ///< the samples the run hands to its output
  std::array<LargeArray<double>, 2> Work;
  LargeArray<float> Positions;
  const double* Previous = nullptr; ///< the last update's result; null: the input
};

/**
 * The grid run on a signal stored as T (float, double or 8-bit): the signal's
 * range, the masks of its finite samples and faces, then the flow updates.
 */
template <int D, typename S>
Status RunGrid(const GridShape& shape, int C, const S& input, const SampleWriter& output,
  const AdvectionParameters& p, AdvectionReport& report, GridFlowFields* fields,
  const ProgressFunction& progress, const CarriedSignal* carried = nullptr)
{
  const Lattice<D> L(shape);
  const int threads = ThreadsForWork(p.numberOfThreads, L.numSamples);
  const SignalRange scan = ScanSignal(L.numSamples, C, input, threads);
  const double range = p.valueScale > 0.0 ? p.valueScale : scan.high - scan.low;
  if (range == std::numeric_limits<double>::infinity())
  {
    return { ValueSpanError(scan.low, scan.high) };
  }
  if (fields)
  {
    ZeroFlowFields(L.numSamples, L.numFaces, *fields);
  }
  // What the traces sample and hand to `output`: the input, or the carried signal.
  const RowBlocks<D> written = WrittenBlocks<D>(L, p.writtenSamples);
  const auto writeUnchanged = [&] {
    if (carried)
    {
      WriteSignal<D>(L, written, carried->components, carried->values, output, threads);
    }
    else
    {
      WriteSignal<D>(L, written, C, input, output, threads);
    }
  };
  if (!(range > 0.0) || !std::isfinite(range))
  {
    writeUnchanged();
    return {}; // constant (or entirely non-finite) signal: no flow
  }
  const ValidityMasks<D> masks(L, C, input, scan.allFinite, threads);
  FlowComputation<D> flow(L, C, p.smoothingPasses, masks.Samples(), masks.Faces(), threads);
  if (fields)
  {
    flow.KeepPotential();
  }
  const AdvectionContext<D> ctx{ L, carried ? carried->components : C, threads, p.sampling, masks.Samples(),
    progress, report };
  FlowUpdates<D, S> updates(ctx, flow, shape, C, input, p, range, carried, fields);
  report.aborted = !updates.Run(output);
  if (report.aborted || !(p.time > 0.0))
  {
    writeUnchanged();
  }
  return {};
}

/// The checks and the dispatch on the number of active axes of AdvectGridSignal.
template <typename S>
Status AdvectGrid(const GridShape& shape, int components, const S& input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress,
  const CarriedSignal* carried = nullptr)
{
  const Status valid = CheckGridRun(shape, components, input, output, parameters);
  if (!valid.Ok())
  {
    return valid;
  }
  if (carried)
  {
    if (!carried->values || carried->components < 1)
    {
      return { "the carried signal must be non-null, with at least one component" };
    }
    if (parameters.flowMode != FlowMode::Fixed)
    {
      return { "a carried signal follows the fixed flow only (FlowMode Fixed)" };
    }
  }

  AdvectionReport localReport;
  AdvectionReport& r = report ? *report : localReport;
  r = AdvectionReport();
  switch (shape.ActiveAxes())
  {
    case 1:
      return RunGrid<1>(
        shape, components, input, output, parameters, r, fields, progress, carried);
    case 2:
      return RunGrid<2>(
        shape, components, input, output, parameters, r, fields, progress, carried);
    case 3:
      return RunGrid<3>(
        shape, components, input, output, parameters, r, fields, progress, carried);
    default:
      // A single sample has no faces, hence no flow.
      if (carried)
      {
        WriteSignal(shape.NumberOfSamples(), carried->components, carried->values, output, 1);
      }
      else if constexpr (IsOneArray<S>) // (a layered signal spans an axis: AdvectLayered)
      {
        WriteSignal(shape.NumberOfSamples(), components, input, output, 1);
      }
      if (fields)
      {
        ZeroFlowFields(shape.NumberOfSamples(), shape.NumberOfFaces(), *fields);
      }
      return {};
  }
}

/**
 * AdvectGridSignal on a LayeredSignal: its arrays checked against the grid and
 * read as LayeredValues (GridLayered.h).
 */
template <typename T>
Status AdvectLayered(const GridShape& shape, int components, const LayeredSignal<T>& input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  const Status arguments = CheckGridShape(shape, components);
  if (!arguments.Ok())
  {
    return arguments;
  }
  // The layers: along the grid's last axis of more than one sample.
  int axis = -1;
  std::int64_t layerSamples = 1;
  for (int a = 0; a < 3; ++a)
  {
    if (shape.dimensions[a] > 1)
    {
      axis = a;
    }
  }
  if (axis < 0)
  {
    return { "a layered signal needs a grid with more than one sample" };
  }
  for (int a = 0; a < axis; ++a)
  {
    layerSamples *= shape.dimensions[a];
  }
  const std::int64_t n = shape.dimensions[axis];
  const std::int64_t first = input.pieceFirst;
  const std::int64_t end = input.pieceEnd;
  if (!(0 <= first && first < end && end <= n) || !input.piece || (first > 0) != (input.below != nullptr) ||
    (end < n) != (input.above != nullptr))
  {
    return { "the layered signal's piece (layers " + std::to_string(first) + " to " + std::to_string(end) +
      " of " + std::to_string(n) + ") must be within the grid, with an array below it exactly when it does "
      "not start at layer 0 and one above it exactly when it does not end at the last" };
  }
  if (parameters.hierarchyLevels > 1)
  {
    return { "a layered signal is advected without coarser levels (hierarchyLevels 1)" };
  }
  const std::int64_t layerValues = layerSamples * components;
  constexpr std::int64_t O = LayeredSignalOverlap;
  grid::LayeredValues<T> values;
  values.below = input.below; // from layer 0
  values.piece = input.piece - first * layerValues;
  values.above = input.above ? input.above - std::max<std::int64_t>(end - O, 0) * layerValues : nullptr;
  values.low = first > 0 ? first * layerSamples : 0;
  values.high = std::max(values.low, end < n ? (end - O) * layerSamples : n * layerSamples);
  return AdvectGrid(shape, components, values, output, parameters, report, fields, progress);
}

} // namespace

Status AdvectGridSignal(const GridShape& shape, int components, const LayeredSignal<float>& input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  return AdvectLayered(shape, components, input, output, parameters, report, fields, progress);
}

Status AdvectGridSignal(const GridShape& shape, int components, const LayeredSignal<double>& input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  return AdvectLayered(shape, components, input, output, parameters, report, fields, progress);
}

Status AdvectGridSignal(const GridShape& shape, int components, const LayeredSignal<unsigned char>& input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  return AdvectLayered(shape, components, input, output, parameters, report, fields, progress);
}

Status AdvectGridSignal(const GridShape& shape, int components, const double* input,
  double* output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  if (output && input == output)
  {
    return { "input and output must be distinct, non-null buffers" };
  }
  return AdvectGrid(shape, components, input,
    output ? BufferWriter(output, components) : SampleWriter(), parameters, report, fields,
    progress);
}

Status AdvectGridSignal(const GridShape& shape, int components, const float* input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  return AdvectGrid(shape, components, input, output, parameters, report, fields, progress);
}

Status AdvectGridSignal(const GridShape& shape, int components, const double* input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  return AdvectGrid(shape, components, input, output, parameters, report, fields, progress);
}

Status AdvectGridSignal(const GridShape& shape, int components, const unsigned char* input,
  const SampleWriter& output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  return AdvectGrid(shape, components, input, output, parameters, report, fields, progress);
}

template <typename T>
Status AdvectCarriedGridSignal(const GridShape& shape, int components, const T* input,
  const CarriedSignal& carried, const SampleWriter& output, const AdvectionParameters& parameters,
  AdvectionReport* report, GridFlowFields* fields, const ProgressFunction& progress)
{
  return AdvectGrid(
    shape, components, input, output, parameters, report, fields, progress, &carried);
}

template Status AdvectCarriedGridSignal(const GridShape&, int, const double*, const CarriedSignal&,
  const SampleWriter&, const AdvectionParameters&, AdvectionReport*, GridFlowFields*,
  const ProgressFunction&);
template Status AdvectCarriedGridSignal(const GridShape&, int, const float*, const CarriedSignal&,
  const SampleWriter&, const AdvectionParameters&, AdvectionReport*, GridFlowFields*,
  const ProgressFunction&);
template Status AdvectCarriedGridSignal(const GridShape&, int, const unsigned char*,
  const CarriedSignal&, const SampleWriter&, const AdvectionParameters&, AdvectionReport*,
  GridFlowFields*, const ProgressFunction&);

int GridStencilLayers(const AdvectionParameters& parameters)
{
  if ((parameters.flowMode != FlowMode::Fixed && parameters.flowUpdates > 1) || parameters.hierarchyLevels > 1)
  {
    return -1;
  }
  // Face c's flow (GridFlow.h: FlowComputation::Halo) is the gradient of the
  // smoothed potential at its corners c and c + 1; the potential of a sample
  // averages the energy of its faces, read from the smoothed signal at their
  // corners; each smoothing pass reads one sample further: samples
  // c - (2P + 1) .. c + 1 + (2P + 1). A trace that reached r faces beyond the
  // faces beside the written samples reads samples r + 2P + 2 beyond them.
  return 2 * std::max(0, parameters.smoothingPasses) + 2;
}

} // namespace shock
