/**
 * @file GridAdvect.h
 * @brief Appendix A AdvectVertices on a regular grid: one pass over the samples
 * in row blocks on the threads, each sample by the paper's path (TraceSample,
 * GridSample.h) or by the short road with the same values (GridShortRoad.h).
 * Loops use OpenMP: include only from translation units built with it.
 */
#ifndef GridAdvect_h
#define GridAdvect_h

#include "GridSample.h"
#include "GridShortRoad.h"
#include "ParallelItems.h"

namespace shock
{
namespace grid
{

/**
 * Appendix A AdvectVertices: every valid sample of the pass's blocks (the
 * whole grid, or the samples a run writes) is traced from an offset into each
 * adjacent face, the source signal is sampled at the traced points and the
 * results are averaged. With `positions` (Composed flow; D floats per sample and
 * corner pattern), traces resume from and update the stored positions instead
 * of starting at the offsets.
 *
 * The common case takes a shorter road with the same result: an interior sample
 * of an all-finite signal, read multilinearly, whose traces mostly stay in their
 * start faces. Their reads are gathered as weights on the sample's 3^D
 * neighbourhood and applied once; the traces that leave go through the tracer.
 *
 * The pass holds the set-up; Run is the work of one thread, which takes row
 * blocks from `items` until none is left. Wide: Run is inlined in a region
 * built for AVX2, and 8-bit images with 3 or 4 components are read with
 * CombineByteReadsAvx2.
 */
template <int D, typename S>
struct VertexAdvection
{
  using T = SignalValue<S>;
  const AdvectionContext<D>& ctx;
  const GridTracer<D>& tracer;
  double time;
  const S source; ///< one array, or LayeredValues (GridLayered.h)
  const SampleWriter& out;
  float* positions;
  Neighbourhood<D> hood;
  RowBlocks<D> blocks;
  bool shortRoad;
  bool withinFirst;
  // The largest lower corner of a cell whose corners can all be read four bytes at a time.
  std::int64_t lastLower;

  VertexAdvection(const AdvectionContext<D>& context, const GridTracer<D>& tracer_, double time_,
    const S& source_, const SampleWriter& out_, float* positions_, const RowBlocks<D>& blocks_)
    : ctx(context)
    , tracer(tracer_)
    , time(time_)
    , source(source_)
    , out(out_)
    , positions(positions_)
    , hood(context.L, context.C)
    , blocks(blocks_)
    , shortRoad(!positions_ && !context.valid && context.sampling == Sampling::Linear &&
        tracer_.CrossesFaces())
    , withinFirst(this->shortRoad && TriesWithinFaceFirst<D>(context.L, tracer_, time_))
    , lastLower(context.C == 4 ? std::numeric_limits<std::int64_t>::max()
                               : context.L.numSamples - 2 - context.L.corner[Lattice<D>::Corners - 1])
  {
  }

  template <bool Wide>
  SHOCK_ALWAYS_INLINE void Run(
    ParallelItems& items, TraceTally<D>& tally) const
  {
    const Lattice<D>& L = this->ctx.L;
    const int C = this->ctx.C;
    const unsigned char* valid = this->ctx.valid;
    // (Four bytes a read: one past a sample of 3 components, so one array only.)
    const bool vectorReads =
      Wide && D == 2 && IsOneArray<S> && std::is_same_v<T, unsigned char> && (C == 3 || C == 4);
    // The results of one block, handed to `out` at its end.
    std::vector<double> row(static_cast<size_t>(BlockLength * C));
    // One block at a time (grain 1): the items handed out are [k, k + 1).
    for (std::int64_t k, end; items.Next(k, end); items.Done(k, end))
    {
      std::array<std::int64_t, D> i;
      const std::int64_t length = this->blocks.Get(k, i);
      const std::int64_t x0 = i[0];
      const std::int64_t s0 = L.SampleIndex(i);
      const AdjacentFaces<D> faces(L, i);
      // Interior rows (all neighbours along the other axes exist) take the short road
      // between x = 1 and n - 2.
      bool interiorRow = this->shortRoad;
      for (int d = 1; d < D; ++d)
      {
        interiorRow = interiorRow && i[d] >= 1 && i[d] + 1 < L.n[d];
      }
      for (std::int64_t j = 0; j < length; ++j)
      {
        const std::int64_t s = s0 + j;
        i[0] = x0 + j;
        double* result = row.data() + j * C;
        if (valid && !valid[s])
        {
          const T* own = ValuesNear(this->source, s) + s * C;
          std::copy(own, own + C, result);
        }
        else if (interiorRow && i[0] >= 1 && i[0] + 1 < L.n[0])
        {
          if (this->withinFirst)
          {
            this->template ShortRoad<Wide>(i, s, faces, vectorReads, result, tally);
          }
          else
          {
            this->template ShortRoadAllTraced<Wide>(i, s, faces, vectorReads, result, tally);
          }
        }
        else
        {
          this->template PaperPath<Wide>(i, s, faces, result, tally);
        }
      }
      this->out(s0, length, row.data());
    }
  }

  /**
   * Appendix A for one sample, as the paper writes it (TraceSample,
   * GridSample.h): the traces' reads are gathered first, then combined per
   * component in registers (no read-modify-write of the output per corner).
   */
  template <bool Wide>
  SHOCK_ALWAYS_INLINE void PaperPath(const std::array<std::int64_t, D>& i, std::int64_t s, const AdjacentFaces<D>& faces,
    double* result, TraceTally<D>& tally) const
  {
    Stencil<D> stencil;
    const int traces =
      TraceSample<D, Wide>(this->ctx, this->tracer, this->time, faces, i, s, this->positions, stencil, tally);
    for (int c = 0; c < this->ctx.C; ++c)
    {
      result[c] = stencil.Apply(this->source, this->ctx.C, c) / traces;
    }
  }

  /**
   * The short road (GridShortRoad.h): the traces that stay in their start
   * faces add their reads as weights on the sample's 3^D neighbourhood; the
   * others go through the tracer; the reads are applied once.
   */
  template <bool Wide>
  SHOCK_ALWAYS_INLINE void ShortRoad(const std::array<std::int64_t, D>& i, std::int64_t s,
    const AdjacentFaces<D>& faces, bool vectorReads, double* result, TraceTally<D>& tally) const
  {
    constexpr int Corners = Lattice<D>::Corners;
    std::array<double, D> ends[Corners]; // of the traces that leave their faces
    double weights[Neighbourhood<D>::Size] = {};
    int far = 0;
    if constexpr (D == 3)
    {
      // Most traces stay in their faces: the loop unrolled (every
      // neighbourhood entry a constant), the others out of line.
#pragma GCC unroll 8
      for (int b = 0; b < Corners; ++b)
      {
        const std::int64_t f = faces.Face(i[0], b);
        if (!TraceWithinFace<D>(this->tracer.Velocity(f), b, this->time, weights))
        {
          TraceLeavingFaceOutOfLine<D, Wide>(this->tracer, this->time, i, b, f, ends[far++], tally);
        }
      }
    }
    else
    {
      // Images at smaller t (measured: the 3D arrangement is slower here).
      for (int b = 0; b < Corners; ++b)
      {
        const std::int64_t f = faces.Face(i[0], b);
        if (!TraceWithinFace<D>(this->tracer.Velocity(f), b, this->time, weights))
        {
          TraceLeavingFace<D, Wide>(this->tracer, this->time, i, b, f, ends[far++], tally);
        }
      }
    }
    CombineSampleReads<D, S, Wide>(
      vectorReads, this->lastLower, this->ctx.L, this->hood, this->source, s, this->ctx.C, weights, ends, far, result);
  }

  /// The short road when traces seldom stay in their faces (images at large t): every trace through the tracer.
  template <bool Wide>
  SHOCK_ALWAYS_INLINE void ShortRoadAllTraced(const std::array<std::int64_t, D>& i, std::int64_t s,
    const AdjacentFaces<D>& faces, bool vectorReads, double* result, TraceTally<D>& tally) const
  {
    constexpr int Corners = Lattice<D>::Corners;
    std::array<double, D> ends[Corners];
    std::array<double, D> at;
    for (int d = 0; d < D; ++d)
    {
      at[d] = static_cast<double>(i[d]);
    }
    // Unrolled: each start's offsets are constants.
#pragma GCC unroll 8
    for (int b = 0; b < Corners; ++b)
    {
      TraceFromSample<D, Wide>(this->tracer, this->time, i, at, b, faces.Face(i[0], b), ends[b], tally);
    }
    CombineSampleReads<D, S, Wide, false>(
      vectorReads, this->lastLower, this->ctx.L, this->hood, this->source, s, this->ctx.C, nullptr, ends, Corners,
      result);
  }
};

/// The threads' region of a VertexAdvection pass, built for the baseline x86-64.
template <int D, typename S>
void RunVertexAdvection(const VertexAdvection<D, S>& pass, ParallelItems& items,
  TraceTally<D>& tally)
{
#pragma omp parallel num_threads(pass.ctx.threads)
  {
    TraceTally<D> mine;
    pass.template Run<false>(items, mine);
#pragma omp critical(ShockGridTraceTally)
    tally.Merge(mine);
  }
}

#ifdef SHOCK_GRID_AVX2
/// RunVertexAdvection built for AVX2 (GridAvx2.h). The region is written out
/// again, not shared: GCC builds an OpenMP region for its enclosing function's target.
template <int D, typename S>
SHOCK_TARGET_AVX2 void RunVertexAdvectionAvx2(const VertexAdvection<D, S>& pass,
  ParallelItems& items, TraceTally<D>& tally)
{
#pragma omp parallel num_threads(pass.ctx.threads)
  {
    TraceTally<D> mine;
    pass.template Run<true>(items, mine);
#pragma omp critical(ShockGridTraceTally)
    tally.Merge(mine);
  }
}
#endif

/// AdvectVertices (see VertexAdvection) on the samples of `blocks`; false when aborted through the progress callback.
template <int D, typename S>
bool AdvectVertices(const AdvectionContext<D>& ctx, const GridTracer<D>& tracer, double time,
  const S& source, const SampleWriter& out, float* positions, const RowBlocks<D>& blocks,
  double progressStart, double progressSpan)
{
  const VertexAdvection<D, S> pass(ctx, tracer, time, source, out, positions, blocks);
  // The blocks are independent: the threads take them one at a time as they come.
  ParallelItems items(pass.blocks.Count(), 1, ctx.progress, progressStart, progressSpan);
  TraceTally<D> tally;
#ifdef SHOCK_GRID_AVX2
  if (UsesAvx2())
  {
    RunVertexAdvectionAvx2<D, S>(pass, items, tally);
  }
  else
#endif
  {
    RunVertexAdvection<D, S>(pass, items, tally);
  }
  ctx.report.traceSteps += tally.steps;
  ctx.report.truncatedTraces += tally.truncated;
  for (int d = 0; d < D; ++d)
  {
    const int a = ctx.L.axis[d];
    ctx.report.haloReach[2 * a] = std::max<std::int64_t>(ctx.report.haloReach[2 * a], tally.reach[2 * d]);
    ctx.report.haloReach[2 * a + 1] = std::max<std::int64_t>(ctx.report.haloReach[2 * a + 1], tally.reach[2 * d + 1]);
  }
  return items.Finish();
}

/// Initial Composed-flow positions: the offsets of AdvectVertices, D floats per
/// sample and corner pattern.
template <int D>
LargeArray<float> InitialTracePositions(const Lattice<D>& L, int threads)
{
  constexpr int Corners = Lattice<D>::Corners;
  LargeArray<float> positions = AllocateLargeArray<float>(L.numSamples * Corners * D);
  const RowBlocks<D> blocks(L.n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t k = 0; k < blocks.Count(); ++k)
  {
    std::array<std::int64_t, D> i;
    const std::int64_t length = blocks.Get(k, i);
    const std::int64_t s0 = L.SampleIndex(i);
    const std::int64_t x0 = i[0];
    for (std::int64_t j = 0; j < length; ++j)
    {
      i[0] = x0 + j;
      for (int b = 0; b < Corners; ++b)
      {
        for (int d = 0; d < D; ++d)
        {
          positions[((s0 + j) * Corners + b) * D + d] =
            static_cast<float>(static_cast<double>(i[d]) + VertexOffset * (0.5 - ((b >> d) & 1)));
        }
      }
    }
  }
  return positions;
}

} // namespace grid
} // namespace shock

#endif
