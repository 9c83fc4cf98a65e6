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

namespace shock
{

namespace
{

using namespace grid;

/// The flow of the current signal, on range-normalised intensities, timed into the
/// report. After the last update's flow, the fields are exported and the
/// workspace released (only the velocity is needed from there on).
template <int D, typename T>
void ComputeFlow(const Lattice<D>& L, FlowComputation<D>& flow, const T* signal, double range,
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
template <int D, typename T>
bool AdvectUpdate(const AdvectionContext<D>& ctx, const FlowComputation<D>& flow,
  const AdvectionParameters& p, double stepTime, const T* source, const SampleWriter& target,
  float* positions, double progressStart, double progressSpan)
{
  const auto advectStart = Clock::now();
  const GridTracer<D> tracer(ctx.L, flow.Velocity(), p);
  const bool completed = AdvectVertices<D>(
    ctx, tracer, stepTime, source, target, positions, progressStart, progressSpan);
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
 * The grid run on a signal stored as T (float, double or 8-bit). The updates before the
 * last (Composed and Naive flows) keep their results in double buffers; the
 * last update hands its results to `output`.
 */
template <int D, typename T>
Status RunGrid(const GridShape& shape, int C, const T* input, const SampleWriter& output,
  const AdvectionParameters& p, AdvectionReport& report, GridFlowFields* fields,
  const ProgressFunction& progress, const CarriedSignal* carried = nullptr)
{
  const Lattice<D> L(shape);
  const int threads = ThreadsForWork(p.numberOfThreads, L.numSamples);
  const std::int64_t count = L.numSamples * C;

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
  const auto writeUnchanged = [&] {
    if (carried)
    {
      WriteSignal(L.numSamples, carried->components, carried->values, output, threads);
    }
    else
    {
      WriteSignal(L.numSamples, C, input, output, threads);
    }
  };
  if (!(range > 0.0) || !std::isfinite(range))
  {
    writeUnchanged();
    return {}; // constant (or entirely non-finite) signal: no flow
  }

  const ValidityMasks<D> masks(L, C, input, scan.allFinite, threads);
  const unsigned char* validSample = masks.Samples();

  // t = 0 gives the input, exactly (the flow fields may still be wanted).
  const bool advect = p.time > 0.0;
  const bool naive = p.flowMode == FlowMode::Naive;
  const int updates = p.flowMode == FlowMode::Fixed ? 1 : std::max(1, p.flowUpdates);
  const double stepTime = p.time / updates;
  // Results of the updates before the last: the Composed flow's feed the next
  // flow; the Naive flow's are also resampled, alternating between two buffers.
  std::array<LargeArray<double>, 2> work;
  if (advect && updates > 1)
  {
    work[0] = AllocateLargeArray<double>(count);
    if (naive && updates > 2)
    {
      work[1] = AllocateLargeArray<double>(count);
    }
  }
  // Stored trace positions: the Composed flow's, and the coarse-to-fine traces'.
  const std::vector<GridShape> levels = PyramidShapes(shape, p.hierarchyLevels);
  report.hierarchyLevels = static_cast<int>(levels.size());
  LargeArray<float> positions;
  if (advect && (p.flowMode == FlowMode::Composed || levels.size() > 1))
  {
    positions = InitialTracePositions<D>(L, threads);
  }
  FlowComputation<D> flow(L, C, p.smoothingPasses, validSample, masks.Faces(), threads);
  if (fields)
  {
    flow.KeepPotential();
  }
  const AdvectionContext<D> ctx{ L, carried ? carried->components : C, threads, p.sampling,
    validSample, progress, report };

  const double* previous = nullptr; // the last update's result; null: the input
  // Calls `step` with the signal of this update: the input (T) or the last result (double).
  const auto withSignal = [&](auto&& step) { return previous ? step(previous) : step(input); };
  for (int k = 0; k < updates; ++k)
  {
    const bool last = k == updates - 1;
    withSignal([&](auto signal) { ComputeFlow<D>(L, flow, signal, range, last, fields, report); });
    const double progressStart = (k + 0.1) / updates;
    if (progress && !progress(progressStart))
    {
      report.aborted = true;
      break;
    }
    if (!advect)
    {
      continue;
    }
    if (levels.size() > 1)
    {
      // Coarse-to-fine (GridHierarchy.h): the traces cross the coarser levels first;
      // a Naive step starts them afresh, as it does without levels.
      if (naive && k > 0)
      {
        positions = InitialTracePositions<D>(L, threads);
      }
      const bool completed = withSignal([&](auto signal) {
        return TraceThroughCoarseLevels<D>(levels, C, signal, range, validSample, p, stepTime,
          positions.get(), report, progress, progressStart);
      });
      if (!completed)
      {
        report.aborted = true;
        break;
      }
    }

    // Fixed and Composed flows sample the input (Composed from the composed
    // positions, its result feeding the next flow); Naive resamples the last result.
    double* buffer = last ? nullptr : work[naive ? k % 2 : 0].get();
    const SampleWriter target = buffer ? BufferWriter(buffer, C) : output;
    const bool completed = carried
      ? AdvectUpdate<D>(ctx, flow, p, stepTime, carried->values, target, positions.get(),
          progressStart, 0.9 / updates)
      : naive && previous
      ? AdvectUpdate<D>(ctx, flow, p, stepTime, previous, target, positions.get(), progressStart,
          0.9 / updates)
      : AdvectUpdate<D>(ctx, flow, p, stepTime, input, target, positions.get(), progressStart,
          0.9 / updates);
    if (!completed)
    {
      report.aborted = true;
      break;
    }
    previous = buffer;
  }

  if (report.aborted || !advect)
  {
    writeUnchanged();
  }
  return {};
}

/// The checks and the dispatch on the number of active axes of AdvectGridSignal.
template <typename T>
Status AdvectGrid(const GridShape& shape, int components, const T* input,
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
      else
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

} // namespace

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

} // namespace shock
