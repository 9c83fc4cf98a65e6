// Thread-count policy of the kernels (ShockTypes.h): small inputs get fewer threads,
// large ones all that were asked for, and never fewer than one. The advection
// passes' loop (ParallelItems.h): every item once, progress, abort.
#include "ParallelItems.h"
#include "ShockTypes.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include <omp.h>

namespace
{
TEST(ThreadsForWork, SmallWorkGetsOneThread)
{
  EXPECT_EQ(shock::ThreadsForWork(8, 0), 1);
  EXPECT_EQ(shock::ThreadsForWork(8, 64 * 48), 1);
  EXPECT_EQ(shock::ThreadsForWork(8, shock::MinimumWorkPerThread - 1), 1);
}

TEST(ThreadsForWork, GrowsWithWorkUpToTheRequest)
{
  const std::int64_t unit = shock::MinimumWorkPerThread;
  EXPECT_EQ(shock::ThreadsForWork(8, 2 * unit), 2);
  EXPECT_EQ(shock::ThreadsForWork(8, 5 * unit + unit / 2), 5);
  EXPECT_EQ(shock::ThreadsForWork(8, 1000 * unit), 8);
  EXPECT_EQ(shock::ThreadsForWork(3, 1000 * unit), 3);
}

TEST(ThreadsForWork, ZeroMeansTheMachineCapped)
{
  const int all = shock::ResolveThreadCount(0);
  EXPECT_GE(all, 1);
  EXPECT_EQ(shock::ThreadsForWork(0, std::int64_t(1) << 40), all);
  EXPECT_EQ(shock::ThreadsForWork(0, 1), 1);
}

// What a loop through ParallelItems did.
struct ItemRun
{
  bool finished = false;     // what Finish returned
  std::vector<int> runs;     // how often each item ran
  int threadsWithItems = 0;  // threads that took at least one grain
  int grainsAfterAbort = 0;  // grains begun after the callback said stop
};

// Runs `count` items on `threads` threads through ParallelItems (progress into
// [0.25, 0.75]); each item takes at least `itemMicros` microseconds. With
// `everyThread`, each thread holds its first grain until every thread has one.
// A callback that returns false is the abort: `stop` must be set before it returns.
ItemRun RunItems(std::int64_t count, std::int64_t grain, int threads,
  const shock::ProgressFunction& progress, int itemMicros = 0, bool everyThread = false,
  const std::atomic<bool>* stop = nullptr)
{
  shock::ParallelItems items(count, grain, progress, 0.25, 0.5);
  std::vector<std::atomic<int>> ran(static_cast<size_t>(count));
  std::atomic<int> withItems{ 0 };
  std::atomic<int> afterAbort{ 0 };
#pragma omp parallel num_threads(threads)
  {
    bool first = true;
    for (std::int64_t begin, end; items.Next(begin, end); items.Done(begin, end))
    {
      EXPECT_LT(begin, end);
      EXPECT_LE(end, count);
      EXPECT_LE(end - begin, grain);
      afterAbort += (stop && stop->load()) ? 1 : 0;
      for (std::int64_t k = begin; k < end; ++k)
      {
        ran[static_cast<size_t>(k)].fetch_add(1);
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(itemMicros);
        while (std::chrono::steady_clock::now() < until)
        {
        }
      }
      if (first)
      {
        first = false;
        withItems.fetch_add(1);
        const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (everyThread && withItems.load() < omp_get_num_threads() &&
          std::chrono::steady_clock::now() < limit)
        {
          std::this_thread::yield();
        }
      }
    }
  }
  ItemRun run;
  run.finished = items.Finish();
  for (auto& r : ran)
  {
    run.runs.push_back(r.load());
  }
  run.threadsWithItems = withItems.load();
  run.grainsAfterAbort = afterAbort.load();
  return run;
}

TEST(ParallelItems, EveryItemRunsOnceOnAnyThreadsAndGrain)
{
  for (int threads : { 1, 2, 3 })
  {
    for (std::int64_t count : { 0, 1, 7, 1000, 4099 })
    {
      for (std::int64_t grain : { 1, 3, 256 })
      {
        const bool everyThread = count >= threads * grain;
        const ItemRun run = RunItems(count, grain, threads, shock::ProgressFunction(), 0, everyThread);
        EXPECT_TRUE(run.finished);
        EXPECT_EQ(std::count(run.runs.begin(), run.runs.end(), 1), count)
          << threads << " threads, " << count << " items, grain " << grain;
        if (everyThread)
        {
          EXPECT_EQ(run.threadsWithItems, threads) << "the threads share the items";
        }
      }
    }
  }
}

TEST(ParallelItems, ProgressComesFromTheCallingThreadInOrderAndEndsAtTheSpan)
{
  for (int threads : { 1, 2 })
  {
    const auto caller = std::this_thread::get_id();
    std::vector<double> fractions;
    bool elsewhere = false;
    const ItemRun run = RunItems(5000, 7, threads,
      [&](double f) {
        elsewhere = elsewhere || std::this_thread::get_id() != caller;
        fractions.push_back(f);
        return true;
      },
      5, true);
    EXPECT_TRUE(run.finished);
    EXPECT_FALSE(elsewhere);
    ASSERT_GE(fractions.size(), 2u);
    EXPECT_LE(fractions.size(), 65u); // each 1/64 at most once, and the end
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_GT(fractions.front(), 0.25);
    EXPECT_EQ(fractions.back(), 0.75); // start + span
    EXPECT_EQ(std::count(run.runs.begin(), run.runs.end(), 1), 5000);
  }
}

TEST(ParallelItems, AnAbortStopsEveryThreadAndIsNotReportedAgain)
{
  for (int threads : { 1, 2 })
  {
    int calls = 0;
    double abortedAt = 0.0;
    std::atomic<bool> stop{ false };
    const ItemRun run = RunItems(20000, 10, threads,
      [&](double f) {
        abortedAt = f;
        stop = ++calls >= 3;
        return !stop;
      },
      5, true, &stop);
    EXPECT_FALSE(run.finished);
    EXPECT_EQ(calls, 3); // no report after the one that aborted
    const auto done = std::count(run.runs.begin(), run.runs.end(), 1);
    EXPECT_EQ(std::count(run.runs.begin(), run.runs.end(), 0) + done, 20000); // none twice
    EXPECT_LT(done, 20000);
    // The items done when the callback said stop (fraction 0.25 + 0.5 done / count)
    // were done; after it, each other thread begins about the grain it was taking.
    EXPECT_GE(static_cast<double>(done), std::round((abortedAt - 0.25) / 0.5 * 20000));
    // (A little slack: thread 0 may be preempted between the callback's return
    // and the flag that stops the others.)
    EXPECT_LE(run.grainsAfterAbort, 4 * (threads - 1));
  }
}
TEST(ParallelItems, AThrowingCallbackStopsThePassAndIsRethrownAfterIt)
{
  for (int threads : { 1, 2 })
  {
    int calls = 0;
    std::atomic<bool> stop{ false };
    const shock::ProgressFunction throwing = [&](double) -> bool {
      if (++calls == 2)
      {
        stop = true;
        throw std::runtime_error("no more");
      }
      return true;
    };
    EXPECT_THROW(RunItems(20000, 10, threads, throwing, 5, true, &stop), std::runtime_error);
    EXPECT_EQ(calls, 2); // no report after the throw
  }
}
} // namespace
