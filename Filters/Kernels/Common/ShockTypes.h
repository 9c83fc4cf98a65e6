/**
 * @file ShockTypes.h
 * @brief Parameters, reports and callbacks shared by the VTK-free shock-filter kernels.
 *
 * The kernels implement F. Prada and M. Kazhdan, "Unconditionally Stable Shock
 * Filters for Image and Geometry Processing", Computer Graphics Forum 34(5), 2015.
 * All quantities here are in the kernels' normalised units: intensities are
 * divided by the data range of the filtered signal and lengths by the mean edge
 * length of the domain, so that a parameter means the same on any data.
 */
#ifndef ShockTypes_h
#define ShockTypes_h

// Forces the inlining of a small function on a hot path, or keeps a rare path
// out of line (GCC and Clang).
#if defined(__GNUC__) || defined(__clang__)
#define SHOCK_ALWAYS_INLINE inline __attribute__((always_inline))
#define SHOCK_NOINLINE __attribute__((noinline))
#else
#define SHOCK_ALWAYS_INLINE inline
#define SHOCK_NOINLINE
#endif

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>

namespace shock
{

/// How the flow field evolves during the advection (paper section 3.3).
enum class FlowMode : int
{
  Fixed = 0,    ///< one flow from the input, traced for the whole time t (the paper's choice)
  Composed = 1, ///< flow recomputed K times; back-traces composed, only the input is sampled
  Naive = 2     ///< flow recomputed K times; the signal is resampled after each step
};

/// How the signal is read at a back-traced position.
enum class Sampling : int
{
  Linear = 0, ///< multilinear (grids) or barycentric (meshes) interpolation
  Nearest = 1 ///< value of the nearest sample
};

/// How a flow line is followed.
enum class Tracing : int
{
  /// Exact piecewise-linear tracing: the flow is constant inside a face, so each
  /// move goes straight to the face boundary (the limit of Stepped as delta -> 0).
  FaceCrossing = 0,
  /// The paper's Appendix A Trace: steps of at most delta = stepFraction x mean edge length.
  Stepped = 1
};

/// Parameters of one shock-filter run.
struct AdvectionParameters
{
  /// Flow time t (>= 0, finite), in normalised units (range-normalised intensities,
  /// lengths in mean edge lengths). t = 0 returns the input.
  double time = 0.0;
  /// Umbrella-smoothing passes applied before each of the two gradient computations (>= 0).
  int smoothingPasses = 1;
  /// Tracing step delta for Tracing::Stepped, as a fraction of the mean edge length (0, 1].
  double stepFraction = 0.1;
  FlowMode flowMode = FlowMode::Fixed;
  /// Number of flow computations K for the Composed and Naive modes (>= 1); ignored for Fixed.
  int flowUpdates = 1;
  Sampling sampling = Sampling::Linear;
  Tracing tracing = Tracing::FaceCrossing;
  /// OpenMP threads; 0 uses all available cores.
  int numberOfThreads = 0;
  /// Intensity scale of the grid kernel (AdvectGridSignal): values are divided by it
  /// instead of by their data range when > 0 (the VTK filters pass the range over all
  /// pieces of a parallel run). 0, the default, uses the data range. Mesh signals carry
  /// their own MeshSignal::valueScale.
  double valueScale = 0.0;
  /// Resolution levels of the grid kernel's coarse-to-fine tracing (>= 1; GridHierarchy.h):
  /// 1 is the paper's single level. Levels the grid is too small for are not built.
  /// Ignored by the mesh kernels.
  int hierarchyLevels = 1;
  /// The samples whose results the grid advection hands to its output: per grid
  /// axis x, y, z the first and the last sample index, the whole axis when the
  /// first is past the last (the default: every sample). A piece of a distributed
  /// image asks for its own samples: the halo around them feeds the flow and the
  /// traces, and is not traced itself. The other kernels (mesh, PDE, the gradient
  /// domain, which solves over the whole grid) hand every sample.
  std::array<std::int64_t, 6> writtenSamples{ { 0, -1, 0, -1, 0, -1 } };
};

/// What a run did, for logs, timings and tests.
struct AdvectionReport
{
  double flowSeconds = 0.0;      ///< smoothing, potential and flow computation (all updates)
  double advectionSeconds = 0.0; ///< back-tracing and sampling (all updates)
  double integrationSeconds = 0.0; ///< the gradient domain's screened Poisson solve (GridGradientDomain.h)
  std::uint64_t traceSteps = 0;  ///< face crossings (FaceCrossing) or delta-steps (Stepped), all traces
  std::uint64_t truncatedTraces = 0; ///< traces stopped by the step cap (a discrete cycle guard)
  bool aborted = false;          ///< the progress callback asked to stop
  int hierarchyLevels = 1;       ///< resolution levels the grid kernel used (GridHierarchy.h)
  /// Mesh kernel on a piece (MeshSignal::triangleRing): the deepest ghost ring a
  /// trace of the piece's own samples read; -1 when none was traced.
  int deepestRing = -1;
  /// Grid kernel with AdvectionParameters::writtenSamples: per grid axis x, y, z,
  /// how many face layers below (2a) and above (2a + 1) the faces beside the
  /// written samples the deepest of their traces went; 0 when none left them.
  /// Every face a trace read lies within (GridTracer's fence).
  std::array<std::int64_t, 6> haloReach{};
};

/**
 * Progress callback, called only from the calling thread (during a parallel
 * pass, while the other threads go on: ParallelItems.h) with the fraction done
 * in [0, 1], never decreasing. Returning false aborts the run promptly. It
 * should be cheap; an exception it throws aborts the pass and is rethrown to
 * the kernel's caller once the threads have stopped.
 */
using ProgressFunction = std::function<bool(double fraction)>;

/// Result of a kernel call. An empty message means success.
struct Status
{
  std::string error;
  bool Ok() const { return this->error.empty(); }
};

/**
 * The error of finite values whose difference overflows a double (the data
 * range the flow is normalised by): from `low` to `high`.
 */
std::string ValueSpanError(double low, double high);

/**
 * Resolve a thread-count parameter: values <= 0 mean OMP_NUM_THREADS when it
 * is set, else all available cores (those of the process's affinity mask; see
 * UseTheWholeNodeWhenAlone).
 */
int ResolveThreadCount(int requested);

/// Work units (samples, vertices, faces, trace starts) below which a second thread
/// costs more to start and synchronise than it saves (measured in Benchmarks/RESULTS.md).
constexpr std::int64_t MinimumWorkPerThread = 16384;

/**
 * The threads worth using for `work` units of roughly equal cost:
 * ResolveThreadCount(requested), but at most one per MinimumWorkPerThread units and
 * at least one, so that small inputs do not get slower with more threads. Kernel
 * results never depend on the thread count, so this changes only the time.
 */
int ThreadsForWork(int requested, std::int64_t work);

/// Check the ranges documented in AdvectionParameters; an empty Status when valid.
Status CheckAdvectionParameters(const AdvectionParameters& parameters);

/**
 * Run body(begin, end) on contiguous ranges that split [0, count), one per thread
 * of an OpenMP team of ResolveThreadCount(threads) threads. For element-wise work
 * in code that is not built with OpenMP (the VTK glue); the body must be safe to
 * run concurrently on disjoint ranges.
 */
void ParallelFor(std::int64_t count, int threads,
  const std::function<void(std::int64_t begin, std::int64_t end)>& body);

/**
 * Results as 8-bit values: each clamped to [0, 255] and rounded half away from
 * zero (as std::round), NaN as 0: out[i] for in[i], i < count. Eight values at a
 * time with SSE2 where available (the same operations: the same bytes).
 */
void RoundAndClampBytes(const double* in, std::int64_t count, unsigned char* out);

/**
 * Uninitialised storage for the large arrays of the kernels and filters (signals,
 * potentials, flows), released with FreeLarge and the same size. On Linux, blocks
 * of 2 MiB and more are mapped on their own, aligned to 2 MiB; with the build
 * option SHOCK_HUGE_PAGES (off by default, MachineChoices.h) they are also
 * advised for transparent huge pages. Throws std::bad_alloc on failure.
 */
void* AllocateLarge(std::size_t bytes);
void FreeLarge(void* block, std::size_t bytes) noexcept;

/// Deleter of LargeArray: FreeLarge needs the size.
struct LargeArrayDeleter
{
  std::size_t bytes = 0;
  void operator()(void* block) const noexcept { FreeLarge(block, this->bytes); }
};

/// An uninitialised array from AllocateLarge.
template <typename T>
using LargeArray = std::unique_ptr<T[], LargeArrayDeleter>;

template <typename T>
LargeArray<T> AllocateLargeArray(std::int64_t count)
{
  static_assert(std::is_trivial<T>::value, "large arrays hold plain values, left uninitialised");
  const std::size_t bytes = static_cast<std::size_t>(count) * sizeof(T);
  return LargeArray<T>(static_cast<T*>(AllocateLarge(bytes)), LargeArrayDeleter{ bytes });
}

} // namespace shock

#endif
