#include "GridGradientDomain.h"
#include "GridFlow.h"
#include "Timer.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace shock
{
namespace
{

/// The axes with more than one sample: their lengths, strides and spacings.
struct ActiveAxes
{
  int count = 0;
  std::int64_t n[3] = { 1, 1, 1 };      ///< samples along the axis
  std::int64_t stride[3] = { 1, 1, 1 }; ///< index step along the axis
  double h[3] = { 1.0, 1.0, 1.0 };      ///< spacing in mean edge lengths

  explicit ActiveAxes(const GridShape& shape)
  {
    const double unit = shape.MeanEdgeLength();
    std::int64_t stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      if (shape.dimensions[a] > 1)
      {
        this->n[this->count] = shape.dimensions[a];
        this->stride[this->count] = stride;
        this->h[this->count] = shape.spacing[a] / unit;
        ++this->count;
      }
      stride *= shape.dimensions[a];
    }
  }

  /// The coordinate of sample s along active axis k.
  std::int64_t Coordinate(std::int64_t s, int k) const
  {
    return (s / this->stride[k]) % this->n[k];
  }
};

/// Per channel: whether every value is finite, and the middle of its range.
struct ChannelScan
{
  bool allFinite = true;
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  std::vector<double> middle;
};

template <typename T>
ChannelScan ScanChannels(std::int64_t N, int C, const T* input, int threads)
{
  ChannelScan scan;
  scan.middle.resize(static_cast<size_t>(C));
  for (int c = 0; c < C; ++c)
  {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    bool finite = true;
#pragma omp parallel for schedule(static) num_threads(threads) \
  reduction(min : low) reduction(max : high) reduction(&& : finite)
    for (std::int64_t s = 0; s < N; ++s)
    {
      const double v = static_cast<double>(input[s * C + c]);
      finite = finite && std::isfinite(v);
      low = std::min(low, v);
      high = std::max(high, v);
    }
    scan.allFinite = scan.allFinite && finite;
    scan.low = std::min(scan.low, low);
    scan.high = std::max(scan.high, high);
    scan.middle[static_cast<size_t>(c)] = 0.5 * low + 0.5 * high;
  }
  return scan;
}

/**
 * Step 1: per sample, its value and, per active axis, its forward and backward
 * differences; C * (1 + 2 * axes) floats. All are divided by the data range
 * `range` (the value less its channel's mid-range first), so that floats keep 7
 * digits of the range on data of any scale.
 */
template <typename T>
LargeArray<float> CarriedDifferences(std::int64_t N, int C, const ActiveAxes& axes,
  const T* input, const std::vector<double>& middle, double range, int threads)
{
  const int carriedC = C * (1 + 2 * axes.count);
  LargeArray<float> carried = AllocateLargeArray<float>(N * carriedC);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t s = 0; s < N; ++s)
  {
    float* out = carried.get() + s * carriedC;
    const T* here = input + s * C;
    for (int c = 0; c < C; ++c)
    {
      out[c] = static_cast<float>((static_cast<double>(here[c]) - middle[static_cast<size_t>(c)]) / range);
    }
    for (int k = 0; k < axes.count; ++k)
    {
      const std::int64_t i = axes.Coordinate(s, k);
      const std::int64_t step = axes.stride[k] * C;
      float* forward = out + C * (1 + 2 * k);
      float* backward = forward + C;
      for (int c = 0; c < C; ++c)
      {
        const double v = static_cast<double>(here[c]);
        forward[c] = i + 1 < axes.n[k]
          ? static_cast<float>((static_cast<double>(input[s * C + step + c]) - v) / range)
          : 0.0f;
        backward[c] = i > 0
          ? static_cast<float>((v - static_cast<double>(input[s * C - step + c])) / range)
          : 0.0f;
      }
    }
  }
  return carried;
}

/**
 * Step 3 for the edge from sample s along active axis k: the covariant
 * difference of the advected values, or the transported carried difference,
 * whichever is longer over the channels; written to g (C values).
 */
inline void TargetGradient(const float* advected, std::int64_t s, int k, std::int64_t stride,
  int C, int carriedC, double* g)
{
  const float* from = advected + s * carriedC;
  const float* to = advected + (s + stride) * carriedC;
  const float* forward = from + C * (1 + 2 * k); // F_k at the end of s's trace
  const float* backward = to + C * (2 + 2 * k);  // B_k at the end of (s + e_k)'s trace
  double covariant = 0.0;
  double transported = 0.0;
  for (int c = 0; c < C; ++c)
  {
    const double dv = static_cast<double>(to[c]) - static_cast<double>(from[c]);
    const double tv = 0.5 * (static_cast<double>(forward[c]) + static_cast<double>(backward[c]));
    covariant += dv * dv;
    transported += tv * tv;
  }
  const bool stretch = covariant >= transported;
  for (int c = 0; c < C; ++c)
  {
    g[c] = stretch ? static_cast<double>(to[c]) - static_cast<double>(from[c])
                   : 0.5 * (static_cast<double>(forward[c]) + static_cast<double>(backward[c]));
  }
}

/**
 * The right-hand side of step 4, channel-planar (rhs[c * N + s]):
 * lambda I + sum_k D_k^T g_k / h_k^2, where (D^T g)(s) = g(s - e_k) - g(s)
 * over the edges that exist; g is in units of the range (`range` scales it back).
 */
template <typename T>
LargeArray<double> ScreenedRightHandSide(std::int64_t N, int C, const ActiveAxes& axes,
  const T* input, const float* advected, double lambda, double range, int threads)
{
  const int carriedC = C * (1 + 2 * axes.count);
  LargeArray<double> rhs = AllocateLargeArray<double>(N * C);
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> g(static_cast<size_t>(C));
    std::vector<double> sum(static_cast<size_t>(C));
#pragma omp for schedule(static)
    for (std::int64_t s = 0; s < N; ++s)
    {
      for (int c = 0; c < C; ++c)
      {
        sum[static_cast<size_t>(c)] = lambda * static_cast<double>(input[s * C + c]);
      }
      for (int k = 0; k < axes.count; ++k)
      {
        const std::int64_t i = axes.Coordinate(s, k);
        const double weight = range / (axes.h[k] * axes.h[k]);
        if (i > 0)
        {
          TargetGradient(advected, s - axes.stride[k], k, axes.stride[k], C, carriedC, g.data());
          for (int c = 0; c < C; ++c)
          {
            sum[static_cast<size_t>(c)] += weight * g[static_cast<size_t>(c)];
          }
        }
        if (i + 1 < axes.n[k])
        {
          TargetGradient(advected, s, k, axes.stride[k], C, carriedC, g.data());
          for (int c = 0; c < C; ++c)
          {
            sum[static_cast<size_t>(c)] -= weight * g[static_cast<size_t>(c)];
          }
        }
      }
      for (int c = 0; c < C; ++c)
      {
        rhs[c * N + s] = sum[static_cast<size_t>(c)];
      }
    }
  }
  return rhs;
}

/**
 * The discrete cosine transform of one line length, through a complex FFT of
 * the same length (Makhoul's reordering; Eigen's FFT). Forward is the DCT-II
 * X_k = sum_n x_n cos(pi k (n + 1/2) / n), the Neumann Laplacian's eigenbasis;
 * Inverse is its exact inverse. One object per thread (the FFT keeps state).
 */
class CosineTransform
{
public:
  explicit CosineTransform(std::int64_t n)
    : N(n)
    , Reordered(static_cast<size_t>(n))
    , Spectrum(static_cast<size_t>(n))
    , Twiddle(static_cast<size_t>(n))
  {
    const double pi = 3.14159265358979323846;
    for (std::int64_t k = 0; k < n; ++k)
    {
      this->Twiddle[static_cast<size_t>(k)] =
        std::polar(1.0, -pi * static_cast<double>(k) / (2.0 * static_cast<double>(n)));
    }
  }

  void Forward(double* x)
  {
    const std::int64_t n = this->N;
    for (std::int64_t k = 0; 2 * k < n; ++k)
    {
      this->Reordered[static_cast<size_t>(k)] = x[2 * k];
    }
    for (std::int64_t k = 0; 2 * k + 1 < n; ++k)
    {
      this->Reordered[static_cast<size_t>(n - 1 - k)] = x[2 * k + 1];
    }
    this->Fft.fwd(this->Spectrum, this->Reordered);
    for (std::int64_t k = 0; k < n; ++k)
    {
      x[k] = (this->Twiddle[static_cast<size_t>(k)] * this->Spectrum[static_cast<size_t>(k)]).real();
    }
  }

  void Inverse(double* c)
  {
    const std::int64_t n = this->N;
    for (std::int64_t k = 0; k < n; ++k)
    {
      const double mirrored = k > 0 ? c[n - k] : 0.0;
      this->Spectrum[static_cast<size_t>(k)] =
        std::conj(this->Twiddle[static_cast<size_t>(k)]) * std::complex<double>(c[k], -mirrored);
    }
    this->Fft.inv(this->Reordered, this->Spectrum); // scaled by 1/n
    for (std::int64_t k = 0; 2 * k < n; ++k)
    {
      c[2 * k] = this->Reordered[static_cast<size_t>(k)].real();
    }
    for (std::int64_t k = 0; 2 * k + 1 < n; ++k)
    {
      c[2 * k + 1] = this->Reordered[static_cast<size_t>(n - 1 - k)].real();
    }
  }

private:
  std::int64_t N;
  std::vector<std::complex<double>> Reordered;
  std::vector<std::complex<double>> Spectrum;
  std::vector<std::complex<double>> Twiddle;
  Eigen::FFT<double> Fft;
};

/// The transform along active axis k of every line of `data` (N samples).
void TransformLines(double* data, std::int64_t N, const ActiveAxes& axes, int k, bool forward,
  int threads)
{
  const std::int64_t n = axes.n[k];
  const std::int64_t stride = axes.stride[k];
  const std::int64_t outer = N / (stride * n);
  const auto apply = [forward](CosineTransform& transform, double* line) {
    if (forward)
    {
      transform.Forward(line);
    }
    else
    {
      transform.Inverse(line);
    }
  };
  if (stride == 1)
  {
#pragma omp parallel num_threads(threads)
    {
      CosineTransform transform(n);
#pragma omp for schedule(static)
      for (std::int64_t o = 0; o < outer; ++o)
      {
        apply(transform, data + o * n);
      }
    }
    return;
  }
  // Lines across memory: gathered a few adjacent ones at a time, so that the
  // reads and writes go along rows.
  constexpr std::int64_t Gather = 16;
  const std::int64_t blocks = (stride + Gather - 1) / Gather;
#pragma omp parallel num_threads(threads)
  {
    CosineTransform transform(n);
    std::vector<double> lines(static_cast<size_t>(Gather * n));
#pragma omp for schedule(static)
    for (std::int64_t item = 0; item < outer * blocks; ++item)
    {
      const std::int64_t first = (item % blocks) * Gather;
      const std::int64_t count = std::min(Gather, stride - first);
      double* base = data + (item / blocks) * stride * n + first;
      for (std::int64_t i = 0; i < n; ++i)
      {
        for (std::int64_t j = 0; j < count; ++j)
        {
          lines[static_cast<size_t>(j * n + i)] = base[i * stride + j];
        }
      }
      for (std::int64_t j = 0; j < count; ++j)
      {
        apply(transform, lines.data() + j * n);
      }
      for (std::int64_t i = 0; i < n; ++i)
      {
        for (std::int64_t j = 0; j < count; ++j)
        {
          base[i * stride + j] = lines[static_cast<size_t>(j * n + i)];
        }
      }
    }
  }
}

/// Step 4 on one channel, with the axes already resolved.
void SolveChannel(const ActiveAxes& axes, std::int64_t N, double lambda, double* rhs, int threads)
{
  // DCT-II along every axis: the Neumann Laplacian's eigenbasis.
  for (int k = 0; k < axes.count; ++k)
  {
    TransformLines(rhs, N, axes, k, true, threads);
  }
  // Divide by the eigenvalues lambda + sum_k (2 - 2 cos(pi i_k / n_k)) / h_k^2.
  std::vector<std::vector<double>> eigen(static_cast<size_t>(axes.count));
  for (int k = 0; k < axes.count; ++k)
  {
    const std::int64_t n = axes.n[k];
    auto& values = eigen[static_cast<size_t>(k)];
    values.resize(static_cast<size_t>(n));
    for (std::int64_t i = 0; i < n; ++i)
    {
      const double pi = 3.14159265358979323846;
      values[static_cast<size_t>(i)] =
        (2.0 - 2.0 * std::cos(pi * static_cast<double>(i) / static_cast<double>(n))) /
        (axes.h[k] * axes.h[k]);
    }
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t s = 0; s < N; ++s)
  {
    double denominator = lambda;
    for (int k = 0; k < axes.count; ++k)
    {
      denominator += eigen[static_cast<size_t>(k)][static_cast<size_t>(axes.Coordinate(s, k))];
    }
    rhs[s] /= denominator;
  }
  // Back to samples.
  for (int k = 0; k < axes.count; ++k)
  {
    TransformLines(rhs, N, axes, k, false, threads);
  }
}

/// Hands the channel-planar `solved` to `output`, interleaved, in parallel runs.
void WriteInterleaved(std::int64_t N, int C, const double* solved, const SampleWriter& output,
  int threads)
{
  const std::int64_t runs = (N + grid::BlockLength - 1) / grid::BlockLength;
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> row(static_cast<size_t>(grid::BlockLength * C));
#pragma omp for schedule(static)
    for (std::int64_t r = 0; r < runs; ++r)
    {
      const std::int64_t first = r * grid::BlockLength;
      const std::int64_t count = std::min(grid::BlockLength, N - first);
      for (std::int64_t j = 0; j < count; ++j)
      {
        for (int c = 0; c < C; ++c)
        {
          row[static_cast<size_t>(j * C + c)] = solved[c * N + first + j];
        }
      }
      output(first, count, row.data());
    }
  }
}

} // namespace

Status SolveScreenedPoisson(
  const GridShape& shape, const double axisLength[3], double lambda, double* rhs, int threads)
{
  if (!(lambda > 0.0) || !std::isfinite(lambda))
  {
    return { "the screening weight must be finite and > 0" };
  }
  ActiveAxes axes(shape);
  for (int a = 0, k = 0; a < 3; ++a)
  {
    if (shape.dimensions[a] > 1)
    {
      axes.h[k++] = axisLength[a];
    }
  }
  SolveChannel(axes, shape.NumberOfSamples(), lambda, rhs, ThreadsForWork(threads, shape.NumberOfSamples()));
  return {};
}

namespace
{

/// The checks of a gradient-domain run beyond those of every grid run.
Status CheckGradientRun(const AdvectionParameters& parameters, const GradientDomainParameters& domain)
{
  if (parameters.flowMode != FlowMode::Fixed)
  {
    return { "the gradient domain follows the fixed flow only (FlowMode Fixed)" };
  }
  if (!(domain.screening > 0.0) || !std::isfinite(domain.screening))
  {
    return { "the screening weight must be finite and > 0" };
  }
  return {};
}

/**
 * Steps 1 and 2: the values and differences (in units of `range`), carried
 * along the flow of the values; progress 0 to 0.8. Empty when aborted.
 */
template <typename T>
LargeArray<float> AdvectDifferences(const GridShape& shape, int C, const T* input,
  const ActiveAxes& axes, const ChannelScan& scan, double range,
  const AdvectionParameters& parameters, AdvectionReport& report, GridFlowFields* fields,
  const ProgressFunction& progress, int threads, Status& status)
{
  const std::int64_t N = shape.NumberOfSamples();
  const int carriedC = C * (1 + 2 * axes.count);
  LargeArray<float> advected = AllocateLargeArray<float>(N * carriedC);
  const LargeArray<float> carried = CarriedDifferences(N, C, axes, input, scan.middle, range, threads);
  float* into = advected.get();
  const SampleWriter keep = [into, carriedC](std::int64_t first, std::int64_t count, const double* values) {
    std::transform(values, values + count * carriedC, into + first * carriedC,
      [](double v) { return static_cast<float>(v); });
  };
  const ProgressFunction scaled = !progress
    ? ProgressFunction()
    : ProgressFunction([&progress](double f) { return progress(0.8 * f); });
  status = AdvectCarriedGridSignal(
    shape, C, input, CarriedSignal{ carried.get(), carriedC }, keep, parameters, &report, fields, scaled);
  if (!status.Ok() || report.aborted)
  {
    advected.reset();
  }
  return advected;
}

/**
 * Steps 3 and 4: the target gradients of `advected`, integrated channel by
 * channel (channel-planar result); progress 0.8 to 0.95. Empty when aborted.
 */
template <typename T>
LargeArray<double> IntegrateTargets(std::int64_t N, int C, const T* input, const ActiveAxes& axes,
  LargeArray<float> advected, double range, double lambda, const ProgressFunction& progress,
  int threads)
{
  LargeArray<double> solved = ScreenedRightHandSide(N, C, axes, input, advected.get(), lambda, range, threads);
  advected.reset();
  for (int c = 0; c < C; ++c)
  {
    if (progress && !progress(0.8 + 0.15 * c / C))
    {
      return {};
    }
    SolveChannel(axes, N, lambda, solved.get() + c * N, threads);
  }
  if (progress && !progress(0.95))
  {
    return {};
  }
  return solved;
}

} // namespace

template <typename T>
Status AdvectGridGradients(const GridShape& shape, int C, const T* input,
  const SampleWriter& output, const AdvectionParameters& parameters,
  const GradientDomainParameters& domain, AdvectionReport* report, GridFlowFields* fields,
  const ProgressFunction& progress)
{
  Status valid = grid::CheckGridRun(shape, C, input, output, parameters);
  valid = valid.Ok() ? CheckGradientRun(parameters, domain) : valid;
  if (!valid.Ok())
  {
    return valid;
  }
  AdvectionReport localReport;
  AdvectionReport& r = report ? *report : localReport;
  // One Poisson problem over the whole grid: every sample is advected and handed to `output`.
  AdvectionParameters whole = parameters;
  whole.writtenSamples = AdvectionParameters().writtenSamples;
  const std::int64_t N = shape.NumberOfSamples();
  const int threads = ThreadsForWork(parameters.numberOfThreads, N);
  const ChannelScan scan = ScanChannels(N, C, input, threads);
  if (!scan.allFinite)
  {
    return { "the gradient domain needs a finite value at every sample (some are NaN, "
             "infinite or blanked): use the value domain, or fill them first" };
  }
  const double range = scan.high - scan.low;
  if (range == std::numeric_limits<double>::infinity())
  {
    return { ValueSpanError(scan.low, scan.high) };
  }
  const ActiveAxes axes(shape);
  if (!(parameters.time > 0.0) || axes.count == 0 || !(range > 0.0))
  {
    // Nothing moves: the input itself (and the flow fields, when asked for).
    return AdvectGridSignal(shape, C, input, output, whole, report, fields, progress);
  }
  Status status;
  LargeArray<float> advected =
    AdvectDifferences(shape, C, input, axes, scan, range, whole, r, fields, progress, threads, status);
  if (!status.Ok())
  {
    return status;
  }
  const auto solveStart = Clock::now();
  const LargeArray<double> solved = advected
    ? IntegrateTargets(N, C, input, axes, std::move(advected), range, domain.screening, progress, threads)
    : LargeArray<double>();
  r.integrationSeconds = SecondsSince(solveStart);
  if (!solved)
  {
    r.aborted = true; // the input, unfiltered
    grid::WriteSignal(N, C, input, output, threads);
    return {};
  }
  WriteInterleaved(N, C, solved.get(), output, threads);
  return {};
}

template Status AdvectGridGradients(const GridShape&, int, const double*, const SampleWriter&,
  const AdvectionParameters&, const GradientDomainParameters&, AdvectionReport*, GridFlowFields*,
  const ProgressFunction&);
template Status AdvectGridGradients(const GridShape&, int, const float*, const SampleWriter&,
  const AdvectionParameters&, const GradientDomainParameters&, AdvectionReport*, GridFlowFields*,
  const ProgressFunction&);
template Status AdvectGridGradients(const GridShape&, int, const unsigned char*,
  const SampleWriter&, const AdvectionParameters&, const GradientDomainParameters&,
  AdvectionReport*, GridFlowFields*, const ProgressFunction&);

} // namespace shock
