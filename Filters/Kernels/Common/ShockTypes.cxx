#include "ShockTypes.h"
#include "MachineChoices.h"

#include <omp.h>
#ifdef __linux__
#include <sched.h>
#include <unistd.h>
#endif

#ifdef __linux__
#include <sys/mman.h>
#endif

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <algorithm>
#include <sstream>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <new>

namespace shock
{

namespace
{
/// One value of RoundAndClampBytes: NaN fails `v > 0` and gives 0; the clamped
/// value is at least 0, so only a rest of at least 0.5 rounds (up).
inline unsigned char RoundAndClampByte(double v)
{
  double clamped = v > 0.0 ? v : 0.0;
  clamped = clamped < 255.0 ? clamped : 255.0;
  const int truncated = static_cast<int>(clamped);
  const double rest = clamped - static_cast<double>(truncated);
  return static_cast<unsigned char>(truncated + (rest >= 0.5 ? 1 : 0));
}

#ifdef __SSE2__
/// RoundAndClampByte of two values, as two 32-bit integers in the low half.
inline __m128i RoundAndClampPair(const double* in)
{
  const __m128d v = _mm_loadu_pd(in);
  // maxpd and minpd return their second operand when the first is NaN or the
  // two are equal: v > 0 ? v : 0, then clamped < 255 ? clamped : 255.
  const __m128d clamped = _mm_min_pd(_mm_max_pd(v, _mm_setzero_pd()), _mm_set1_pd(255.0));
  const __m128i truncated = _mm_cvttpd_epi32(clamped);
  const __m128d rest = _mm_sub_pd(clamped, _mm_cvtepi32_pd(truncated));
  // All ones (-1) in each 64-bit lane whose rest is at least 0.5, moved to the
  // two low 32-bit lanes: subtracting it adds 1 there.
  const __m128i up = _mm_shuffle_epi32(_mm_castpd_si128(_mm_cmpge_pd(rest, _mm_set1_pd(0.5))),
    _MM_SHUFFLE(3, 3, 2, 0));
  return _mm_sub_epi32(truncated, up);
}
#endif
}

void RoundAndClampBytes(const double* in, std::int64_t count, unsigned char* out)
{
  std::int64_t i = 0;
#ifdef __SSE2__
  for (; i + 8 <= count; i += 8)
  {
    const __m128i low = _mm_unpacklo_epi64(RoundAndClampPair(in + i), RoundAndClampPair(in + i + 2));
    const __m128i high =
      _mm_unpacklo_epi64(RoundAndClampPair(in + i + 4), RoundAndClampPair(in + i + 6));
    // 0 .. 255 in 32 bits, packed to 16 and then to 8 bits without saturating.
    const __m128i bytes = _mm_packus_epi16(_mm_packs_epi32(low, high), _mm_setzero_si128());
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + i), bytes);
  }
#endif
  for (; i < count; ++i)
  {
    out[i] = RoundAndClampByte(in[i]);
  }
}

Status CheckAdvectionParameters(const AdvectionParameters& parameters)
{
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
  if (parameters.hierarchyLevels < 1)
  {
    return { "the number of hierarchy levels must be >= 1" };
  }
  if (!(parameters.valueScale >= 0.0) || !std::isfinite(parameters.valueScale))
  {
    return { "the value scale must be finite and >= 0" };
  }
  return {};
}

std::string ValueSpanError(double low, double high)
{
  std::ostringstream text;
  text << "the values span from " << low << " to " << high
       << ", more than a double can hold as their difference (the data range the flow is normalised by); "
          "rescale the array first (e.g. divide it by 1e10)";
  return text.str();
}

int ResolveThreadCount(int requested)
{
  UseTheWholeNodeWhenAlone();
  if (requested > 0)
  {
    return requested;
  }
  // OMP_NUM_THREADS when the user set it (OpenMP's own default), else every core available.
  return std::max(1, std::getenv("OMP_NUM_THREADS") ? omp_get_max_threads() : omp_get_num_procs());
}

int ThreadsForWork(int requested, std::int64_t work)
{
  const std::int64_t useful = std::max<std::int64_t>(1, work / MinimumWorkPerThread);
  return static_cast<int>(std::min<std::int64_t>(ResolveThreadCount(requested), useful));
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
    if (UseHugePages())
    {
      madvise(block, size, MADV_HUGEPAGE);
    }
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

} // namespace shock
