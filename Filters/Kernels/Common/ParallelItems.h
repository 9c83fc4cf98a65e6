/**
 * @file ParallelItems.h
 * @brief The items of a parallel loop handed out as they come, with progress
 * reports and an abort, and no barrier between the loop's parts: the advection
 * passes of the grid and mesh kernels. Uses OpenMP: include only from
 * translation units built with it.
 */
#ifndef ParallelItems_h
#define ParallelItems_h

#include "ShockTypes.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>

#include <omp.h>

namespace shock
{

/**
 * The items [0, count) of a loop run by the threads of one OpenMP parallel
 * region, `grain` at a time as each thread asks (Next), so that no thread waits
 * for another until the region ends: a thread that is delayed (a busy host, a
 * slow item) holds back only the items it has taken. The items must be
 * independent: any thread may take any item, so the results do not depend on
 * the thread count.
 *
 * Progress goes to `progress` (may be empty) as fractions in [start, start + span]:
 * the calling thread (OpenMP's thread 0) reports the items done each time it
 * passes another 1/64 of them (Done), and Finish reports the end. When the
 * callback returns false, every thread stops at its next Next, and Finish
 * returns false without another report; when it throws, the same, and Finish
 * rethrows the exception (an exception must not leave an OpenMP region).
 *
 *     ParallelItems items(count, grain, progress, start, span);
 *     #pragma omp parallel num_threads(threads)
 *     for (std::int64_t begin, end; items.Next(begin, end); items.Done(begin, end))
 *       for (std::int64_t k = begin; k < end; ++k) ...;
 *     if (!items.Finish()) ... aborted
 */
class ParallelItems
{
public:
  ParallelItems(std::int64_t count, std::int64_t grain, const ProgressFunction& progress,
    double start = 0.0, double span = 1.0)
    : Count(count)
    , Grain(std::max<std::int64_t>(1, grain))
    , Progress(progress)
    , Start(start)
    , Span(span)
  {
  }

  /// The next items [begin, end) for this thread; false when none are left or
  /// the run was aborted.
  bool Next(std::int64_t& begin, std::int64_t& end)
  {
    if (this->Aborted.load(std::memory_order_relaxed))
    {
      return false;
    }
    begin = this->Taken.fetch_add(this->Grain, std::memory_order_relaxed);
    end = std::min(this->Count, begin + this->Grain);
    return begin < this->Count;
  }

  /// Items [begin, end) are done; on thread 0, reports progress at each 1/64.
  void Done(std::int64_t begin, std::int64_t end)
  {
    if (!this->Progress)
    {
      return; // nothing to report: the count of items done is not needed
    }
    const std::int64_t finished =
      this->Finished.fetch_add(end - begin, std::memory_order_relaxed) + (end - begin);
    if (omp_get_thread_num() != 0 || finished >= this->Count)
    {
      return;
    }
    const std::int64_t due = finished * Reports / this->Count;
    if (due > this->Reported)
    {
      this->Reported = due;
      bool go = false;
      try
      {
        go = this->Progress(
          this->Start + this->Span * static_cast<double>(finished) / static_cast<double>(this->Count));
      }
      catch (...)
      {
        this->Thrown = std::current_exception(); // rethrown by Finish, outside the region
      }
      if (!go)
      {
        this->Aborted.store(true, std::memory_order_relaxed);
      }
    }
  }

  /// After the region: rethrows what the callback threw; false when aborted;
  /// otherwise reports the end (at most 1) and returns what the callback says.
  bool Finish()
  {
    if (this->Thrown)
    {
      std::rethrow_exception(this->Thrown);
    }
    if (this->Aborted.load())
    {
      return false;
    }
    return !this->Progress || this->Progress(std::min(1.0, this->Start + this->Span));
  }

private:
  static constexpr std::int64_t Reports = 64;
  const std::int64_t Count;
  const std::int64_t Grain;
  const ProgressFunction& Progress;
  const double Start;
  const double Span;
  // Taken and Finished on their own cache lines: every thread updates both.
  alignas(64) std::atomic<std::int64_t> Taken{ 0 };
  alignas(64) std::atomic<std::int64_t> Finished{ 0 };
  alignas(64) std::atomic<bool> Aborted{ false };
  std::int64_t Reported = 0; // 1/64 steps reported (thread 0 only)
  std::exception_ptr Thrown; // what the callback threw (thread 0 only)
};

} // namespace shock

#endif
