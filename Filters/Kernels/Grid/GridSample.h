/**
 * @file GridSample.h
 * @brief The paper's path of Appendix A on a regular grid: reading a grid
 * signal at a traced point (Sampling::Linear: multilinear; Sampling::Nearest),
 * the starts of a sample's traces at an offset into each adjacent face, and
 * AdvectVertices for one sample (TraceSample). Every sample can take this road;
 * the faster one (GridShortRoad.h) gives the same values and is tested against
 * it. Include only from translation units built with OpenMP.
 */
#ifndef GridSample_h
#define GridSample_h

#include "GridAvx2.h"
#include "GridLattice.h"
#include "GridLayered.h"
#include "GridTrace.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
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

  /// The weighted sum of component c of `values` (C components per sample; one
  /// array, or LayeredValues: each sample read from the array that holds it).
  template <typename S>
  double Apply(const S& values, int C, int c) const
  {
    const auto read = [&](int r) {
      const std::int64_t s = this->sample[r];
      return Widen(ValuesNear(values, s)[s * C + c]);
    };
    // Four partial sums: four short chains of dependent additions instead of one long one.
    double partial[4] = { 0.0, 0.0, 0.0, 0.0 };
    int r = 0;
    for (; r + 4 <= this->size; r += 4)
    {
      for (int k = 0; k < 4; ++k)
      {
        partial[k] += this->weight[r + k] * read(r + k);
      }
    }
    for (; r < this->size; ++r)
    {
      partial[0] += this->weight[r] * read(r);
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
 * One thread's account of its traces: their steps (face crossings or
 * delta-steps), how many the step cap cut, and how far beyond the tracer's
 * fence they went (TraceMarks::reach, per active axis below and above).
 */
template <int D>
struct TraceTally
{
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;
  std::array<std::int64_t, 2 * D> reach{};

  /// The marks of the next trace, its reach kept here.
  TraceMarks<D> Marks() { return TraceMarks<D>{ false, &this->reach }; }

  /// Count a trace of `n` steps that left `marks`.
  void Count(std::int64_t n, const TraceMarks<D>& marks)
  {
    this->steps += static_cast<std::uint64_t>(n);
    this->truncated += marks.truncated ? 1 : 0;
  }

  /// Add another thread's tally.
  void Merge(const TraceTally& other)
  {
    this->steps += other.steps;
    this->truncated += other.truncated;
    for (int k = 0; k < 2 * D; ++k)
    {
      this->reach[k] = std::max(this->reach[k], other.reach[k]);
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
 * Appendix A AdvectVertices for one sample i (index s), any case: traces from
 * the offset into each adjacent face (or from the stored positions), reads
 * added to `stencil`; returns the number of traces.
 */
template <int D, bool Wide = false>
int TraceSample(const AdvectionContext<D>& ctx, const GridTracer<D>& tracer, double time,
  const AdjacentFaces<D>& faces, const std::array<std::int64_t, D>& i, std::int64_t s,
  float* positions, Stencil<D>& stencil, TraceTally<D>& tally)
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
    TraceMarks<D> marks = tally.Marks();
    tally.Count(tracer.template Trace<Wide>(q, c, f, time, marks), marks);
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

} // namespace grid
} // namespace shock

#endif
