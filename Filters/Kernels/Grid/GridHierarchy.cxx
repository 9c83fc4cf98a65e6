#include "GridHierarchy.h"
#include "GridFlow.h"
#include "GridLattice.h"
#include "GridTrace.h"
#include "Timer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace shock
{
namespace grid
{

std::vector<GridShape> PyramidShapes(const GridShape& fine, int requested)
{
  std::vector<GridShape> shapes{ fine };
  while (static_cast<int>(shapes.size()) < requested)
  {
    const GridShape& last = shapes.back();
    bool halvable = last.ActiveAxes() > 0;
    for (int a = 0; a < 3; ++a)
    {
      halvable = halvable && (last.dimensions[a] == 1 || last.dimensions[a] >= 3);
    }
    if (!halvable)
    {
      break;
    }
    GridShape coarse = last;
    coarse.wholeDimensions = { { 0, 0, 0 } }; // a coarse level is its own grid
    for (int a = 0; a < 3; ++a)
    {
      const int n = last.dimensions[a];
      if (n > 1)
      {
        coarse.dimensions[a] = (n - 1 + 1) / 2 + 1; // ceil((n - 1) / 2) + 1: the same extent
        coarse.spacing[a] = last.spacing[a] * (n - 1) / (coarse.dimensions[a] - 1);
      }
    }
    shapes.push_back(coarse);
  }
  return shapes;
}

namespace
{

/**
 * Umbrella-smoothing passes of the anti-aliasing before halving: a pass of the
 * Appendix A smoothing has variance 2 alpha_d / (1 + sum of the weights) along
 * axis d (index units, interior samples); enough passes for a variance of about
 * 1 along the best-smoothed axis, that of the Burt-Adelson 5-tap kernel.
 */
template <int D>
int PrefilterPasses(const Lattice<D>& L)
{
  double total = 1.0;
  double widest = 0.0;
  for (int d = 0; d < D; ++d)
  {
    total += 2.0 * std::exp(-L.h2[d]);
    widest = std::max(widest, std::exp(-L.h2[d]));
  }
  const double variance = 2.0 * widest / total;
  return std::max(1, std::min(16, static_cast<int>(std::ceil(1.0 / variance))));
}

/**
 * The coarser level's samples read multilinearly from the (smoothed) finer
 * level over its valid corners; NaN where no corner is valid.
 */
template <int D>
std::vector<double> Restrict(const Lattice<D>& fine, const Lattice<D>& coarse, int C,
  const double* values, const unsigned char* valid, int threads)
{
  std::vector<double> out(static_cast<size_t>(coarse.numSamples * C));
  std::array<double, D> ratio;
  for (int d = 0; d < D; ++d)
  {
    ratio[d] = static_cast<double>(fine.m[d]) / static_cast<double>(coarse.m[d]);
  }
  ForEachSampleBlock<D>(coarse, threads, [&](const auto& i, std::int64_t s0, std::int64_t length) {
    for (std::int64_t j = 0; j < length; ++j)
    {
      std::int64_t base = 0;
      std::array<double, D> frac;
      for (int d = 0; d < D; ++d)
      {
        const double q = static_cast<double>(d == 0 ? i[0] + j : i[d]) * ratio[d];
        const std::int64_t cell = std::min<std::int64_t>(static_cast<std::int64_t>(q), fine.m[d] - 1);
        frac[d] = q - static_cast<double>(cell);
        base += cell * fine.sampleStride[d];
      }
      double* o = out.data() + (s0 + j) * C;
      std::fill(o, o + C, 0.0);
      double total = 0.0;
      for (int b = 0; b < Lattice<D>::Corners; ++b)
      {
        double w = 1.0;
        for (int d = 0; d < D; ++d)
        {
          w *= ((b >> d) & 1) ? frac[d] : 1.0 - frac[d];
        }
        const std::int64_t s = base + fine.corner[b];
        if (w == 0.0 || (valid && !valid[s]))
        {
          continue; // 0 x NaN would be NaN
        }
        total += w;
        for (int c = 0; c < C; ++c)
        {
          o[c] += w * values[s * C + c];
        }
      }
      for (int c = 0; c < C; ++c)
      {
        o[c] = total > 0.0 ? o[c] / total : std::numeric_limits<double>::quiet_NaN();
      }
    }
  });
  return out;
}

/// Levels 1 .. shapes.size() - 1 of the signal pyramid (level 0 is `signal` itself).
template <int D, typename T>
std::vector<std::vector<double>> BuildPyramid(const std::vector<GridShape>& shapes, int C,
  const T* signal, const unsigned char* validSample, int threads)
{
  std::vector<std::vector<double>> levels;
  const unsigned char* valid = validSample;
  std::vector<unsigned char> levelValid;
  for (size_t l = 1; l < shapes.size(); ++l)
  {
    const Lattice<D> fine(shapes[l - 1]);
    const Lattice<D> coarse(shapes[l]);
    const int passes = PrefilterPasses(fine);
    std::vector<double> smoothed(static_cast<size_t>(fine.numSamples * C));
    std::vector<double> scratch(passes >= 2 ? smoothed.size() : 0);
    if (l == 1)
    {
      UmbrellaSmooth<D>(fine, C, signal, 1.0, smoothed.data(), scratch.data(), valid, passes, threads);
    }
    else
    {
      UmbrellaSmooth<D>(
        fine, C, levels.back().data(), 1.0, smoothed.data(), scratch.data(), valid, passes, threads);
    }
    levels.push_back(Restrict<D>(fine, coarse, C, smoothed.data(), valid, threads));
    const double* finer = levels.back().data();
    const ValidityMasks<D> masks(
      coarse, C, finer, ScanSignal(coarse.numSamples, C, finer, threads).allFinite, threads);
    levelValid = masks.samples;
    valid = levelValid.empty() ? nullptr : levelValid.data();
  }
  return levels;
}

/**
 * Trace `count` stored positions (D floats each, index coordinates of the finest
 * grid) along the back-trace velocity of lattice L for `time` (L's units): each
 * is mapped to L's index coordinates by `toLevel` (per axis), traced with the
 * grid kernel's tracer (p.tracing, p.stepFraction) and mapped back.
 */
template <int D>
void TraceStoredPositions(const Lattice<D>& L, const float* velocity,
  const AdvectionParameters& p, double time, const std::array<double, D>& toLevel,
  float* positions, std::int64_t count, int threads, AdvectionReport& report)
{
  const GridTracer<D> tracer(L, velocity, p);
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) reduction(+ : steps, truncated)
  for (std::int64_t r = 0; r < count; ++r)
  {
    float* stored = positions + r * D;
    std::array<double, D> q;
    for (int d = 0; d < D; ++d)
    {
      q[d] = std::min(std::max(stored[d] * toLevel[d], 0.0), static_cast<double>(L.m[d]));
    }
    const std::array<double, D> start = q;
    std::array<std::int64_t, D> c;
    const std::int64_t f = tracer.FaceOf(q, c);
    bool cut = false;
    steps += static_cast<std::uint64_t>(tracer.Trace(q, c, f, time, cut));
    truncated += cut ? 1 : 0;
    for (int d = 0; d < D; ++d)
    {
      if (q[d] != start[d]) // an unmoved trace keeps its stored position exactly
      {
        stored[d] = static_cast<float>(q[d] / toLevel[d]);
      }
    }
  }
  report.traceSteps += steps;
  report.truncatedTraces += truncated;
}

} // namespace

template <int D, typename T>
bool TraceThroughCoarseLevels(const std::vector<GridShape>& shapes, int C, const T* signal,
  double range, const unsigned char* validSample, const AdvectionParameters& p, double time,
  float* positions, AdvectionReport& report, const ProgressFunction& progress, double progressAt)
{
  const int threads = ThreadsForWork(p.numberOfThreads, shapes[0].NumberOfSamples());
  const auto pyramidStart = Clock::now();
  const auto levels = BuildPyramid<D>(shapes, C, signal, validSample, threads);
  report.flowSeconds += SecondsSince(pyramidStart);

  const Lattice<D> finest(shapes[0]);
  const double fineEdge = shapes[0].MeanEdgeLength();
  for (size_t l = shapes.size() - 1; l >= 1; --l)
  {
    const auto flowStart = Clock::now();
    const Lattice<D> L(shapes[l]);
    const double* values = levels[l - 1].data();
    const ValidityMasks<D> masks(
      L, C, values, ScanSignal(L.numSamples, C, values, threads).allFinite, threads);
    FlowComputation<D> flow(L, C, p.smoothingPasses, masks.Samples(), masks.Faces(), threads);
    flow.Compute(values, range);
    report.flowSeconds += SecondsSince(flowStart);

    const auto traceStart = Clock::now();
    std::array<double, D> toLevel;
    for (int d = 0; d < D; ++d)
    {
      toLevel[d] = static_cast<double>(L.m[d]) / static_cast<double>(finest.m[d]);
    }
    // The same flow time in the input's units is t / lambda^4 in this level's (see the file comment).
    const double lambda = shapes[l].MeanEdgeLength() / fineEdge;
    TraceStoredPositions<D>(L, flow.Velocity(), p, time / std::pow(lambda, 4), toLevel, positions,
      finest.numSamples * Lattice<D>::Corners, threads, report);
    report.advectionSeconds += SecondsSince(traceStart);
    if (progress && !progress(progressAt))
    {
      return false;
    }
  }
  return true;
}

// The instantiations the grid kernel uses: 1 to 3 axes, float, double or 8-bit signals.
#define SHOCK_TRACE_THROUGH_COARSE_LEVELS(D, T)                                                    \
  template bool TraceThroughCoarseLevels<D, T>(const std::vector<GridShape>&, int, const T*, double, \
    const unsigned char*, const AdvectionParameters&, double, float*, AdvectionReport&,             \
    const ProgressFunction&, double);
SHOCK_TRACE_THROUGH_COARSE_LEVELS(1, float)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(1, double)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(1, unsigned char)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(2, float)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(2, double)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(2, unsigned char)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(3, float)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(3, double)
SHOCK_TRACE_THROUGH_COARSE_LEVELS(3, unsigned char)
#undef SHOCK_TRACE_THROUGH_COARSE_LEVELS

} // namespace grid
} // namespace shock
