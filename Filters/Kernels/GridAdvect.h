/**
 * @file GridAdvect.h
 * @brief Appendix A AdvectVertices on a regular grid, and the reading of a grid
 * signal at a traced point (Sampling::Linear: multilinear; Sampling::Nearest).
 * Loops use OpenMP: include only from translation units built with it.
 */
#ifndef GridAdvect_h
#define GridAdvect_h

#include "GridLattice.h"
#include "GridTrace.h"
#include "ParallelItems.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace shock
{
namespace grid
{

// Offset of a back-trace start from its sample towards the adjacent face centre,
// in units of the sample-to-centre distance (the paper's epsilon).
constexpr double VertexOffset = 0.001;

/// The values 0 .. 255 as doubles: an 8-bit sample is widened by a load from this
/// 2 KiB table, which is faster in the sampling than an integer conversion.
struct ByteValues
{
  double value[256];
  constexpr ByteValues()
    : value()
  {
    for (int i = 0; i < 256; ++i)
    {
      this->value[i] = i;
    }
  }
};
inline constexpr ByteValues ByteTable{};

/// A stored sample value as a double (exact for float, double and 8-bit values).
template <typename T>
SHOCK_ALWAYS_INLINE double Widen(T value)
{
  if constexpr (std::is_same_v<T, unsigned char>)
  {
    return ByteTable.value[value];
  }
  else
  {
    return static_cast<double>(value);
  }
}

/// A weighted sum of samples: the value read at a traced point, or the average of several.
template <int D>
struct Stencil
{
  // Up to one multilinear read (the corners of a cell) per trace, one trace per corner.
  static constexpr int Capacity = Lattice<D>::Corners * Lattice<D>::Corners;
  std::array<std::int64_t, Capacity> sample;
  std::array<double, Capacity> weight;
  int size = 0;

  void Add(std::int64_t s, double w)
  {
    this->sample[this->size] = s;
    this->weight[this->size] = w;
    ++this->size;
  }

  /// The weighted sum of component c of `values` (C components per sample).
  template <typename T>
  double Apply(const T* values, int C, int c) const
  {
    // Four partial sums: four short chains of dependent additions instead of one long one.
    double partial[4] = { 0.0, 0.0, 0.0, 0.0 };
    int r = 0;
    for (; r + 4 <= this->size; r += 4)
    {
      for (int k = 0; k < 4; ++k)
      {
        partial[k] += this->weight[r + k] * Widen(values[this->sample[r + k] * C + c]);
      }
    }
    for (; r < this->size; ++r)
    {
      partial[0] += this->weight[r] * Widen(values[this->sample[r] * C + c]);
    }
    return (partial[0] + partial[1]) + (partial[2] + partial[3]);
  }
};

/**
 * The cell (face) of a multilinear read at index position q, q inside the
 * grid: its lower corner's sample index, and q's coordinates in it (frac).
 */
template <int D>
SHOCK_ALWAYS_INLINE std::int64_t LocateCell(
  const Lattice<D>& L, const std::array<double, D>& q, std::array<double, D>& frac)
{
  std::int64_t base = 0;
  for (int d = 0; d < D; ++d)
  {
    const std::int64_t cell = std::min<std::int64_t>(static_cast<std::int64_t>(q[d]), L.m[d] - 1);
    frac[d] = q[d] - static_cast<double>(cell);
    base += cell * L.sampleStride[d];
  }
  return base;
}

/// Multilinear weight of the cell corner with bit pattern b (bit d: the upper
/// side along axis d) at coordinates frac in the cell.
template <int D>
SHOCK_ALWAYS_INLINE double CornerWeight(const std::array<double, D>& frac, int b)
{
  double w = 1.0;
  for (int d = 0; d < D; ++d)
  {
    w *= ((b >> d) & 1) ? frac[d] : 1.0 - frac[d];
  }
  return w;
}

/**
 * Adds to `stencil` the samples and weights that read a grid signal at index
 * position q.
 * Linear: multilinear interpolation over the valid corners of the cell holding q.
 * Nearest: the nearest sample (the linear rule if that sample is invalid).
 * `valid` is null when every sample is valid.
 * Returns false, adding nothing, when no valid sample is available.
 */
template <int D>
bool SampleGrid(const Lattice<D>& L, const unsigned char* valid, Sampling sampling,
  const std::array<double, D>& q, Stencil<D>& stencil)
{
  if (sampling == Sampling::Nearest)
  {
    std::int64_t s = 0;
    for (int d = 0; d < D; ++d)
    {
      s += static_cast<std::int64_t>(std::floor(q[d] + 0.5)) * L.sampleStride[d];
    }
    if (!valid || valid[s])
    {
      stencil.Add(s, 1.0);
      return true;
    }
  }
  std::array<double, D> frac;
  const std::int64_t base = LocateCell<D>(L, q, frac);
  double weights[Lattice<D>::Corners];
  double total = 0.0;
  for (int b = 0; b < Lattice<D>::Corners; ++b)
  {
    const double w = CornerWeight<D>(frac, b);
    weights[b] = (!valid || valid[base + L.corner[b]]) ? w : 0.0;
    total += weights[b];
  }
  if (!valid)
  {
    // All corners valid: the weights already sum to 1 (and a zero weight is harmless).
    for (int b = 0; b < Lattice<D>::Corners; ++b)
    {
      stencil.Add(base + L.corner[b], weights[b]);
    }
    return true;
  }
  if (!(total > 0.0))
  {
    return false;
  }
  for (int b = 0; b < Lattice<D>::Corners; ++b)
  {
    if (weights[b] != 0.0) // skip invalid corners: 0 x NaN would be NaN
    {
      stencil.Add(base + L.corner[b], weights[b] / total);
    }
  }
  return true;
}

/// Work shared by the advection passes of one run.
template <int D>
struct AdvectionContext
{
  const Lattice<D>& L;
  int C;
  int threads;
  Sampling sampling;
  const unsigned char* valid; // null when every sample is finite
  const ProgressFunction& progress;
  AdvectionReport& report;
};

/**
 * The 3^D samples around an interior sample, where the traces that stay in
 * their start faces read: a trace from the face through corner pattern b reads
 * the corners of that face, whose lower corner is the sample minus bits(b).
 * Weights gathered over this neighbourhood are applied in one pass at the end.
 */
template <int D>
struct Neighbourhood
{
  static constexpr int Size = D == 1 ? 3 : (D == 2 ? 9 : 27);
  std::array<std::int64_t, Size> valueOffset{}; // offset of entry k's values (C per sample)
  // Offset of the values of a cell's corner b from its lower corner's.
  std::array<std::int64_t, Lattice<D>::Corners> cornerOffset{};

  /// The start of a trace, offset from the sample towards its face's centre, as a
  /// coordinate in the face: the sample is the face's lower corner (bit 0) or its upper one.
  static constexpr double Start(int bit) { return bit ? 1.0 - 0.5 * VertexOffset : 0.5 * VertexOffset; }

  /// Entry step from a face's lower corner to its corner c (a constant once unrolled).
  static constexpr int Step(int c)
  {
    return (c & 1) + ((c >> 1) & 1) * 3 + ((c >> 2) & 1) * 9;
  }
  /// Entry of the lower corner of the face through corner pattern b (bits(b) below the sample).
  static constexpr int Lower(int b)
  {
    return (Size - 1) / 2 - Step(b);
  }

  /// The neighbourhood of a signal with C components per sample.
  Neighbourhood(const Lattice<D>& L, int C)
  {
    // Entry k = sum over axes of (o_d + 1) 3^d for the offset o in {-1, 0, 1}^D.
    for (int k = 0; k < Size; ++k)
    {
      std::int64_t o = 0;
      for (int d = 0, rest = k; d < D; ++d, rest /= 3)
      {
        o += (rest % 3 - 1) * L.sampleStride[d];
      }
      this->valueOffset[k] = o * C;
    }
    for (int b = 0; b < Lattice<D>::Corners; ++b)
    {
      this->cornerOffset[b] = L.corner[b] * C;
    }
  }
};

/// StartInFace with the sample's index coordinates also given as doubles (`at`).
template <int D>
SHOCK_ALWAYS_INLINE void StartInFace(const std::array<std::int64_t, D>& i,
  const std::array<double, D>& at, int b, std::array<double, D>& q, std::array<std::int64_t, D>& c)
{
  constexpr double offset[2] = { VertexOffset * 0.5, VertexOffset * -0.5 };
  for (int d = 0; d < D; ++d)
  {
    const int bit = (b >> d) & 1;
    c[d] = i[d] - bit;
    q[d] = at[d] + offset[bit];
  }
}

/**
 * The start of the trace of sample i into its adjacent face through corner
 * pattern b: offset from the sample towards the face centre (index position q);
 * the face's coordinates, the sample's minus the corner bits, go to c.
 */
template <int D>
void StartInFace(const std::array<std::int64_t, D>& i, int b, std::array<double, D>& q,
  std::array<std::int64_t, D>& c)
{
  std::array<double, D> at;
  for (int d = 0; d < D; ++d)
  {
    at[d] = static_cast<double>(i[d]);
  }
  StartInFace<D>(i, at, b, q, c);
}

/**
 * Traces the start of face f (through corner pattern b) of an interior sample
 * when it does not leave the face in time t: the flow is constant on the face,
 * so the trace ends at start + v t, and its multilinear read is added to the
 * neighbourhood weights. False, adding nothing, when the trace would leave the
 * face (the general tracer takes it).
 */
template <int D>
SHOCK_ALWAYS_INLINE bool TraceWithinFace(const float* v, int b, double time, double* weights)
{
  std::array<double, D> frac;
  int outside = 0; // counted, not tested per axis: one branch per trace
  for (int d = 0; d < D; ++d)
  {
    frac[d] = Neighbourhood<D>::Start((b >> d) & 1) + static_cast<double>(v[d]) * time;
    outside += static_cast<int>(!(frac[d] >= 0.0)) + static_cast<int>(!(frac[d] <= 1.0));
  }
  if (outside != 0)
  {
    return false;
  }
  // Multilinear weights of the face's corners, built one axis at a time.
  double corner[Lattice<D>::Corners];
  corner[0] = 1.0;
  for (int d = 0; d < D; ++d)
  {
    for (int c = 0; c < (1 << d); ++c)
    {
      corner[c | (1 << d)] = corner[c] * frac[d];
      corner[c] *= 1.0 - frac[d];
    }
  }
  double* face = weights + Neighbourhood<D>::Lower(b);
  for (int c = 0; c < Lattice<D>::Corners; ++c)
  {
    face[Neighbourhood<D>::Step(c)] += corner[c];
  }
  return true;
}

/**
 * The fraction of the traces from the samples into their adjacent faces that
 * stay in their start faces for time `time`, estimated on about 4096 faces
 * evenly spread (all of a smaller grid; a deterministic subset, so that the
 * estimate does not depend on the thread count).
 */
template <int D>
double StayingFraction(const Lattice<D>& L, const float* velocity, double time)
{
  const std::int64_t Stride = std::max<std::int64_t>(1, L.numFaces / 4096);
  constexpr int Corners = Lattice<D>::Corners;
  double scratch[Neighbourhood<D>::Size] = {};
  std::int64_t stay = 0;
  std::int64_t total = 0;
  for (std::int64_t f = 0; f < L.numFaces; f += Stride)
  {
    for (int b = 0; b < Corners; ++b)
    {
      stay += TraceWithinFace<D>(velocity + f * D, b, time, scratch) ? 1 : 0;
      ++total;
    }
  }
  return total > 0 ? static_cast<double>(stay) / static_cast<double>(total) : 1.0;
}

/**
 * Whether the short road of AdvectVertices first tries each trace within its
 * start face (TraceWithinFace, reads gathered on the neighbourhood) before the
 * tracer. On lines and images, when fewer than a third of the traces stay
 * (large t), that try costs more than it saves, and every trace goes through
 * the tracer (measured on a photo: the two roads take the same time at
 * t = 64, where a third stay; at t = 1024, 17 % stay, and the tracer alone is
 * 6 % faster; at t = 4, 53 % stay, and it is 17 % slower). Volumes always try:
 * most of their traces stay.
 */
template <int D>
bool TriesWithinFaceFirst(const Lattice<D>& L, const GridTracer<D>& tracer, double time)
{
  return D == 3 || 3.0 * StayingFraction<D>(L, tracer.Velocity(0), time) >= 1.0;
}

/**
 * The trace of interior sample i into face f (corner pattern b) that leaves
 * its face: through the tracer; its end is stored in `end`.
 */
template <int D>
SHOCK_ALWAYS_INLINE void TraceLeavingFace(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, int b, std::int64_t f, std::array<double, D>& end,
  std::uint64_t& steps, std::uint64_t& truncated)
{
  std::array<std::int64_t, D> c;
  StartInFace<D>(i, b, end, c);
  bool cut = false;
  steps += static_cast<std::uint64_t>(tracer.Trace(end, c, f, time, cut));
  truncated += cut ? 1 : 0;
}

/// TraceLeavingFace for a trace that may stay in its face, the sample's index
/// coordinates also given as doubles (`at`).
template <int D>
SHOCK_ALWAYS_INLINE void TraceFromSample(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, const std::array<double, D>& at, int b, std::int64_t f,
  std::array<double, D>& end, std::uint64_t& steps, std::uint64_t& truncated)
{
  std::array<std::int64_t, D> c;
  StartInFace<D>(i, at, b, end, c);
  bool cut = false;
  steps += static_cast<std::uint64_t>(tracer.Trace(end, c, f, time, cut));
  truncated += cut ? 1 : 0;
}

/// TraceLeavingFace kept out of line, so that a loop of traces that mostly stay
/// in their faces (3D) stays small.
template <int D>
SHOCK_NOINLINE void TraceLeavingFaceOutOfLine(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, int b, std::int64_t f, std::array<double, D>& end,
  std::uint64_t& steps, std::uint64_t& truncated)
{
  TraceLeavingFace<D>(tracer, time, i, b, f, end, steps, truncated);
}

/**
 * The result of the short road for components [c0, c0 + K) of sample s (C per
 * sample): the average over its traces of their multilinear reads, those of
 * the traces that stayed in their faces gathered as neighbourhood `weights`,
 * those of the `far` traces (ending at `ends`) read here. The sums are formed
 * in the order of Stencil::Apply over the far reads' corners (term r of the
 * reads into partial sum r mod 4; in 1D, where Apply put a lone read's two
 * terms both into the first, the sum is the same), then of the neighbourhood,
 * so that any K gives the same values; K is a constant so that each corner's
 * position and weight serve all K components at once. UseHood false: every
 * trace went through the tracer, the neighbourhood is not read.
 */
template <int D, int K, typename T, bool UseHood = true>
SHOCK_ALWAYS_INLINE void CombineReads(const Lattice<D>& L, const Neighbourhood<D>& hood,
  const T* source, std::int64_t s, int C, int c0, const double* weights,
  const std::array<double, D>* ends, int far, double* result)
{
  constexpr int Corners = Lattice<D>::Corners;
  double partial[K][4] = {};
  for (int e = 0; e < far; ++e)
  {
    // SampleGrid's multilinear read, every corner valid.
    std::array<double, D> frac;
    const T* lower = source + LocateCell<D>(L, ends[e], frac) * C + c0;
    for (int b = 0; b < Corners; ++b)
    {
      const double w = CornerWeight<D>(frac, b);
      const T* value = lower + hood.cornerOffset[b];
      for (int k = 0; k < K; ++k)
      {
        partial[k][(e * Corners + b) % 4] += w * Widen(value[k]);
      }
    }
  }
  const T* own = source + s * C + c0;
  for (int k = 0; k < K; ++k)
  {
    // Four partial sums: short chains of dependent additions.
    double sum[4] = { (partial[k][0] + partial[k][1]) + (partial[k][2] + partial[k][3]), 0.0, 0.0, 0.0 };
    if constexpr (!UseHood)
    {
      result[c0 + k] = sum[0] / Corners;
      continue;
    }
    int e = 0;
    for (; e + 4 <= Neighbourhood<D>::Size; e += 4)
    {
      for (int r = 0; r < 4; ++r)
      {
        sum[r] += weights[e + r] * Widen(own[k + hood.valueOffset[e + r]]);
      }
    }
    for (; e < Neighbourhood<D>::Size; ++e)
    {
      sum[0] += weights[e] * Widen(own[k + hood.valueOffset[e]]);
    }
    result[c0 + k] = ((sum[0] + sum[1]) + (sum[2] + sum[3])) / Corners;
  }
}

/// CombineReads for all C components, four at a time.
template <int D, typename T, bool UseHood = true>
SHOCK_ALWAYS_INLINE void CombineAllReads(const Lattice<D>& L, const Neighbourhood<D>& hood,
  const T* source, std::int64_t s, int C, const double* weights,
  const std::array<double, D>* ends, int far, double* result)
{
  int c0 = 0;
  for (; c0 + 4 <= C; c0 += 4)
  {
    CombineReads<D, 4, T, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
  }
  switch (C - c0)
  {
    case 1:
      CombineReads<D, 1, T, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
      break;
    case 2:
      CombineReads<D, 2, T, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
      break;
    case 3:
      CombineReads<D, 3, T, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
      break;
    default:
      break;
  }
}

/**
 * Appendix A AdvectVertices for one sample i (index s), any case: traces from
 * the offset into each adjacent face (or from the stored positions), reads
 * added to `stencil`; returns the number of traces.
 */
template <int D>
int TraceSample(const AdvectionContext<D>& ctx, const GridTracer<D>& tracer, double time,
  const AdjacentFaces<D>& faces, const std::array<std::int64_t, D>& i, std::int64_t s,
  float* positions, Stencil<D>& stencil, std::uint64_t& steps, std::uint64_t& truncated)
{
  constexpr int Corners = Lattice<D>::Corners;
  int traces = 0;
  for (int b = 0; b < Corners; ++b)
  {
    std::int64_t f = faces.Face(i[0], b);
    if (f < 0)
    {
      continue;
    }
    std::array<double, D> q;
    std::array<std::int64_t, D> c;
    float* stored = positions ? positions + (s * Corners + b) * D : nullptr;
    if (stored)
    {
      std::copy(stored, stored + D, q.begin());
      f = tracer.FaceOf(q, c);
    }
    else
    {
      StartInFace<D>(i, b, q, c);
    }
    bool cut = false;
    steps += static_cast<std::uint64_t>(tracer.Trace(q, c, f, time, cut));
    truncated += cut ? 1 : 0;
    if (stored)
    {
      std::copy(q.begin(), q.end(), stored);
    }
    if (!SampleGrid<D>(ctx.L, ctx.valid, ctx.sampling, q, stencil))
    {
      stencil.Add(s, 1.0); // only non-finite samples around q: keep the sample's own value
    }
    ++traces;
  }
  return traces;
}

/**
 * Appendix A AdvectVertices: every valid sample is traced from an offset into
 * each adjacent face, the source signal is sampled at the traced points and the
 * results are averaged. With `positions` (Composed flow; D floats per sample and
 * corner pattern), traces resume from and update the stored positions instead
 * of starting at the offsets.
 *
 * The common case takes a shorter road with the same result: an interior sample
 * of an all-finite signal, read multilinearly, whose traces mostly stay in their
 * start faces. Their reads are gathered as weights on the sample's 3^D
 * neighbourhood and applied once; the traces that leave go through the tracer.
 * Returns false when aborted through the progress callback.
 */
template <int D, typename T>
bool AdvectVertices(const AdvectionContext<D>& ctx, const GridTracer<D>& tracer, double time,
  const T* source, const SampleWriter& out, float* positions, double progressStart,
  double progressSpan)
{
  const Lattice<D>& L = ctx.L;
  const int C = ctx.C;
  const unsigned char* valid = ctx.valid;
  constexpr int Corners = Lattice<D>::Corners;
  using Hood = Neighbourhood<D>;
  const Hood hood(L, C);
  const bool shortRoad =
    !positions && !valid && ctx.sampling == Sampling::Linear && tracer.CrossesFaces();
  const bool withinFirst = shortRoad && TriesWithinFaceFirst<D>(L, tracer, time);

  const RowBlocks<D> blocks(L.n);
  // The blocks are independent: the threads take them one at a time as they come.
  ParallelItems items(blocks.Count(), 1, ctx.progress, progressStart, progressSpan);
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;
#pragma omp parallel num_threads(ctx.threads) reduction(+ : steps, truncated)
  {
    // The results of one block, handed to `out` at its end.
    std::vector<double> row(static_cast<size_t>(BlockLength * C));
    // One block at a time (grain 1): the items handed out are [k, k + 1).
    for (std::int64_t k, end; items.Next(k, end); items.Done(k, end))
    {
      std::array<std::int64_t, D> i;
      const std::int64_t length = blocks.Get(k, i);
      const std::int64_t x0 = i[0];
      const std::int64_t s0 = L.SampleIndex(i);
      const AdjacentFaces<D> faces(L, i);
      // Interior rows (all neighbours along the other axes exist) take the short road
      // between x = 1 and n - 2.
      bool interiorRow = shortRoad;
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
          std::copy(source + s * C, source + (s + 1) * C, result);
          continue;
        }
        if (interiorRow && i[0] >= 1 && i[0] + 1 < L.n[0])
        {
          std::array<double, D> ends[Corners]; // of the traces that leave their faces
          if (!withinFirst)
          {
            // Images at large t: every trace through the tracer, no neighbourhood.
            std::array<double, D> at;
            for (int d = 0; d < D; ++d)
            {
              at[d] = static_cast<double>(i[d]);
            }
            for (int b = 0; b < Corners; ++b)
            {
              TraceFromSample<D>(tracer, time, i, at, b, faces.Face(i[0], b), ends[b], steps, truncated);
            }
            CombineAllReads<D, T, false>(L, hood, source, s, C, nullptr, ends, Corners, result);
            continue;
          }
          double weights[Hood::Size] = {};
          int far = 0;
          if constexpr (D == 3)
          {
            // Most traces stay in their faces: the loop unrolled (every
            // neighbourhood entry a constant), the others out of line.
#pragma GCC unroll 8
            for (int b = 0; b < Corners; ++b)
            {
              const std::int64_t f = faces.Face(i[0], b);
              if (!TraceWithinFace<D>(tracer.Velocity(f), b, time, weights))
              {
                TraceLeavingFaceOutOfLine<D>(tracer, time, i, b, f, ends[far++], steps, truncated);
              }
            }
          }
          else
          {
            // Images at smaller t (measured: the 3D arrangement is slower here).
            for (int b = 0; b < Corners; ++b)
            {
              const std::int64_t f = faces.Face(i[0], b);
              if (!TraceWithinFace<D>(tracer.Velocity(f), b, time, weights))
              {
                TraceLeavingFace<D>(tracer, time, i, b, f, ends[far++], steps, truncated);
              }
            }
          }
          CombineAllReads<D>(L, hood, source, s, C, weights, ends, far, result);
          continue;
        }
        // The traces' reads are gathered first, then combined per component in
        // registers (no read-modify-write of the output per corner).
        Stencil<D> stencil;
        const int traces =
          TraceSample<D>(ctx, tracer, time, faces, i, s, positions, stencil, steps, truncated);
        for (int c = 0; c < C; ++c)
        {
          result[c] = stencil.Apply(source, C, c) / traces;
        }
      }
      out(s0, length, row.data());
    }
  }
  ctx.report.traceSteps += steps;
  ctx.report.truncatedTraces += truncated;
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
