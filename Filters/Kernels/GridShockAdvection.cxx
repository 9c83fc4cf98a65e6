#include "GridShockAdvection.h"
#include "GridAdvect.h"
#include "GridFlow.h"
#include "GridHierarchy.h"
#include "GridTrace.h"
#include "Timer.h"

#include <omp.h>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>

namespace shock
{

int ResolveThreadCount(int requested)
{
  return requested > 0 ? requested : std::max(1, omp_get_num_procs());
}

void ParallelFor(std::int64_t count, int threads,
  const std::function<void(std::int64_t begin, std::int64_t end)>& body)
{
#pragma omp parallel num_threads(ResolveThreadCount(threads))
  {
    const std::int64_t thread = omp_get_thread_num();
    const std::int64_t team = omp_get_num_threads();
    const std::int64_t begin = count * thread / team;
    const std::int64_t end = count * (thread + 1) / team;
    if (begin < end)
    {
      body(begin, end);
    }
  }
}

#ifdef __linux__
namespace
{
constexpr std::size_t HugePage = std::size_t(2) << 20;

std::size_t HugePageMultiple(std::size_t bytes)
{
  return (bytes + HugePage - 1) / HugePage * HugePage;
}
}
#endif

void* AllocateLarge(std::size_t bytes)
{
#ifdef __linux__
  if (bytes >= HugePage)
  {
    // Map a huge page more than needed, then unmap the unaligned head and the tail.
    const std::size_t size = HugePageMultiple(bytes);
    void* mapped =
      mmap(nullptr, size + HugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED)
    {
      throw std::bad_alloc();
    }
    char* const first = static_cast<char*>(mapped);
    const std::size_t misalignment = reinterpret_cast<std::uintptr_t>(first) % HugePage;
    char* const block = first + (misalignment > 0 ? HugePage - misalignment : 0);
    char* const last = first + size + HugePage;
    if (block > first)
    {
      munmap(first, static_cast<std::size_t>(block - first));
    }
    if (last > block + size)
    {
      munmap(block + size, static_cast<std::size_t>(last - (block + size)));
    }
    // Advice only: without transparent huge pages the block simply has small pages.
    madvise(block, size, MADV_HUGEPAGE);
    return block;
  }
#endif
  void* block = std::malloc(std::max<std::size_t>(bytes, 1));
  if (!block)
  {
    throw std::bad_alloc();
  }
  return block;
}

void FreeLarge(void* block, std::size_t bytes) noexcept
{
#ifdef __linux__
  if (bytes >= HugePage)
  {
    munmap(block, HugePageMultiple(bytes));
    return;
  }
#endif
  std::free(block);
}

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

template <int D>
Status RunGrid(const GridShape& shape, int C, const double* input, double* output,
  const AdvectionParameters& p, AdvectionReport& report, GridFlowFields* fields,
  const ProgressFunction& progress)
{
  const Lattice<D> L(shape);
  const int threads = ResolveThreadCount(p.numberOfThreads);
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

  // Validity masks only when some sample is not finite; null pointers mean all valid.
  std::vector<unsigned char> validSamples, validFaces;
  if (!scan.allFinite)
  {
    validSamples = FiniteSamples(L.numSamples, C, input, threads);
    validFaces = ValidFaces<D>(L, validSamples.data(), threads);
  }
  const unsigned char* validSample = scan.allFinite ? nullptr : validSamples.data();
  const unsigned char* validFace = scan.allFinite ? nullptr : validFaces.data();

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
  FlowComputation<D> flow(L, C, p.smoothingPasses, validSample, validFace, threads);
  const AdvectionContext<D> ctx{ L, C, threads, p.sampling, validSample, progress, report };

  const double* signal = input; // the signal whose flow is computed
  for (int k = 0; k < updates; ++k)
  {
    // Flow of the current signal, on range-normalised intensities.
    const auto flowStart = Clock::now();
    flow.Compute(signal, range);
    report.flowSeconds += SecondsSince(flowStart);

    if (fields && k == updates - 1)
    {
      ExportFlowFields<D>(L, flow, *fields);
    }
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

    const auto advectStart = Clock::now();
    const GridTracer<D> tracer(L, flow.Velocity(), p);
    // Fixed and Composed flows sample the input (Composed from the composed
    // positions, its result feeding the next flow); Naive resamples the last result.
    const bool naive = p.flowMode == FlowMode::Naive;
    const double* source = naive ? signal : input;
    double* target = naive && (updates - 1 - k) % 2 == 1 ? naiveBuffer.get() : output;
    const bool completed = AdvectVertices<D>(
      ctx, tracer, stepTime, source, target, positions.get(), progressStart, 0.9 / updates);
    report.advectionSeconds += SecondsSince(advectStart);
    if (!completed)
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
