/**
 * @file GridAdvect.h
 * @brief Appendix A AdvectVertices on a regular grid, and the reading of a grid
 * signal at a traced point (Sampling::Linear: multilinear; Sampling::Nearest).
 * Loops use OpenMP: include only from translation units built with it.
 */
#ifndef GridAdvect_h
#define GridAdvect_h

#include "GridAvx2.h"
#include "GridLattice.h"
#include "GridTrace.h"
#include "ParallelItems.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#ifdef SHOCK_GRID_AVX2
#include <immintrin.h>
#endif

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
template <int D, bool Wide>
SHOCK_ALWAYS_INLINE void TraceLeavingFace(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, int b, std::int64_t f, std::array<double, D>& end,
  std::uint64_t& steps, std::uint64_t& truncated)
{
  std::array<std::int64_t, D> c;
  StartInFace<D>(i, b, end, c);
  bool cut = false;
  steps += static_cast<std::uint64_t>(tracer.template Trace<Wide>(end, c, f, time, cut));
  truncated += cut ? 1 : 0;
}

/// TraceLeavingFace for a trace that may stay in its face, the sample's index
/// coordinates also given as doubles (`at`).
template <int D, bool Wide>
SHOCK_ALWAYS_INLINE void TraceFromSample(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, const std::array<double, D>& at, int b, std::int64_t f,
  std::array<double, D>& end, std::uint64_t& steps, std::uint64_t& truncated)
{
  std::array<std::int64_t, D> c;
  StartInFace<D>(i, at, b, end, c);
  bool cut = false;
  steps += static_cast<std::uint64_t>(tracer.template Trace<Wide>(end, c, f, time, cut));
  truncated += cut ? 1 : 0;
}

/// TraceLeavingFace kept out of line, so that a loop of traces that mostly stay
/// in their faces (3D) stays small.
template <int D, bool Wide>
SHOCK_NOINLINE void TraceLeavingFaceOutOfLine(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, int b, std::int64_t f, std::array<double, D>& end,
  std::uint64_t& steps, std::uint64_t& truncated)
{
  TraceLeavingFace<D, Wide>(tracer, time, i, b, f, end, steps, truncated);
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
 * @name AVX2 reads of 8-bit images with 3 or 4 components (see GridAvx2.h)
 * The components of a sample in the four lanes of a register: one 4-byte load
 * and two conversions per corner instead of a widening per component, with
 * the products and sums of CombineAllReads in the same order per component.
 */
///@{
#ifdef SHOCK_GRID_AVX2
/// The four bytes at p as four doubles.
SHOCK_TARGET_AVX2 inline __m256d FourBytesAvx2(const unsigned char* p)
{
  std::int32_t word;
  std::memcpy(&word, p, sizeof(word));
  return _mm256_cvtepi32_pd(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(word)));
}

/**
 * CombineAllReads<2, unsigned char, UseHood> for C = 3 or 4 components, the
 * four traces' ends given (far = 4) when UseHood is false. Each read takes four
 * bytes, one past the sample's own with C = 3: cells and neighbourhoods whose
 * lower corner is above `lastLower` (those that hold the last sample) are left
 * to CombineAllReads, and false is returned, nothing written.
 */
template <bool UseHood>
SHOCK_TARGET_AVX2 inline bool CombineByteReadsAvx2(const Lattice<2>& L,
  const Neighbourhood<2>& hood, const unsigned char* source, std::int64_t s, int C,
  std::int64_t lastLower, const double* weights, const std::array<double, 2>* ends, int far,
  double* result)
{
  std::int64_t lower[4];
  std::array<double, 2> frac[4];
  for (int e = 0; e < far; ++e)
  {
    lower[e] = LocateCell<2>(L, ends[e], frac[e]);
    if (lower[e] > lastLower)
    {
      return false;
    }
  }
  if (UseHood && s > lastLower) // the neighbourhood's highest sample is s + corner[3]
  {
    return false;
  }
  // One sum per corner, the lanes the components (partial[k][b] of CombineReads).
  __m256d corner[4] = { _mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd(),
    _mm256_setzero_pd() };
  for (int e = 0; e < far; ++e)
  {
    const unsigned char* values = source + lower[e] * C;
    for (int b = 0; b < 4; ++b)
    {
      const __m256d w = _mm256_set1_pd(CornerWeight<2>(frac[e], b));
      corner[b] = _mm256_add_pd(corner[b], _mm256_mul_pd(w, FourBytesAvx2(values + hood.cornerOffset[b])));
    }
  }
  __m256d total =
    _mm256_add_pd(_mm256_add_pd(corner[0], corner[1]), _mm256_add_pd(corner[2], corner[3]));
  if constexpr (UseHood)
  {
    __m256d sum[4] = { total, _mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd() };
    const unsigned char* own = source + s * C;
    for (int e = 0; e < Neighbourhood<2>::Size; ++e)
    {
      // Entries 0..7 into sums e mod 4, entry 8 into the first (CombineReads's order).
      const int r = e < 8 ? e % 4 : 0;
      sum[r] = _mm256_add_pd(sum[r],
        _mm256_mul_pd(_mm256_set1_pd(weights[e]), FourBytesAvx2(own + hood.valueOffset[e])));
    }
    total = _mm256_add_pd(_mm256_add_pd(sum[0], sum[1]), _mm256_add_pd(sum[2], sum[3]));
  }
  const __m256d average = _mm256_mul_pd(total, _mm256_set1_pd(0.25)); // exactly / 4
  // Plain stores (a masked store is slow on some processors): C values, not the 4th of 3.
  _mm_storeu_pd(result, _mm256_castpd256_pd128(average));
  const __m128d upper = _mm256_extractf128_pd(average, 1);
  _mm_store_sd(result + 2, upper);
  if (C == 4)
  {
    _mm_storeh_pd(result + 3, upper);
  }
  return true;
}
#endif

/**
 * The combine of AdvectVertices's short road for sample s: CombineAllReads, or
 * with Wide and `vectorReads` (D = 2, 8-bit samples, C = 3 or 4) its AVX2
 * version, which only a caller built for AVX2 may take.
 */
template <int D, typename T, bool Wide, bool UseHood = true>
SHOCK_ALWAYS_INLINE void CombineSampleReads(bool vectorReads, std::int64_t lastLower,
  const Lattice<D>& L, const Neighbourhood<D>& hood, const T* source, std::int64_t s, int C,
  const double* weights, const std::array<double, D>* ends, int far, double* result)
{
#ifdef SHOCK_GRID_AVX2
  if constexpr (Wide && D == 2 && std::is_same_v<T, unsigned char>)
  {
    if (vectorReads &&
      CombineByteReadsAvx2<UseHood>(L, hood, source, s, C, lastLower, weights, ends, far, result))
    {
      return;
    }
  }
#endif
  (void)vectorReads;
  (void)lastLower;
  CombineAllReads<D, T, UseHood>(L, hood, source, s, C, weights, ends, far, result);
}

///@}

/**
 * Appendix A AdvectVertices for one sample i (index s), any case: traces from
 * the offset into each adjacent face (or from the stored positions), reads
 * added to `stencil`; returns the number of traces.
 */
template <int D, bool Wide = false>
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
    steps += static_cast<std::uint64_t>(tracer.template Trace<Wide>(q, c, f, time, cut));
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
 *
 * The pass holds the set-up; Run is the work of one thread, which takes row
 * blocks from `items` until none is left. Wide: Run is inlined in a region
 * built for AVX2, and 8-bit images with 3 or 4 components are read with
 * CombineByteReadsAvx2.
 */
template <int D, typename T>
struct VertexAdvection
{
  const AdvectionContext<D>& ctx;
  const GridTracer<D>& tracer;
  double time;
  const T* source;
  const SampleWriter& out;
  float* positions;
  Neighbourhood<D> hood;
  RowBlocks<D> blocks;
  bool shortRoad;
  bool withinFirst;
  // The largest lower corner of a cell whose corners can all be read four bytes at a time.
  std::int64_t lastLower;

  VertexAdvection(const AdvectionContext<D>& context, const GridTracer<D>& tracer_, double time_,
    const T* source_, const SampleWriter& out_, float* positions_)
    : ctx(context)
    , tracer(tracer_)
    , time(time_)
    , source(source_)
    , out(out_)
    , positions(positions_)
    , hood(context.L, context.C)
    , blocks(context.L.n)
    , shortRoad(!positions_ && !context.valid && context.sampling == Sampling::Linear &&
        tracer_.CrossesFaces())
    , withinFirst(this->shortRoad && TriesWithinFaceFirst<D>(context.L, tracer_, time_))
    , lastLower(context.C == 4 ? std::numeric_limits<std::int64_t>::max()
                               : context.L.numSamples - 2 - context.L.corner[Lattice<D>::Corners - 1])
  {
  }

  template <bool Wide>
  SHOCK_ALWAYS_INLINE void Run(
    ParallelItems& items, std::uint64_t& steps, std::uint64_t& truncated) const
  {
    const Lattice<D>& L = this->ctx.L;
    const int C = this->ctx.C;
    const unsigned char* valid = this->ctx.valid;
    constexpr int Corners = Lattice<D>::Corners;
    using Hood = Neighbourhood<D>;
    const Hood& hood = this->hood;
    const RowBlocks<D>& blocks = this->blocks;
    const GridTracer<D>& tracer = this->tracer;
    const double time = this->time;
    const T* source = this->source;
    const bool shortRoad = this->shortRoad;
    const bool withinFirst = this->withinFirst;
    const std::int64_t lastLower = this->lastLower;
    float* positions = this->positions;
    const bool vectorReads = Wide && D == 2 && std::is_same_v<T, unsigned char> && (C == 3 || C == 4);
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
            // Unrolled: each start's offsets are constants.
#pragma GCC unroll 8
            for (int b = 0; b < Corners; ++b)
            {
              TraceFromSample<D, Wide>(tracer, time, i, at, b, faces.Face(i[0], b), ends[b], steps, truncated);
            }
            CombineSampleReads<D, T, Wide, false>(
              vectorReads, lastLower, L, hood, source, s, C, nullptr, ends, Corners, result);
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
                TraceLeavingFaceOutOfLine<D, Wide>(tracer, time, i, b, f, ends[far++], steps, truncated);
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
                TraceLeavingFace<D, Wide>(tracer, time, i, b, f, ends[far++], steps, truncated);
              }
            }
          }
          CombineSampleReads<D, T, Wide>(
            vectorReads, lastLower, L, hood, source, s, C, weights, ends, far, result);
          continue;
        }
        // The traces' reads are gathered first, then combined per component in
        // registers (no read-modify-write of the output per corner).
        Stencil<D> stencil;
        const int traces =
          TraceSample<D, Wide>(this->ctx, tracer, time, faces, i, s, positions, stencil, steps, truncated);
        for (int c = 0; c < C; ++c)
        {
          result[c] = stencil.Apply(source, C, c) / traces;
        }
      }
      this->out(s0, length, row.data());
    }
  }
};

/// The threads' region of a VertexAdvection pass, built for the baseline x86-64.
template <int D, typename T>
void RunVertexAdvection(const VertexAdvection<D, T>& pass, ParallelItems& items,
  std::uint64_t& steps, std::uint64_t& truncated)
{
  std::uint64_t passSteps = 0;
  std::uint64_t passTruncated = 0;
#pragma omp parallel num_threads(pass.ctx.threads) reduction(+ : passSteps, passTruncated)
  pass.template Run<false>(items, passSteps, passTruncated);
  steps += passSteps;
  truncated += passTruncated;
}

#ifdef SHOCK_GRID_AVX2
/// RunVertexAdvection built for AVX2 (GridAvx2.h). The region is written out
/// again, not shared: GCC builds an OpenMP region for its enclosing function's target.
template <int D, typename T>
SHOCK_TARGET_AVX2 void RunVertexAdvectionAvx2(const VertexAdvection<D, T>& pass,
  ParallelItems& items, std::uint64_t& steps, std::uint64_t& truncated)
{
  std::uint64_t passSteps = 0;
  std::uint64_t passTruncated = 0;
#pragma omp parallel num_threads(pass.ctx.threads) reduction(+ : passSteps, passTruncated)
  pass.template Run<true>(items, passSteps, passTruncated);
  steps += passSteps;
  truncated += passTruncated;
}
#endif

/// AdvectVertices (see VertexAdvection); false when aborted through the progress callback.
template <int D, typename T>
bool AdvectVertices(const AdvectionContext<D>& ctx, const GridTracer<D>& tracer, double time,
  const T* source, const SampleWriter& out, float* positions, double progressStart,
  double progressSpan)
{
  const VertexAdvection<D, T> pass(ctx, tracer, time, source, out, positions);
  // The blocks are independent: the threads take them one at a time as they come.
  ParallelItems items(pass.blocks.Count(), 1, ctx.progress, progressStart, progressSpan);
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;
#ifdef SHOCK_GRID_AVX2
  if (UsesAvx2())
  {
    RunVertexAdvectionAvx2<D, T>(pass, items, steps, truncated);
  }
  else
#endif
  {
    RunVertexAdvection<D, T>(pass, items, steps, truncated);
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
