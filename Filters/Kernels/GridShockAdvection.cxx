#include "GridShockAdvection.h"
#include "GridFlow.h"
#include "GridHierarchy.h"

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
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Offset of a back-trace start from its sample towards the adjacent face centre,
// in units of the sample-to-centre distance (the paper's epsilon).
constexpr double VertexOffset = 0.001;

using namespace grid;


/**
 * Appendix A Trace on the grid, in index coordinates. The flow is constant per
 * face; a trace stops when the time is used up, when the flow reverses
 * (<v, v0> <= 0, measured in the physical metric), at the grid boundary, or at
 * the step cap that guards against cycles of the discrete flow.
 */
template <int D>
class GridTracer
{
public:
  GridTracer(const Lattice<D>& lattice, const float* velocity, const AdvectionParameters& p)
    : L(lattice)
    , V(velocity)
    , Mode(p.tracing)
    , Delta(p.stepFraction)
  {
    // A discrete gradient flow has no cycles in the continuum limit; in case the
    // discretisation creates one, cap the work per trace at a few grid diameters.
    double diameter = 0.0;
    std::int64_t samples = 0;
    for (int d = 0; d < D; ++d)
    {
      diameter += L.n[d] * L.h[d];
      samples += L.n[d];
    }
    this->MaxSteps = (this->Mode == Tracing::FaceCrossing)
      ? 8 * samples
      : static_cast<std::int64_t>(std::ceil(4.0 * diameter / this->Delta)) + 1;
  }

  /**
   * Trace q (index coordinates), which lies in face f with coordinates c (as
   * FaceOf finds them), for time t; returns the number of steps taken.
   */
  std::int64_t Trace(std::array<double, D>& q, const std::array<std::int64_t, D>& c,
    std::int64_t f, double t, bool& truncated) const
  {
    return this->Mode == Tracing::FaceCrossing ? this->TraceFaceCrossing(q, c, f, t, truncated)
                                               : this->TraceStepped(q, c, f, t, truncated);
  }

  /// The face holding q (clamped to the grid): its index, and its coordinates in c.
  std::int64_t FaceOf(const std::array<double, D>& q, std::array<std::int64_t, D>& c) const
  {
    std::int64_t f = 0;
    for (int d = 0; d < D; ++d)
    {
      c[d] = std::min<std::int64_t>(std::max<std::int64_t>(static_cast<std::int64_t>(q[d]), 0), L.m[d] - 1);
      f += c[d] * L.faceStride[d];
    }
    return f;
  }

private:
  /// Dot product of index-space velocities in the physical metric.
  template <typename A, typename B>
  double Dot(const A& a, const B& b) const
  {
    double dot = 0.0;
    for (int d = 0; d < D; ++d)
    {
      dot += L.h2[d] * a[d] * b[d];
    }
    return dot;
  }

  void Load(std::int64_t f, std::array<double, D>& v) const
  {
    for (int d = 0; d < D; ++d)
    {
      v[d] = this->V[f * D + d];
    }
  }

  /**
   * Filippov velocity on the boundary between face `lowerFace` and its upper
   * neighbour along `axis`, both pushing into it: the convex combination of their
   * velocities with no component across the boundary. False if it vanishes.
   */
  bool Sliding(std::int64_t lowerFace, int axis, std::array<double, D>& v) const
  {
    std::array<double, D> a, b;
    this->Load(lowerFace, a);
    this->Load(lowerFace + L.faceStride[axis], b);
    const double lambda = -b[axis] / (a[axis] - b[axis]);
    for (int d = 0; d < D; ++d)
    {
      v[d] = lambda * a[d] + (1.0 - lambda) * b[d];
    }
    v[axis] = 0.0;
    return this->Dot(v, v) > 0.0;
  }

  /**
   * Exact tracing: straight to the next face boundary, then into the neighbour.
   * Where both faces of a boundary push towards it (a valley of the potential
   * crossed by the back-trace), the trace slides along the boundary with the
   * Filippov velocity, the convex combination of the two flows that is tangent
   * to it: this is the delta -> 0 limit of the zig-zag of the stepped trace.
   * Where the trace is pushed onto a grid edge or corner from several faces at
   * once, the exact rule is not unique; the rest of that trace uses the paper's
   * stepping, which zig-zags along the edge (or stops at a sink).
   */
  std::int64_t TraceFaceCrossing(std::array<double, D>& q, std::array<std::int64_t, D> c,
    std::int64_t f, double t, bool& truncated) const
  {
    std::array<double, D> v;
    this->Load(f, v);
    if (!(this->Dot(v, v) > 0.0))
    {
      return 0;
    }
    int pinned = -1; // axis of the boundary the trace slides on; c is the lower face there
    std::int64_t steps = 0;
    while (t > 0.0)
    {
      // First boundary reached; written with selects rather than branches, as
      // the exit axis is unpredictable (a division by 0 is computed, then ignored).
      double exitTime = std::numeric_limits<double>::infinity();
      int exitAxis = -1;
      for (int d = 0; d < D; ++d)
      {
        const double distance = v[d] > 0.0 ? c[d] + 1 - q[d] : c[d] - q[d];
        const double quotient = distance / v[d];
        const double te =
          (d == pinned || v[d] == 0.0) ? std::numeric_limits<double>::infinity() : quotient;
        exitAxis = te < exitTime ? d : exitAxis;
        exitTime = te < exitTime ? te : exitTime;
      }
      if (exitAxis < 0)
      {
        break; // no motion left (a sliding velocity of zero)
      }
      exitTime = std::max(exitTime, 0.0);
      if (exitTime >= t)
      {
        for (int d = 0; d < D; ++d)
        {
          q[d] += v[d] * t;
        }
        break;
      }
      for (int d = 0; d < D; ++d)
      {
        q[d] += v[d] * exitTime;
      }
      t -= exitTime;
      const int dir = v[exitAxis] > 0.0 ? 1 : -1;
      q[exitAxis] = static_cast<double>(dir > 0 ? c[exitAxis] + 1 : c[exitAxis]);
      ++steps;
      const std::int64_t next = c[exitAxis] + dir;
      if (next < 0 || next >= L.m[exitAxis])
      {
        break; // grid boundary
      }
      if (steps >= this->MaxSteps)
      {
        truncated = true;
        break;
      }
      const std::int64_t left = f;
      c[exitAxis] = next;
      f += dir * L.faceStride[exitAxis];

      std::array<double, D> w;
      if (pinned < 0)
      {
        this->Load(f, w);
        if (!(this->Dot(w, v) > 0.0))
        {
          break; // the flow reverses: a ridge of the potential
        }
        if (w[exitAxis] * dir < 0.0)
        {
          // Both faces push towards the boundary just crossed: slide along it.
          pinned = exitAxis;
          if (dir > 0)
          {
            c[pinned] -= 1;
            f = left;
          }
          if (!this->Sliding(f, pinned, w))
          {
            break;
          }
        }
      }
      else
      {
        // Sliding into the next pair of faces along the pinned boundary.
        std::array<double, D> lower, upper;
        this->Load(f, lower);
        this->Load(f + L.faceStride[pinned], upper);
        if (lower[pinned] > 0.0 && upper[pinned] < 0.0)
        {
          this->Sliding(f, pinned, w);
        }
        else
        {
          // Leave the boundary into a face that does not push back into it.
          const bool lowerOk = lower[pinned] <= 0.0;
          const bool upperOk = upper[pinned] >= 0.0;
          const bool takeUpper =
            upperOk && (!lowerOk || this->Dot(upper, v) > this->Dot(lower, v));
          if (takeUpper)
          {
            c[pinned] += 1;
            f += L.faceStride[pinned];
          }
          w = takeUpper ? upper : lower;
          pinned = -1;
        }
        if (!(this->Dot(w, v) > 0.0))
        {
          break; // the flow reverses
        }
      }
      if (w[exitAxis] * dir < 0.0 && exitAxis != pinned)
      {
        // Pushed onto an edge or corner.
        this->ClampToGrid(q);
        const std::int64_t face = this->FaceOf(q, c);
        return steps + this->TraceStepped(q, c, face, t, truncated);
      }
      v = w;
    }
    this->ClampToGrid(q);
    return steps;
  }

  std::int64_t TraceStepped(std::array<double, D>& q, std::array<std::int64_t, D> c,
    std::int64_t f, double t, bool& truncated) const
  {
    const float* v = this->V + f * D;
    const float* v0 = v;
    std::int64_t steps = 0;
    while (t > 0.0 && this->Dot(v, v0) > 0.0)
    {
      const double speed = std::sqrt(this->Dot(v, v));
      const double dt = std::min(t, this->Delta / speed);
      bool outside = false;
      for (int d = 0; d < D; ++d)
      {
        q[d] += v[d] * dt;
        outside = outside || q[d] < 0.0 || q[d] > static_cast<double>(L.m[d]);
      }
      t -= dt;
      ++steps;
      if (outside)
      {
        break; // grid boundary
      }
      if (steps >= this->MaxSteps)
      {
        truncated = true;
        break;
      }
      v0 = v;
      v = this->V + this->FaceOf(q, c) * D;
    }
    this->ClampToGrid(q);
    return steps;
  }

  void ClampToGrid(std::array<double, D>& q) const
  {
    for (int d = 0; d < D; ++d)
    {
      q[d] = std::min(std::max(q[d], 0.0), static_cast<double>(L.m[d]));
    }
  }

  const Lattice<D>& L;
  const float* V;
  Tracing Mode;
  double Delta;
  std::int64_t MaxSteps = 0;
};

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
  double Apply(const double* values, int C, int c) const
  {
    // Four partial sums: four short chains of dependent additions instead of one long one.
    double partial[4] = { 0.0, 0.0, 0.0, 0.0 };
    int r = 0;
    for (; r + 4 <= this->size; r += 4)
    {
      for (int k = 0; k < 4; ++k)
      {
        partial[k] += this->weight[r + k] * values[this->sample[r + k] * C + c];
      }
    }
    for (; r < this->size; ++r)
    {
      partial[0] += this->weight[r] * values[this->sample[r] * C + c];
    }
    return (partial[0] + partial[1]) + (partial[2] + partial[3]);
  }
};

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
  std::int64_t base = 0;
  std::array<double, D> frac;
  for (int d = 0; d < D; ++d)
  {
    const std::int64_t cell = std::min<std::int64_t>(static_cast<std::int64_t>(q[d]), L.m[d] - 1);
    frac[d] = q[d] - static_cast<double>(cell);
    base += cell * L.sampleStride[d];
  }
  double weights[Lattice<D>::Corners];
  double total = 0.0;
  for (int b = 0; b < Lattice<D>::Corners; ++b)
  {
    double w = 1.0;
    for (int d = 0; d < D; ++d)
    {
      w *= ((b >> d) & 1) ? frac[d] : 1.0 - frac[d];
    }
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
 * Appendix A AdvectVertices: every valid sample is traced from an offset into
 * each adjacent face, the source signal is sampled at the traced points and the
 * results are averaged. With `positions` (Composed flow; D floats per sample and
 * corner pattern), traces resume from and update the stored positions instead
 * of starting at the offsets.
 * Returns false when aborted through the progress callback.
 */
template <int D>
bool AdvectVertices(const AdvectionContext<D>& ctx, const GridTracer<D>& tracer, double time,
  const double* source, double* out, float* positions, double progressStart, double progressSpan)
{
  const Lattice<D>& L = ctx.L;
  const int C = ctx.C;
  const unsigned char* valid = ctx.valid;
  constexpr int Corners = Lattice<D>::Corners;
  const RowBlocks<D> blocks(L.n);
  // Progress is reported, and an abort honoured, between chunks of blocks.
  const std::int64_t chunkCount =
    std::max<std::int64_t>(1, std::min<std::int64_t>(64, L.numSamples / 8192));
  const std::int64_t chunkSize = (blocks.Count() + chunkCount - 1) / chunkCount;
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;

  for (std::int64_t chunk = 0; chunk < chunkCount; ++chunk)
  {
    const std::int64_t begin = chunk * chunkSize;
    const std::int64_t end = std::min(blocks.Count(), begin + chunkSize);
#pragma omp parallel for schedule(dynamic) num_threads(ctx.threads) reduction(+ : steps, truncated)
    for (std::int64_t k = begin; k < end; ++k)
    {
      std::array<std::int64_t, D> i;
      const std::int64_t length = blocks.Get(k, i);
      const std::int64_t x0 = i[0];
      const std::int64_t s0 = L.SampleIndex(i);
      const AdjacentFaces<D> faces(L, i);
      for (std::int64_t j = 0; j < length; ++j)
      {
        const std::int64_t s = s0 + j;
        i[0] = x0 + j;
        double* result = out + s * C;
        if (valid && !valid[s])
        {
          std::copy(source + s * C, source + (s + 1) * C, result);
          continue;
        }
        // The traces' reads are gathered first, then combined per component in
        // registers (no read-modify-write of the output per corner).
        Stencil<D> stencil;
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
            // The start lies in face f, whose coordinates are the sample's minus the corner bits.
            for (int d = 0; d < D; ++d)
            {
              const int bit = (b >> d) & 1;
              c[d] = i[d] - bit;
              q[d] = static_cast<double>(i[d]) + VertexOffset * (0.5 - bit);
            }
          }
          bool cut = false;
          steps += static_cast<std::uint64_t>(tracer.Trace(q, c, f, time, cut));
          truncated += cut ? 1 : 0;
          if (stored)
          {
            std::copy(q.begin(), q.end(), stored);
          }
          if (!SampleGrid<D>(L, valid, ctx.sampling, q, stencil))
          {
            stencil.Add(s, 1.0); // only non-finite samples around q: keep the sample's own value
          }
          ++traces;
        }
        for (int c = 0; c < C; ++c)
        {
          result[c] = stencil.Apply(source, C, c) / traces;
        }
      }
    }
    if (ctx.progress &&
      !ctx.progress(progressStart + progressSpan * static_cast<double>(end) / blocks.Count()))
    {
      ctx.report.traceSteps += steps;
      ctx.report.truncatedTraces += truncated;
      return false;
    }
  }
  ctx.report.traceSteps += steps;
  ctx.report.truncatedTraces += truncated;
  return true;
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

    const auto advectStart = Clock::now();
    const GridTracer<D> tracer(L, flow.Velocity(), p);
    // Fixed and Composed flows sample the input (Composed from the composed
    // positions, its result feeding the next flow); Naive resamples the last result.
    const bool naive = p.flowMode == FlowMode::Naive;
    const double* source = naive ? signal : input;
    double* target = naive && (updates - 1 - k) % 2 == 1 ? naiveBuffer.get() : output;
    if (levels.size() > 1)
    {
      // Coarse-to-fine (GridHierarchy.h): the traces cross the coarser levels first;
      // a Naive step starts them afresh, as it does without levels.
      if (naive && k > 0)
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

namespace grid
{
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

template void TraceStoredPositions<1>(const Lattice<1>&, const float*, const AdvectionParameters&,
  double, const std::array<double, 1>&, float*, std::int64_t, int, AdvectionReport&);
template void TraceStoredPositions<2>(const Lattice<2>&, const float*, const AdvectionParameters&,
  double, const std::array<double, 2>&, float*, std::int64_t, int, AdvectionReport&);
template void TraceStoredPositions<3>(const Lattice<3>&, const float*, const AdvectionParameters&,
  double, const std::array<double, 3>&, float*, std::int64_t, int, AdvectionReport&);
} // namespace grid

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
