#include "GridShockAdvection.h"
#include "GridAdvect.h"
#include "GridFlow.h"
#include "GridHierarchy.h"
#include "GridTrace.h"
#include "Timer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace shock
{

std::int64_t GridShape::NumberOfSamples() const
{
  return static_cast<std::int64_t>(this->dimensions[0]) * this->dimensions[1] *
    this->dimensions[2];
}

std::int64_t GridShape::NumberOfFaces() const
{
  std::int64_t faces = 1;
  for (int d : this->dimensions)
  {
    faces *= std::max(d - 1, 1);
  }
  return faces;
}

int GridShape::ActiveAxes() const
{
  return static_cast<int>(
    std::count_if(this->dimensions.begin(), this->dimensions.end(), [](int d) { return d > 1; }));
}

double GridShape::MeanEdgeLength() const
{
  // Edges along axis a: (n_a - 1) * product of the other dimensions.
  double edges = 0.0;
  double length = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    if (this->dimensions[a] < 2)
    {
      continue;
    }
    double count = this->dimensions[a] - 1.0;
    for (int b = 0; b < 3; ++b)
    {
      count *= (b == a) ? 1.0 : this->dimensions[b];
    }
    edges += count;
    length += count * this->spacing[a];
  }
  return edges > 0.0 ? length / edges : 0.0;
}

namespace
{

using namespace grid;

/// The flow of the current signal, on range-normalised intensities, timed into the
/// report. After the last update's flow, the fields are exported and the
/// workspace released (only the velocity is needed from there on).
template <int D>
void ComputeFlow(const Lattice<D>& L, FlowComputation<D>& flow, const double* signal,
  double range, bool last, GridFlowFields* fields, AdvectionReport& report)
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
template <int D>
bool AdvectUpdate(const AdvectionContext<D>& ctx, const FlowComputation<D>& flow,
  const AdvectionParameters& p, double stepTime, const double* source, double* target,
  float* positions, double progressStart, double progressSpan)
{
  const auto advectStart = Clock::now();
  const GridTracer<D> tracer(ctx.L, flow.Velocity(), p);
  const bool completed = AdvectVertices<D>(
    ctx, tracer, stepTime, source, target, positions, progressStart, progressSpan);
  ctx.report.advectionSeconds += SecondsSince(advectStart);
  return completed;
}

template <int D>
Status RunGrid(const GridShape& shape, int C, const double* input, double* output,
  const AdvectionParameters& p, AdvectionReport& report, GridFlowFields* fields,
  const ProgressFunction& progress)
{
  const Lattice<D> L(shape);
  const int threads = ThreadsForWork(p.numberOfThreads, L.numSamples);
  const std::int64_t count = L.numSamples * C;

  const SignalRange scan = ScanSignal(L.numSamples, C, input, threads);
  const double range = p.valueScale > 0.0 ? p.valueScale : scan.high - scan.low;
  if (fields)
  {
    ZeroFlowFields(L.numSamples, L.numFaces, *fields);
  }
  if (!(range > 0.0) || !std::isfinite(range))
  {
    std::copy(input, input + count, output);
    return {}; // constant (or entirely non-finite) signal: no flow
  }

  const ValidityMasks<D> masks(L, C, input, scan.allFinite, threads);
  const unsigned char* validSample = masks.Samples();

  // t = 0 gives the input, exactly (the flow fields may still be wanted).
  const bool advect = p.time > 0.0;
  const int updates = p.flowMode == FlowMode::Fixed ? 1 : std::max(1, p.flowUpdates);
  const double stepTime = p.time / updates;
  // Naive flow: the resampled signal alternates between this buffer and output,
  // arranged so that the last update writes output.
  LargeArray<double> naiveBuffer;
  if (advect && p.flowMode == FlowMode::Naive && updates > 1)
  {
    naiveBuffer = AllocateLargeArray<double>(count);
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
  const AdvectionContext<D> ctx{ L, C, threads, p.sampling, validSample, progress, report };

  const double* signal = input; // the signal whose flow is computed
  for (int k = 0; k < updates; ++k)
  {
    ComputeFlow<D>(L, flow, signal, range, k == updates - 1, fields, report);
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
      if (p.flowMode == FlowMode::Naive && k > 0)
      {
        positions = InitialTracePositions<D>(L, threads);
      }
      if (!TraceThroughCoarseLevels<D>(levels, C, signal, range, validSample, p, stepTime,
            positions.get(), report, progress, progressStart))
      {
        report.aborted = true;
        break;
      }
    }

    // Fixed and Composed flows sample the input (Composed from the composed
    // positions, its result feeding the next flow); Naive resamples the last result.
    const bool naive = p.flowMode == FlowMode::Naive;
    double* target = naive && (updates - 1 - k) % 2 == 1 ? naiveBuffer.get() : output;
    if (!AdvectUpdate<D>(ctx, flow, p, stepTime, naive ? signal : input, target, positions.get(),
          progressStart, 0.9 / updates))
    {
      report.aborted = true;
      break;
    }
    signal = target;
  }

  if (report.aborted || !advect)
  {
    std::copy(input, input + count, output);
  }
  return {};
}

} // namespace

Status AdvectGridSignal(const GridShape& shape, int components, const double* input,
  double* output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  const Status arguments = CheckGridArguments(shape, components, input, output);
  if (!arguments.Ok())
  {
    return arguments;
  }
  const Status valid = CheckAdvectionParameters(parameters);
  if (!valid.Ok())
  {
    return valid;
  }

  AdvectionReport localReport;
  AdvectionReport& r = report ? *report : localReport;
  r = AdvectionReport();
  switch (shape.ActiveAxes())
  {
    case 1:
      return RunGrid<1>(shape, components, input, output, parameters, r, fields, progress);
    case 2:
      return RunGrid<2>(shape, components, input, output, parameters, r, fields, progress);
    case 3:
      return RunGrid<3>(shape, components, input, output, parameters, r, fields, progress);
    default:
      // A single sample has no faces, hence no flow.
      std::copy(input, input + shape.NumberOfSamples() * components, output);
      if (fields)
      {
        ZeroFlowFields(shape.NumberOfSamples(), shape.NumberOfFaces(), *fields);
      }
      return {};
  }
}

} // namespace shock
