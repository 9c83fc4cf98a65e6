// machinenoise: how steady this machine runs a fixed piece of pure compute work.
// Every thread repeats the same dependent floating-point chain (no memory
// traffic, no system calls, no synchronisation between threads) in windows of
// about WINDOW_MS milliseconds and records each window's time; it prints, per
// thread, the median window, the 99th percentile, the slowest, and how many
// windows took more than 1.3 times the median.
//
//   machinenoise [THREADS [WINDOWS [WINDOW_MS]]]     (defaults 2, 800, 20)
//
// Windows slower than the median are time the machine (other work on the host,
// a shared core) took from a program that did the same thing every time
// (Benchmarks/RESULTS.md, issue 18, session 12).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <omp.h>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The fixed work: `steps` dependent multiply-adds.
double Chain(double x, long steps)
{
  for (long i = 0; i < steps; ++i)
  {
    x = x * 1.0000001 + 1e-9;
  }
  return x;
}
}

int main(int argc, char* argv[])
{
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int windows = argc > 2 ? std::atoi(argv[2]) : 800;
  const double windowMs = argc > 3 ? std::atof(argv[3]) : 20.0;
  if (threads < 1 || windows < 1 || !(windowMs > 0.0))
  {
    std::fprintf(stderr, "usage: machinenoise [THREADS [WINDOWS [WINDOW_MS]]]\n");
    return 2;
  }
  // Steps per window, from a calibration run of 2 million steps.
  const double start = Now();
  volatile double sink = Chain(1.0, 2000000);
  const double perStep = std::max(1e-12, (Now() - start) / 2e6);
  const long steps = std::max(1L, static_cast<long>(windowMs * 1e-3 / perStep));

  std::vector<std::vector<double>> times(static_cast<size_t>(threads));
  std::vector<double> results(static_cast<size_t>(threads)); // kept, so the work is done
#pragma omp parallel num_threads(threads)
  {
    const size_t me = static_cast<size_t>(omp_get_thread_num());
    double x = 1.0;
    for (int w = 0; w < windows; ++w)
    {
      const double t0 = Now();
      x = Chain(x, steps);
      times[me].push_back(Now() - t0);
    }
    results[me] = x;
  }
  for (double x : results)
  {
    sink = sink + x;
  }
  for (int t = 0; t < static_cast<int>(times.size()); ++t)
  {
    std::vector<double> v = times[static_cast<size_t>(t)];
    if (v.empty())
    {
      continue; // fewer threads than asked
    }
    std::sort(v.begin(), v.end());
    const double median = v[v.size() / 2];
    const auto slow = std::count_if(v.begin(), v.end(), [&](double d) { return d > 1.3 * median; });
    std::printf("thread %d: median %.2f ms, 99th percentile %.2f ms, slowest %.2f ms, "
                "windows over 1.3 x median: %ld of %zu\n",
      t, median * 1e3, v[v.size() * 99 / 100] * 1e3, v.back() * 1e3, static_cast<long>(slow), v.size());
  }
  return 0;
}
