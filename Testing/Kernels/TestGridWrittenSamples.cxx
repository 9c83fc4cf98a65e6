// The written samples of the grid advection (AdvectionParameters::writtenSamples):
// a box of the grid whose results are handed to the output, the rest of the grid
// feeding the flow and the traces. The box's results must be those of the
// whole run, and nothing outside the box may reach the output.
#include "GridGradientDomain.h"
#include "GridShockAdvection.h"
#include "TestSignals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <vector>

namespace
{
using namespace shock;
using namespace shocktest;

/// What a run handed to its output: the values, and how often each sample was handed.
struct Received
{
  std::vector<double> values;
  std::vector<int> times;
};

Received RunWithBox(const GridShape& shape, int C, const std::vector<double>& input, AdvectionParameters p,
  const std::array<std::int64_t, 6>& box)
{
  p.writtenSamples = box;
  Received got{ std::vector<double>(input.size(), std::numeric_limits<double>::quiet_NaN()),
    std::vector<int>(static_cast<size_t>(shape.NumberOfSamples()), 0) };
  std::mutex lock;
  const SampleWriter writer = [&](std::int64_t first, std::int64_t count, const double* values) {
    const std::lock_guard<std::mutex> hold(lock);
    for (std::int64_t s = first; s < first + count; ++s)
    {
      ++got.times[static_cast<size_t>(s)];
      for (int c = 0; c < C; ++c)
      {
        got.values[static_cast<size_t>(s * C + c)] = values[(s - first) * C + c];
      }
    }
  };
  const Status status = AdvectGridSignal(shape, C, input.data(), writer, p);
  EXPECT_TRUE(status.Ok()) << status.error;
  return got;
}

/// Whether sample s of `shape` lies in `box` (an axis whose first is past its last is whole).
bool InBox(const GridShape& shape, const std::array<std::int64_t, 6>& box, std::int64_t s)
{
  const std::int64_t i[3] = { s % shape.dimensions[0], (s / shape.dimensions[0]) % shape.dimensions[1],
    s / shape.dimensions[0] / shape.dimensions[1] };
  for (int a = 0; a < 3; ++a)
  {
    if (box[2 * a] <= box[2 * a + 1] && (i[a] < box[2 * a] || i[a] > box[2 * a + 1]))
    {
      return false;
    }
  }
  return true;
}

/// The box run hands each box sample once, with the whole run's value, and nothing else.
void ExpectTheWholeRunsBox(const GridShape& shape, int C, const std::vector<double>& input,
  const AdvectionParameters& p, const std::array<std::int64_t, 6>& box, bool moves = true)
{
  SCOPED_TRACE(::testing::Message() << "box " << box[0] << " " << box[1] << " " << box[2] << " " << box[3] << " "
                                    << box[4] << " " << box[5]);
  const std::vector<double> whole = Filter(shape, C, input, p);
  ASSERT_EQ(whole.size(), input.size());
  const Received got = RunWithBox(shape, C, input, p, box);
  std::int64_t inside = 0;
  std::int64_t changed = 0;
  for (std::int64_t s = 0; s < shape.NumberOfSamples(); ++s)
  {
    if (!InBox(shape, box, s))
    {
      ASSERT_EQ(got.times[s], 0) << "sample " << s << " is outside the box";
      continue;
    }
    ++inside;
    ASSERT_EQ(got.times[s], 1) << "sample " << s;
    for (int c = 0; c < C; ++c)
    {
      const size_t v = static_cast<size_t>(s * C + c);
      // Bit for bit (NaN samples keep their NaN).
      ASSERT_TRUE(got.values[v] == whole[v] || (std::isnan(got.values[v]) && std::isnan(whole[v])))
        << "sample " << s << " component " << c << ": " << got.values[v] << " against " << whole[v];
      changed += got.values[v] != input[v] ? 1 : 0;
    }
  }
  EXPECT_GT(inside, 0);
  if (moves)
  {
    EXPECT_GT(changed, 0) << "the flow moved nothing in the box: the comparison proves little";
  }
}

TEST(GridWrittenSamples, ABoxOfAVolumeGetsTheWholeRunsValuesAndNothingElse)
{
  const GridShape shape = Grid(11, 9, 13);
  const auto input = Noisy(Bumps(shape, 2), 0.05, 3);
  for (FlowMode mode : { FlowMode::Fixed, FlowMode::Composed, FlowMode::Naive })
  {
    for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
    {
      AdvectionParameters p;
      p.time = 9.0;
      p.flowMode = mode;
      p.flowUpdates = 3;
      p.tracing = tracing;
      p.numberOfThreads = 2;
      SCOPED_TRACE(static_cast<int>(mode) * 10 + static_cast<int>(tracing));
      // A slab along z (as an image is split into pieces), and a box touching no border.
      ExpectTheWholeRunsBox(shape, 2, input, p, { 0, -1, 0, -1, 4, 9 });
      ExpectTheWholeRunsBox(shape, 2, input, p, { 2, 7, 1, 5, 3, 11 });
    }
  }
}

TEST(GridWrittenSamples, ImagesLinesNearestSamplingAndLevelsToo)
{
  const GridShape image = Grid(37, 23);
  const auto pixels = Noisy(Bumps(image, 3), 0.05, 5);
  AdvectionParameters p;
  p.time = 40.0;
  ExpectTheWholeRunsBox(image, 3, pixels, p, { 3, 30, 0, -1, 0, -1 });   // columns
  ExpectTheWholeRunsBox(image, 3, pixels, p, { 0, 36, 20, 22, 0, 0 });   // the last rows, every axis given
  ExpectTheWholeRunsBox(image, 3, pixels, p, { 5, 5, 4, 18, 0, -1 });    // one column
  p.sampling = Sampling::Nearest;
  p.time = 400.0;
  ExpectTheWholeRunsBox(image, 3, pixels, p, { 4, 20, 4, 18, 0, -1 });
  p.sampling = Sampling::Linear;
  p.time = 40.0;
  p.hierarchyLevels = 3;
  ExpectTheWholeRunsBox(image, 3, pixels, p, { 10, 25, 6, 16, 0, -1 });

  const GridShape line = Grid(300, 1);
  const auto values = Noisy(Bumps(line, 1), 0.02, 9);
  AdvectionParameters q;
  q.time = 100.0;
  ExpectTheWholeRunsBox(line, 1, values, q, { 40, 290, 0, -1, 0, -1 }); // longer than one row block
}

TEST(GridWrittenSamples, NonFiniteSamplesAndRunsWithoutFlowWriteTheBoxOnly)
{
  const GridShape shape = Grid(14, 12, 6);
  auto input = Bumps(shape, 1);
  input[3 * 14 * 12 + 5 * 14 + 7] = std::numeric_limits<double>::quiet_NaN();
  AdvectionParameters p;
  p.time = 16.0;
  ExpectTheWholeRunsBox(shape, 1, input, p, { 0, -1, 2, 9, 1, 4 });
  // t = 0 and a constant signal hand the input unchanged, and still the box only.
  p.time = 0.0;
  ExpectTheWholeRunsBox(shape, 1, input, p, { 0, -1, 2, 9, 1, 4 }, false);
  p.time = 16.0;
  ExpectTheWholeRunsBox(shape, 1, std::vector<double>(input.size(), 2.5), p, { 1, 3, 0, -1, 5, 5 }, false);
}

TEST(GridWrittenSamples, TheGradientDomainSolvesTheWholeGridAndHandsEverySample)
{
  // One Poisson problem over the whole grid: a box changes nothing of what is handed.
  const GridShape shape = Grid(23, 17);
  const auto input = Noisy(Bumps(shape, 2), 0.03, 11);
  GradientDomainParameters domain;
  const auto run = [&](const std::array<std::int64_t, 6>& box) {
    AdvectionParameters p;
    p.time = 30.0;
    p.writtenSamples = box;
    std::vector<double> out(input.size(), std::numeric_limits<double>::quiet_NaN());
    std::vector<int> times(static_cast<size_t>(shape.NumberOfSamples()), 0);
    std::mutex lock;
    const SampleWriter writer = [&](std::int64_t first, std::int64_t count, const double* values) {
      const std::lock_guard<std::mutex> hold(lock);
      std::copy(values, values + count * 2, out.begin() + first * 2);
      for (std::int64_t s = first; s < first + count; ++s)
      {
        ++times[static_cast<size_t>(s)];
      }
    };
    const Status status = AdvectGridGradients(shape, 2, input.data(), writer, p, domain);
    EXPECT_TRUE(status.Ok()) << status.error;
    EXPECT_TRUE(std::all_of(times.begin(), times.end(), [](int n) { return n == 1; }));
    return out;
  };
  const auto whole = run({ 0, -1, 0, -1, 0, -1 });
  const auto boxed = run({ 4, 15, 3, 9, 0, 0 });
  ASSERT_EQ(boxed, whole);
  EXPECT_NE(whole, input);
}

TEST(GridWrittenSamples, ABoxOutsideTheGridIsRefused)
{
  const GridShape shape = Grid(8, 6, 4);
  const auto input = Bumps(shape, 1);
  for (const std::array<std::int64_t, 6>& box : { std::array<std::int64_t, 6>{ 0, 8, 0, -1, 0, -1 },
         std::array<std::int64_t, 6>{ 0, -1, -1, 3, 0, -1 }, std::array<std::int64_t, 6>{ 0, -1, 0, -1, 2, 4 } })
  {
    AdvectionParameters p;
    p.time = 4.0;
    p.writtenSamples = box;
    std::vector<double> output(input.size());
    const Status status = AdvectGridSignal(shape, 1, input.data(), output.data(), p);
    ASSERT_FALSE(status.Ok());
    EXPECT_NE(status.error.find("written samples"), std::string::npos) << status.error;
  }
}
} // namespace
