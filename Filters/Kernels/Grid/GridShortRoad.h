/**
 * @file GridShortRoad.h
 * @brief The short road of the grid advection (docs/performance.md): traces that
 * stay in their start faces end at start + v t and are read as weights on the
 * sample's 3^D neighbourhood; the other traces' reads are combined a few
 * components at a time (and, in the optional AVX2 build, 8-bit images a sample
 * at a time). The same values as TraceSample (GridSample.h), bit for bit or to
 * rounding as each function says; the GridSteps tests prove it.
 */
#ifndef GridShortRoad_h
#define GridShortRoad_h

#include "GridSample.h"

#ifdef SHOCK_GRID_AVX2
#include <immintrin.h>
#endif

namespace shock
{
namespace grid
{

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
 * the tracer: a third is where the two roads took the same time on a photo.
 * Volumes always try: most of their traces stay.
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
  TraceTally<D>& tally)
{
  std::array<std::int64_t, D> c;
  StartInFace<D>(i, b, end, c);
  TraceMarks<D> marks = tally.Marks();
  tally.Count(tracer.template Trace<Wide>(end, c, f, time, marks), marks);
}

/// TraceLeavingFace for a trace that may stay in its face, the sample's index
/// coordinates also given as doubles (`at`).
template <int D, bool Wide>
SHOCK_ALWAYS_INLINE void TraceFromSample(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, const std::array<double, D>& at, int b, std::int64_t f,
  std::array<double, D>& end, TraceTally<D>& tally)
{
  std::array<std::int64_t, D> c;
  StartInFace<D>(i, at, b, end, c);
  TraceMarks<D> marks = tally.Marks();
  tally.Count(tracer.template Trace<Wide>(end, c, f, time, marks), marks);
}

/// TraceLeavingFace kept out of line, so that a loop of traces that mostly stay
/// in their faces (3D) stays small.
template <int D, bool Wide>
SHOCK_NOINLINE void TraceLeavingFaceOutOfLine(const GridTracer<D>& tracer, double time,
  const std::array<std::int64_t, D>& i, int b, std::int64_t f, std::array<double, D>& end,
  TraceTally<D>& tally)
{
  TraceLeavingFace<D, Wide>(tracer, time, i, b, f, end, tally);
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
template <int D, int K, typename S, bool UseHood = true>
SHOCK_ALWAYS_INLINE void CombineReads(const Lattice<D>& L, const Neighbourhood<D>& hood,
  const S& source, std::int64_t s, int C, int c0, const double* weights,
  const std::array<double, D>* ends, int far, double* result)
{
  using T = SignalValue<S>;
  constexpr int Corners = Lattice<D>::Corners;
  double partial[K][4] = {};
  for (int e = 0; e < far; ++e)
  {
    // SampleGrid's multilinear read, every corner valid (the cell's corners in
    // the array of its lower corner: GridLayered.h).
    std::array<double, D> frac;
    const std::int64_t cell = LocateCell<D>(L, ends[e], frac);
    const T* lower = ValuesNear(source, cell) + cell * C + c0;
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
  // The neighbourhood's lowest layer is the one below the sample's (an interior sample).
  const T* own = ValuesNear(source, s - L.sampleStride[D - 1]) + s * C + c0;
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
template <int D, typename S, bool UseHood = true>
SHOCK_ALWAYS_INLINE void CombineAllReads(const Lattice<D>& L, const Neighbourhood<D>& hood,
  const S& source, std::int64_t s, int C, const double* weights,
  const std::array<double, D>* ends, int far, double* result)
{
  int c0 = 0;
  for (; c0 + 4 <= C; c0 += 4)
  {
    CombineReads<D, 4, S, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
  }
  switch (C - c0)
  {
    case 1:
      CombineReads<D, 1, S, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
      break;
    case 2:
      CombineReads<D, 2, S, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
      break;
    case 3:
      CombineReads<D, 3, S, UseHood>(L, hood, source, s, C, c0, weights, ends, far, result);
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
 * with Wide and `vectorReads` (D = 2, 8-bit samples in one array, C = 3 or 4)
 * its AVX2 version, which only a caller built for AVX2 may take.
 */
template <int D, typename S, bool Wide, bool UseHood = true>
SHOCK_ALWAYS_INLINE void CombineSampleReads(bool vectorReads, std::int64_t lastLower,
  const Lattice<D>& L, const Neighbourhood<D>& hood, const S& source, std::int64_t s, int C,
  const double* weights, const std::array<double, D>* ends, int far, double* result)
{
#ifdef SHOCK_GRID_AVX2
  if constexpr (Wide && D == 2 && IsOneArray<S> && std::is_same_v<SignalValue<S>, unsigned char>)
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
  CombineAllReads<D, S, UseHood>(L, hood, source, s, C, weights, ends, far, result);
}

///@}

} // namespace grid
} // namespace shock

#endif
