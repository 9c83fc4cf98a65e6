#include "GridShockAdvection.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace shock
{

int ResolveThreadCount(int requested)
{
  return requested > 0 ? requested : std::max(1, omp_get_num_procs());
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

/// The active axes of a grid, with strides and normalised spacings.
template <int D>
struct Lattice
{
  static constexpr int Corners = 1 << D;
  std::array<int, D> axis{};                // grid axis (0..2) of each active axis
  std::array<std::int64_t, D> n{};          // samples per active axis (>= 2)
  std::array<std::int64_t, D> m{};          // faces per active axis (n - 1)
  std::array<std::int64_t, D> sampleStride{};
  std::array<std::int64_t, D> faceStride{};
  std::array<double, D> h{};                // spacing / mean edge length
  std::array<double, D> h2{};               // h^2: metric for dot products of index velocities
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
        this->sampleStride[k] = stride;
        this->h[k] = shape.spacing[a] / meanEdge;
        this->h2[k] = this->h[k] * this->h[k];
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

  // Greedy decomposition from the largest stride; the first active axis always
  // has stride 1 (flat axes before it have one sample), so D - 1 divisions.
  std::array<std::int64_t, D> SampleCoordinates(std::int64_t s) const
  {
    return Decompose(s, this->sampleStride);
  }

  std::array<std::int64_t, D> FaceCoordinates(std::int64_t f) const
  {
    return Decompose(f, this->faceStride);
  }

  static std::array<std::int64_t, D> Decompose(
    std::int64_t index, const std::array<std::int64_t, D>& stride)
  {
    std::array<std::int64_t, D> i{};
    for (int d = D - 1; d > 0; --d)
    {
      i[d] = index / stride[d];
      index -= i[d] * stride[d];
    }
    i[0] = index;
    return i;
  }

  std::int64_t FaceBaseSample(const std::array<std::int64_t, D>& c) const
  {
    std::int64_t s = 0;
    for (int d = 0; d < D; ++d)
    {
      s += c[d] * this->sampleStride[d];
    }
    return s;
  }
};

/// Per-sample validity: all components finite.
std::vector<unsigned char> FiniteSamples(
  std::int64_t numSamples, int components, const double* values, bool& allValid)
{
  std::vector<unsigned char> valid(static_cast<size_t>(numSamples), 1);
  allValid = true;
  for (std::int64_t s = 0; s < numSamples; ++s)
  {
    for (int c = 0; c < components; ++c)
    {
      if (!std::isfinite(values[s * components + c]))
      {
        valid[s] = 0;
        allValid = false;
        break;
      }
    }
  }
  return valid;
}

/**
 * Appendix A umbrella smoothing with Gaussian weights exp(-|(v-w)/l|^2) over the
 * grid one-ring (the 2D neighbours along the active axes). Invalid samples neither
 * change nor contribute.
 */
template <int D>
void UmbrellaSmooth(const Lattice<D>& L, int C, std::vector<double>& values,
  const std::vector<unsigned char>& valid, int passes, int threads)
{
  if (passes <= 0)
  {
    return;
  }
  std::array<double, D> alpha{};
  for (int d = 0; d < D; ++d)
  {
    alpha[d] = std::exp(-L.h2[d]);
  }
  std::vector<double> smoothed(values.size());
  for (int pass = 0; pass < passes; ++pass)
  {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t s = 0; s < L.numSamples; ++s)
    {
      double* out = &smoothed[s * C];
      const double* self = &values[s * C];
      std::copy(self, self + C, out);
      if (!valid[s])
      {
        continue;
      }
      const auto i = L.SampleCoordinates(s);
      double weight = 1.0;
      for (int d = 0; d < D; ++d)
      {
        for (int dir = -1; dir <= 1; dir += 2)
        {
          const std::int64_t j = i[d] + dir;
          const std::int64_t w = s + dir * L.sampleStride[d];
          if (j < 0 || j >= L.n[d] || !valid[w])
          {
            continue;
          }
          weight += alpha[d];
          for (int c = 0; c < C; ++c)
          {
            out[c] += alpha[d] * values[w * C + c];
          }
        }
      }
      for (int c = 0; c < C; ++c)
      {
        out[c] /= weight;
      }
    }
    values.swap(smoothed);
  }
}

/// Face gradient of channel c: per axis, the mean finite difference over the face's parallel edges.
template <int D>
std::array<double, D> FaceGradient(
  const Lattice<D>& L, const double* values, int C, int c, std::int64_t base)
{
  std::array<double, D> g{};
  constexpr double edgesPerAxis = Lattice<D>::Corners / 2;
  for (int d = 0; d < D; ++d)
  {
    double sum = 0.0;
    for (int b = 0; b < Lattice<D>::Corners; ++b)
    {
      if (!((b >> d) & 1))
      {
        sum += values[(base + L.corner[b | (1 << d)]) * C + c] - values[(base + L.corner[b]) * C + c];
      }
    }
    g[d] = sum / (edgesPerAxis * L.h[d]);
  }
  return g;
}

/// Faces whose corners are all valid samples; only they carry gradients and flow.
template <int D>
std::vector<unsigned char> ValidFaces(
  const Lattice<D>& L, const std::vector<unsigned char>& validSample, int threads)
{
  std::vector<unsigned char> valid(static_cast<size_t>(L.numFaces), 1);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t f = 0; f < L.numFaces; ++f)
  {
    const std::int64_t base = L.FaceBaseSample(L.FaceCoordinates(f));
    for (int b = 0; b < Lattice<D>::Corners; ++b)
    {
      if (!validSample[base + L.corner[b]])
      {
        valid[f] = 0;
        break;
      }
    }
  }
  return valid;
}

/**
 * Potential P: |grad I|^2 per face summed over channels (section 3.3 coupling),
 * averaged over each sample's valid adjacent faces (all faces have equal area).
 */
template <int D>
std::vector<double> SamplePotential(const Lattice<D>& L, int C, const std::vector<double>& signal,
  const std::vector<unsigned char>& validFace, int threads)
{
  std::vector<double> energy(static_cast<size_t>(L.numFaces), 0.0);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t f = 0; f < L.numFaces; ++f)
  {
    if (!validFace[f])
    {
      continue;
    }
    const std::int64_t base = L.FaceBaseSample(L.FaceCoordinates(f));
    double e = 0.0;
    for (int c = 0; c < C; ++c)
    {
      const auto g = FaceGradient<D>(L, signal.data(), C, c, base);
      for (int d = 0; d < D; ++d)
      {
        e += g[d] * g[d];
      }
    }
    energy[f] = e;
  }

  std::vector<double> potential(static_cast<size_t>(L.numSamples), 0.0);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t s = 0; s < L.numSamples; ++s)
  {
    const auto i = L.SampleCoordinates(s);
    double sum = 0.0;
    int count = 0;
    for (int b = 0; b < Lattice<D>::Corners; ++b)
    {
      std::int64_t f = 0;
      bool inside = true;
      for (int d = 0; d < D && inside; ++d)
      {
        const std::int64_t c = i[d] - ((b >> d) & 1);
        inside = c >= 0 && c < L.m[d];
        f += c * L.faceStride[d];
      }
      if (inside && validFace[f])
      {
        sum += energy[f];
        ++count;
      }
    }
    potential[s] = count > 0 ? sum / count : 0.0;
  }
  return potential;
}

/// Back-trace velocity per face in index units: -u / h with u = 1/2 grad P.
template <int D>
std::vector<float> BackTraceVelocity(const Lattice<D>& L, const std::vector<double>& potential,
  const std::vector<unsigned char>& validFace, int threads)
{
  std::vector<float> velocity(static_cast<size_t>(L.numFaces * D), 0.0f);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t f = 0; f < L.numFaces; ++f)
  {
    if (!validFace[f])
    {
      continue;
    }
    const auto g = FaceGradient<D>(L, potential.data(), 1, 0, L.FaceBaseSample(L.FaceCoordinates(f)));
    for (int d = 0; d < D; ++d)
    {
      velocity[f * D + d] = static_cast<float>(-0.5 * g[d] / L.h[d]);
    }
  }
  return velocity;
}

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

  /// Trace q (index coordinates) for time t; returns the number of steps taken.
  std::int64_t Trace(std::array<double, D>& q, double t, bool& truncated) const
  {
    return this->Mode == Tracing::FaceCrossing ? this->TraceFaceCrossing(q, t, truncated)
                                               : this->TraceStepped(q, t, truncated);
  }

private:
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
  std::int64_t TraceFaceCrossing(std::array<double, D>& q, double t, bool& truncated) const
  {
    std::array<std::int64_t, D> c;
    std::int64_t f = this->FaceOf(q, c);
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
      double exitTime = std::numeric_limits<double>::infinity();
      int exitAxis = -1;
      for (int d = 0; d < D; ++d)
      {
        if (d == pinned || v[d] == 0.0)
        {
          continue;
        }
        const double te = (v[d] > 0.0 ? c[d] + 1 - q[d] : c[d] - q[d]) / v[d];
        if (te < exitTime)
        {
          exitTime = te;
          exitAxis = d;
        }
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
        this->ClampToGrid(q);
        return steps + this->TraceStepped(q, t, truncated); // pushed onto an edge or corner
      }
      v = w;
    }
    this->ClampToGrid(q);
    return steps;
  }

  std::int64_t TraceStepped(std::array<double, D>& q, double t, bool& truncated) const
  {
    std::array<std::int64_t, D> c;
    const float* v = this->V + this->FaceOf(q, c) * D;
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

/**
 * Reads a grid signal at index position q, adding weight x value into acc.
 * Linear: multilinear interpolation over the valid corners of the cell holding q.
 * Nearest: the nearest sample (the linear rule if that sample is invalid).
 * Returns false when no valid sample is available.
 */
template <int D>
bool SampleGrid(const Lattice<D>& L, const double* values, int C,
  const unsigned char* valid, Sampling sampling, const std::array<double, D>& q, double* acc)
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
      for (int c = 0; c < C; ++c)
      {
        acc[c] += values[s * C + c];
      }
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
    if (valid && !valid[base + L.corner[b]])
    {
      w = 0.0;
    }
    weights[b] = w;
    total += w;
  }
  if (!(total > 0.0))
  {
    return false;
  }
  for (int b = 0; b < Lattice<D>::Corners; ++b)
  {
    if (weights[b] != 0.0)
    {
      const double* v = values + (base + L.corner[b]) * C;
      const double w = weights[b] / total;
      for (int c = 0; c < C; ++c)
      {
        acc[c] += w * v[c];
      }
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
  const std::vector<unsigned char>& valid;
  bool allValid;
  const ProgressFunction& progress;
  AdvectionReport& report;
};

/**
 * Appendix A AdvectVertices: every valid sample is traced from an offset into
 * each adjacent face, the source signal is sampled at the traced points and the
 * results are averaged. With `positions` (Composed flow), traces resume from and
 * update the stored positions instead of starting at the offsets.
 * Returns false when aborted through the progress callback.
 */
template <int D>
bool AdvectVertices(const AdvectionContext<D>& ctx, const GridTracer<D>& tracer, double time,
  const double* source, double* out, std::vector<float>* positions, double progressStart,
  double progressSpan)
{
  const Lattice<D>& L = ctx.L;
  const int C = ctx.C;
  const unsigned char* valid = ctx.allValid ? nullptr : ctx.valid.data();
  constexpr int Corners = Lattice<D>::Corners;
  const std::int64_t chunkCount = std::max<std::int64_t>(1, std::min<std::int64_t>(64, L.numSamples / 8192));
  const std::int64_t chunkSize = (L.numSamples + chunkCount - 1) / chunkCount;
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;

  for (std::int64_t chunk = 0; chunk < chunkCount; ++chunk)
  {
    const std::int64_t begin = chunk * chunkSize;
    const std::int64_t end = std::min(L.numSamples, begin + chunkSize);
#pragma omp parallel for schedule(dynamic, 256) num_threads(ctx.threads) reduction(+ : steps, truncated)
    for (std::int64_t s = begin; s < end; ++s)
    {
      double* acc = out + s * C;
      if (valid && !valid[s])
      {
        std::copy(source + s * C, source + (s + 1) * C, acc);
        continue;
      }
      std::fill(acc, acc + C, 0.0);
      const auto i = L.SampleCoordinates(s);
      int samples = 0;
      for (int b = 0; b < Corners; ++b)
      {
        bool inside = true;
        for (int d = 0; d < D && inside; ++d)
        {
          const std::int64_t c = i[d] - ((b >> d) & 1);
          inside = c >= 0 && c < L.m[d];
        }
        if (!inside)
        {
          continue;
        }
        std::array<double, D> q;
        float* stored = positions ? positions->data() + (s * Corners + b) * D : nullptr;
        for (int d = 0; d < D; ++d)
        {
          q[d] = stored ? static_cast<double>(stored[d])
                        : static_cast<double>(i[d]) + VertexOffset * (0.5 - ((b >> d) & 1));
        }
        bool cut = false;
        steps += static_cast<std::uint64_t>(tracer.Trace(q, time, cut));
        truncated += cut ? 1 : 0;
        if (stored)
        {
          for (int d = 0; d < D; ++d)
          {
            stored[d] = static_cast<float>(q[d]);
          }
        }
        if (!SampleGrid<D>(L, source, C, valid, ctx.sampling, q, acc))
        {
          // Only non-finite samples around q: keep the sample's own value.
          for (int c = 0; c < C; ++c)
          {
            acc[c] += source[s * C + c];
          }
        }
        ++samples;
      }
      for (int c = 0; c < C; ++c)
      {
        acc[c] /= samples;
      }
    }
    if (ctx.progress &&
      !ctx.progress(progressStart + progressSpan * static_cast<double>(end) / L.numSamples))
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

/// Initial Composed-flow positions: the offsets of AdvectVertices.
template <int D>
std::vector<float> InitialTracePositions(const Lattice<D>& L)
{
  constexpr int Corners = Lattice<D>::Corners;
  std::vector<float> positions(static_cast<size_t>(L.numSamples * Corners * D));
  for (std::int64_t s = 0; s < L.numSamples; ++s)
  {
    const auto i = L.SampleCoordinates(s);
    for (int b = 0; b < Corners; ++b)
    {
      for (int d = 0; d < D; ++d)
      {
        positions[(s * Corners + b) * D + d] =
          static_cast<float>(static_cast<double>(i[d]) + VertexOffset * (0.5 - ((b >> d) & 1)));
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

  bool allValid = true;
  const std::vector<unsigned char> valid = FiniteSamples(L.numSamples, C, input, allValid);
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (std::int64_t s = 0; s < L.numSamples; ++s)
  {
    if (valid[s])
    {
      for (int c = 0; c < C; ++c)
      {
        low = std::min(low, input[s * C + c]);
        high = std::max(high, input[s * C + c]);
      }
    }
  }
  std::copy(input, input + count, output);
  const double range = p.valueScale > 0.0 ? p.valueScale : high - low;
  if (fields)
  {
    fields->potential.assign(static_cast<size_t>(L.numSamples), 0.0);
    fields->flow.assign(static_cast<size_t>(shape.NumberOfFaces() * 3), 0.0);
  }
  if (!(range > 0.0) || !std::isfinite(range))
  {
    return {}; // constant (or entirely non-finite) signal: no flow
  }

  const std::vector<unsigned char> validFace = ValidFaces<D>(L, valid, threads);
  const int updates = p.flowMode == FlowMode::Fixed ? 1 : std::max(1, p.flowUpdates);
  const double stepTime = p.time / updates;
  std::vector<double> current;
  if (p.flowMode != FlowMode::Fixed)
  {
    current.assign(input, input + count);
  }
  std::vector<double> next(p.flowMode == FlowMode::Naive ? count : 0);
  std::vector<float> positions;
  if (p.flowMode == FlowMode::Composed && p.time > 0.0)
  {
    positions = InitialTracePositions<D>(L);
  }
  const AdvectionContext<D> ctx{ L, C, threads, p.sampling, valid, allValid, progress, report };

  for (int k = 0; k < updates; ++k)
  {
    // Flow of the current signal, on range-normalised intensities.
    const auto flowStart = Clock::now();
    const double* signal = current.empty() ? input : current.data();
    std::vector<double> smoothed(signal, signal + count);
    for (double& v : smoothed)
    {
      v /= range;
    }
    UmbrellaSmooth<D>(L, C, smoothed, valid, p.smoothingPasses, threads);
    std::vector<double> potential = SamplePotential<D>(L, C, smoothed, validFace, threads);
    UmbrellaSmooth<D>(L, 1, potential, valid, p.smoothingPasses, threads);
    const std::vector<float> velocity = BackTraceVelocity<D>(L, potential, validFace, threads);
    report.flowSeconds += SecondsSince(flowStart);

    if (fields && k == updates - 1)
    {
      fields->potential = potential;
      for (std::int64_t f = 0; f < L.numFaces; ++f)
      {
        for (int d = 0; d < D; ++d)
        {
          fields->flow[f * 3 + L.axis[d]] = -static_cast<double>(velocity[f * D + d]) * L.h[d];
        }
      }
    }
    const double progressStart = (k + 0.1) / updates;
    if (progress && !progress(progressStart))
    {
      report.aborted = true;
      break;
    }
    if (!(p.time > 0.0))
    {
      continue; // t = 0: the input, exactly (the flow fields may still be wanted)
    }

    const auto advectStart = Clock::now();
    const GridTracer<D> tracer(L, velocity.data(), p);
    bool completed = true;
    switch (p.flowMode)
    {
      case FlowMode::Fixed:
        completed = AdvectVertices<D>(ctx, tracer, stepTime, input, output, nullptr, progressStart, 0.9 / updates);
        break;
      case FlowMode::Naive:
        completed = AdvectVertices<D>(ctx, tracer, stepTime, current.data(), next.data(), nullptr, progressStart, 0.9 / updates);
        current.swap(next);
        break;
      case FlowMode::Composed:
        completed = AdvectVertices<D>(ctx, tracer, stepTime, input, current.data(), &positions, progressStart, 0.9 / updates);
        break;
    }
    report.advectionSeconds += SecondsSince(advectStart);
    if (!completed)
    {
      report.aborted = true;
      break;
    }
  }

  if (report.aborted)
  {
    std::copy(input, input + count, output);
  }
  else if (p.flowMode != FlowMode::Fixed && p.time > 0.0)
  {
    std::copy(current.begin(), current.end(), output);
  }
  return {};
}

} // namespace

Status AdvectGridSignal(const GridShape& shape, int components, const double* input,
  double* output, const AdvectionParameters& parameters, AdvectionReport* report,
  GridFlowFields* fields, const ProgressFunction& progress)
{
  for (int a = 0; a < 3; ++a)
  {
    if (shape.dimensions[a] < 1)
    {
      return { "grid dimensions must be >= 1" };
    }
    if (!(shape.spacing[a] > 0.0) || !std::isfinite(shape.spacing[a]))
    {
      return { "grid spacing must be finite and > 0" };
    }
  }
  if (components < 1)
  {
    return { "the signal needs at least one component" };
  }
  if (!input || !output || input == output)
  {
    return { "input and output must be distinct, non-null buffers" };
  }
  if (!(parameters.time >= 0.0) || !std::isfinite(parameters.time))
  {
    return { "the flow time must be finite and >= 0" };
  }
  if (parameters.smoothingPasses < 0)
  {
    return { "the number of smoothing passes must be >= 0" };
  }
  if (!(parameters.stepFraction > 0.0) || parameters.stepFraction > 1.0)
  {
    return { "the step fraction must be in (0, 1]" };
  }
  if (parameters.flowUpdates < 1)
  {
    return { "the number of flow updates must be >= 1" };
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
        fields->potential.assign(static_cast<size_t>(shape.NumberOfSamples()), 0.0);
        fields->flow.assign(static_cast<size_t>(shape.NumberOfFaces() * 3), 0.0);
      }
      return {};
  }
}

} // namespace shock
