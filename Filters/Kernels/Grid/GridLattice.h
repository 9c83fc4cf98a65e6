/**
 * @file GridLattice.h
 * @brief The regular grid as the grid kernels see it: the lattice of active
 * axes with strides and normalised spacings, row-blocked loops over samples and
 * faces, the faces adjacent to a sample, and the validity masks of non-finite
 * samples. Loops use OpenMP: include only from translation units built with it.
 */
#ifndef GridLattice_h
#define GridLattice_h

#include "GridLayered.h"
#include "GridShape.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace shock
{
namespace grid
{

// Elements per work unit of the row-wise loops (see RowBlocks).
constexpr std::int64_t BlockLength = 256;

/// The active axes of a grid, with strides and normalised spacings.
template <int D>
struct Lattice
{
  static constexpr int Corners = 1 << D;
  std::array<int, D> axis{};                // grid axis (0..2) of each active axis
  std::array<std::int64_t, D> n{};          // samples per active axis (>= 2)
  std::array<std::int64_t, D> m{};          // faces per active axis (n - 1)
  std::array<std::int64_t, D> wholeN{};     // samples per active axis of the whole grid (GridShape::wholeDimensions)
  std::array<std::int64_t, D> sampleStride{};
  std::array<std::int64_t, D> faceStride{};
  std::array<double, D> h{};                // spacing / mean edge length
  std::array<double, D> h2{};               // h^2: metric for dot products of index velocities
  std::array<double, D> meanDifference{};   // 1 / (edges per axis x h): mean edge difference to gradient
  std::array<std::int64_t, Corners> corner{}; // sample offset of face corner with bit pattern b
  std::int64_t numSamples = 0;
  std::int64_t numFaces = 0;

  explicit Lattice(const GridShape& shape)
  {
    const double meanEdge = shape.MeanEdgeLength();
    std::int64_t stride = 1;
    int k = 0;
    for (int a = 0; a < 3; ++a)
    {
      if (shape.dimensions[a] > 1)
      {
        this->axis[k] = a;
        this->n[k] = shape.dimensions[a];
        this->m[k] = shape.dimensions[a] - 1;
        this->wholeN[k] = shape.WholeDimension(a);
        this->sampleStride[k] = stride;
        this->h[k] = shape.spacing[a] / meanEdge;
        this->h2[k] = this->h[k] * this->h[k];
        // A face has 2^(D-1) edges along each axis.
        this->meanDifference[k] = 1.0 / (static_cast<double>(Corners / 2) * this->h[k]);
        ++k;
      }
      stride *= shape.dimensions[a];
    }
    this->numSamples = stride;
    this->numFaces = 1;
    for (int d = 0; d < D; ++d)
    {
      this->faceStride[d] = this->numFaces;
      this->numFaces *= this->m[d];
    }
    for (int b = 0; b < Corners; ++b)
    {
      std::int64_t offset = 0;
      for (int d = 0; d < D; ++d)
      {
        offset += ((b >> d) & 1) ? this->sampleStride[d] : 0;
      }
      this->corner[b] = offset;
    }
  }

  /**
   * The lattice of the first `layers` (>= 2) sample layers along the last active
   * axis, with this lattice's strides and normalised spacings: a slab, addressed
   * from a pointer to its first layer.
   */
  Lattice Layers(std::int64_t layers) const
  {
    Lattice slab = *this;
    slab.n[D - 1] = layers;
    slab.m[D - 1] = layers - 1;
    slab.numSamples = this->sampleStride[D - 1] * layers;
    slab.numFaces = this->faceStride[D - 1] * (layers - 1);
    return slab;
  }

  /// Index of the sample with coordinates i; also the lower corner of the face with coordinates i.
  std::int64_t SampleIndex(const std::array<std::int64_t, D>& i) const
  {
    std::int64_t s = 0;
    for (int d = 0; d < D; ++d)
    {
      s += i[d] * this->sampleStride[d];
    }
    return s;
  }

  std::int64_t FaceIndex(const std::array<std::int64_t, D>& c) const
  {
    std::int64_t f = 0;
    for (int d = 0; d < D; ++d)
    {
      f += c[d] * this->faceStride[d];
    }
    return f;
  }
};

/**
 * Work units of the row-wise loops over the samples (extent n) or the faces
 * (extent m) of a lattice: runs of at most BlockLength consecutive elements of one
 * row along the first active axis, which has stride 1. A loop over a block steps
 * along x without decomposing indices into coordinates, and long rows (1D grids
 * in particular) still spread over the threads.
 */
template <int D>
class RowBlocks
{
public:
  explicit RowBlocks(const std::array<std::int64_t, D>& extent)
    : RowBlocks(std::array<std::int64_t, D>{}, extent)
  {
  }

  /// The blocks of the box from `begin` (included) to `end` (excluded) per axis.
  RowBlocks(const std::array<std::int64_t, D>& begin, const std::array<std::int64_t, D>& end)
    : Begin(begin)
  {
    for (int d = 0; d < D; ++d)
    {
      this->Extent[d] = std::max<std::int64_t>(0, end[d] - begin[d]);
    }
    this->PerRow = (this->Extent[0] + BlockLength - 1) / BlockLength;
    this->Total = this->PerRow;
    for (int d = 1; d < D; ++d)
    {
      this->Total *= this->Extent[d];
    }
  }

  std::int64_t Count() const { return this->Total; }

  /// Block k: sets the coordinates of its first element and returns its length.
  std::int64_t Get(std::int64_t k, std::array<std::int64_t, D>& first) const
  {
    std::int64_t row = k / this->PerRow;
    first[0] = this->Begin[0] + (k - row * this->PerRow) * BlockLength;
    for (int d = 1; d < D; ++d)
    {
      first[d] = this->Begin[d] + row % this->Extent[d];
      row /= this->Extent[d];
    }
    return std::min(BlockLength, this->Begin[0] + this->Extent[0] - first[0]);
  }

private:
  std::array<std::int64_t, D> Begin;
  std::array<std::int64_t, D> Extent;
  std::int64_t PerRow;
  std::int64_t Total = 0;
};

/**
 * The blocks of the samples whose results a run hands to its output
 * (AdvectionParameters::writtenSamples, given per grid axis): every sample by default.
 */
template <int D>
RowBlocks<D> WrittenBlocks(const Lattice<D>& L, const std::array<std::int64_t, 6>& written)
{
  std::array<std::int64_t, D> begin{};
  std::array<std::int64_t, D> end = L.n;
  for (int d = 0; d < D; ++d)
  {
    const int a = L.axis[d];
    if (written[2 * a] <= written[2 * a + 1])
    {
      begin[d] = written[2 * a];
      end[d] = written[2 * a + 1] + 1;
    }
  }
  return RowBlocks<D>(begin, end);
}

/**
 * The row-blocked loop over an extent (the samples' n or the faces' m), in
 * parallel (static schedule): body(first, length) for each block (RowBlocks)
 * of `length` elements along the first axis, the first at coordinates `first`.
 */
template <int D, typename Body>
void ForEachBlock(const std::array<std::int64_t, D>& extent, int threads, const Body& body)
{
  const RowBlocks<D> blocks(extent);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t k = 0; k < blocks.Count(); ++k)
  {
    std::array<std::int64_t, D> first;
    const std::int64_t length = blocks.Get(k, first);
    body(first, length);
  }
}

/// ForEachBlock over the samples of L: body(i, s0, length), s0 the sample index of i.
template <int D, typename Body>
void ForEachSampleBlock(const Lattice<D>& L, int threads, const Body& body)
{
  ForEachBlock<D>(L.n, threads, [&](const std::array<std::int64_t, D>& i, std::int64_t length) {
    body(i, L.SampleIndex(i), length);
  });
}

/// ForEachBlock over the faces of L: body(f0, base0, length), f0 the face index
/// of the first face and base0 the sample index of its lower corner.
template <int D, typename Body>
void ForEachFaceBlock(const Lattice<D>& L, int threads, const Body& body)
{
  ForEachBlock<D>(L.m, threads, [&](const std::array<std::int64_t, D>& c, std::int64_t length) {
    body(L.FaceIndex(c), L.SampleIndex(c), length);
  });
}

/**
 * The faces adjacent to the samples of one row. A sample's face through corner
 * bit pattern b has coordinates i - bits(b); the bits along the axes other than
 * the first are the same for the whole row, so their rows of faces are found once.
 */
template <int D>
class AdjacentFaces
{
public:
  AdjacentFaces(const Lattice<D>& lattice, const std::array<std::int64_t, D>& i)
    : L(lattice)
  {
    for (int r = 0; r < Lattice<D>::Corners / 2; ++r)
    {
      std::int64_t f = 0;
      bool inside = true;
      for (int d = 1; d < D; ++d)
      {
        const std::int64_t c = i[d] - ((r >> (d - 1)) & 1);
        inside = inside && c >= 0 && c < L.m[d];
        f += c * L.faceStride[d];
      }
      this->RowStarts[r] = inside ? f : -1;
    }
  }

  /// The face at x = 0 of the row of faces through corner patterns 2r and 2r + 1; -1 outside.
  std::int64_t RowStart(int r) const { return this->RowStarts[r]; }

  /// The face adjacent to sample x of the row through corner pattern b; -1 outside the grid.
  std::int64_t Face(std::int64_t x, int b) const
  {
    const std::int64_t start = this->RowStarts[b >> 1];
    const std::int64_t fx = x - (b & 1);
    return (start < 0 || fx < 0 || fx >= L.m[0]) ? -1 : start + fx;
  }

private:
  const Lattice<D>& L;
  std::array<std::int64_t, Lattice<D>::Corners / 2> RowStarts{}; // face at x = 0, or -1
};

/// Data range over the samples whose components are all finite.
struct SignalRange
{
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  bool allFinite = true;
};

/// The range and finiteness of a signal in one parallel pass (min and max are
/// exact, so any thread count gives the same range).
template <typename T>
SignalRange ScanSignal(std::int64_t numSamples, int components, const T* values, int threads)
{
  if constexpr (std::is_integral_v<T>)
  {
    // Integers are finite: the range alone, in T, each thread over a
    // contiguous part with a plain loop, which the compiler vectorises (an
    // OpenMP simd reduction over the whole array did not: 4 ms for an 8-bit
    // photo's 7.5M values on one thread).
    const std::int64_t count = numSamples * components;
    T lowest = std::numeric_limits<T>::max();
    T highest = std::numeric_limits<T>::lowest();
    const int parts = std::max(1, threads);
#pragma omp parallel for schedule(static) num_threads(threads) \
  reduction(min : lowest) reduction(max : highest)
    for (int part = 0; part < parts; ++part)
    {
      const T* first = values + count * part / parts;
      const T* last = values + count * (part + 1) / parts;
      T low = std::numeric_limits<T>::max();
      T high = std::numeric_limits<T>::lowest();
      for (const T* v = first; v < last; ++v)
      {
        low = std::min(low, *v);
        high = std::max(high, *v);
      }
      lowest = std::min(lowest, low);
      highest = std::max(highest, high);
    }
    return { static_cast<double>(lowest), static_cast<double>(highest), true };
  }
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  bool allFinite = true;
#pragma omp parallel for schedule(static) num_threads(threads) \
  reduction(min : low) reduction(max : high) reduction(&& : allFinite)
  for (std::int64_t s = 0; s < numSamples; ++s)
  {
    const T* v = values + s * components;
    bool finite = true;
    for (int c = 0; c < components; ++c)
    {
      finite = finite && std::isfinite(v[c]);
    }
    if (!finite)
    {
      allFinite = false;
      continue;
    }
    for (int c = 0; c < components; ++c)
    {
      low = std::min(low, static_cast<double>(v[c]));
      high = std::max(high, static_cast<double>(v[c]));
    }
  }
  return { low, high, allFinite };
}

/// Per-sample validity: all components finite.
template <typename T>
std::vector<unsigned char> FiniteSamples(
  std::int64_t numSamples, int components, const T* values, int threads)
{
  std::vector<unsigned char> valid(static_cast<size_t>(numSamples));
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t s = 0; s < numSamples; ++s)
  {
    const T* v = values + s * components;
    valid[s] = std::all_of(v, v + components, [](T x) { return std::isfinite(x); });
  }
  return valid;
}

/// Faces whose corners are all valid samples; only they carry gradients and flow.
template <int D>
std::vector<unsigned char> ValidFaces(
  const Lattice<D>& L, const unsigned char* validSample, int threads)
{
  std::vector<unsigned char> valid(static_cast<size_t>(L.numFaces));
  ForEachFaceBlock<D>(L, threads, [&](std::int64_t f0, std::int64_t base0, std::int64_t length) {
    for (std::int64_t j = 0; j < length; ++j)
    {
      bool all = true;
      for (int b = 0; b < Lattice<D>::Corners; ++b)
      {
        all = all && validSample[base0 + j + L.corner[b]];
      }
      valid[f0 + j] = all;
    }
  });
  return valid;
}

/// ScanSignal of a layered signal (GridLayered.h): each array's own samples.
template <typename T>
SignalRange ScanSignal(std::int64_t numSamples, int components, const LayeredValues<T>& values, int threads)
{
  SignalRange all;
  ForEachRun(values, 0, numSamples, [&](std::int64_t first, std::int64_t count, const T* array) {
    const SignalRange part = ScanSignal(count, components, array + first * components, threads);
    all.low = std::min(all.low, part.low);
    all.high = std::max(all.high, part.high);
    all.allFinite = all.allFinite && part.allFinite;
  });
  return all;
}

/// FiniteSamples of a layered signal (GridLayered.h).
template <typename T>
std::vector<unsigned char> FiniteSamples(
  std::int64_t numSamples, int components, const LayeredValues<T>& values, int threads)
{
  std::vector<unsigned char> valid(static_cast<size_t>(numSamples));
  ForEachRun(values, 0, numSamples, [&](std::int64_t first, std::int64_t count, const T* array) {
    const std::vector<unsigned char> part = FiniteSamples(count, components, array + first * components, threads);
    std::copy(part.begin(), part.end(), valid.begin() + first);
  });
  return valid;
}

/// Validity masks of a signal: both empty, and null pointers, when every sample is finite.
template <int D>
struct ValidityMasks
{
  std::vector<unsigned char> samples, faces;

  template <typename S>
  ValidityMasks(const Lattice<D>& L, int C, const S& values, bool allFinite, int threads)
  {
    if (!allFinite)
    {
      this->samples = FiniteSamples(L.numSamples, C, values, threads);
      this->faces = ValidFaces<D>(L, this->samples.data(), threads);
    }
  }
  const unsigned char* Samples() const { return this->samples.empty() ? nullptr : this->samples.data(); }
  const unsigned char* Faces() const { return this->faces.empty() ? nullptr : this->faces.data(); }
};

/// Hands `values` (the whole signal) to `output`, in parallel runs.
template <typename T>
void WriteSignal(std::int64_t numSamples, int C, const T* values, const SampleWriter& output,
  int threads)
{
  const std::int64_t run = BlockLength;
  const std::int64_t runs = (numSamples + run - 1) / run;
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> row(static_cast<size_t>(run * C));
#pragma omp for schedule(static)
    for (std::int64_t r = 0; r < runs; ++r)
    {
      const std::int64_t first = r * run;
      const std::int64_t count = std::min(run, numSamples - first);
      std::copy(values + first * C, values + (first + count) * C, row.data());
      output(first, count, row.data());
    }
  }
}

/// The samples of `blocks` handed unchanged to `output` (the values of a run without flow).
template <int D, typename S>
void WriteSignal(const Lattice<D>& L, const RowBlocks<D>& blocks, int C, const S& values,
  const SampleWriter& output, int threads)
{
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> row(static_cast<size_t>(BlockLength * C));
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < blocks.Count(); ++k)
    {
      std::array<std::int64_t, D> i;
      const std::int64_t count = blocks.Get(k, i);
      const std::int64_t first = L.SampleIndex(i);
      CopySamples(values, C, first, count, row.data());
      output(first, count, row.data());
    }
  }
}

} // namespace grid
} // namespace shock

#endif
