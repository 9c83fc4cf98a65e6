// Micro-benchmark of the VTK-free grid kernel (Google Benchmark; optional).
// A 512 x 512 one-channel image of blurred discs, fixed flow, all threads;
// the argument is the flow time t.
#include "GridShockAdvection.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace
{
std::vector<double> BlurredDiscs(int n)
{
  std::vector<double> v(static_cast<size_t>(n) * n);
  for (int y = 0; y < n; ++y)
  {
    for (int x = 0; x < n; ++x)
    {
      // Smooth steps (width ~3 px) around a grid of discs of radius n/10.
      const double cx = std::fmod(x, n / 4.0) - n / 8.0;
      const double cy = std::fmod(y, n / 4.0) - n / 8.0;
      const double r = std::sqrt(cx * cx + cy * cy) - n / 10.0;
      v[static_cast<size_t>(y) * n + x] = 1.0 / (1.0 + std::exp(r / 1.5));
    }
  }
  return v;
}

void BM_FixedFlow(benchmark::State& state)
{
  const int n = 512;
  const std::vector<double> input = BlurredDiscs(n);
  std::vector<double> output(input.size());
  shock::GridShape shape;
  shape.dimensions = { { n, n, 1 } };
  shock::AdvectionParameters p;
  p.time = static_cast<double>(state.range(0));
  shock::AdvectionReport report;
  for (auto _ : state)
  {
    report = shock::AdvectionReport();
    shock::AdvectGridSignal(shape, 1, input.data(), output.data(), p, &report);
    benchmark::DoNotOptimize(output.data());
  }
  state.counters["flow_s"] = report.flowSeconds;
  state.counters["advection_s"] = report.advectionSeconds;
  state.counters["steps"] = static_cast<double>(report.traceSteps);
}
BENCHMARK(BM_FixedFlow)->RangeMultiplier(4)->Range(1, 4096)->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK_MAIN();
