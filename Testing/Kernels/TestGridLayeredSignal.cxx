// The grid advection on a LayeredSignal (GridShockAdvection.h): a piece held
// where it lies and the halo layers below and above it in arrays of their own,
// as a process of a distributed image holds them. The results must be those of
// the same values in one array, to the last bit, wherever the piece lies and
// however thin it is; a read from the wrong array must show. Each array sits
// between poison values (NaN, or 8-bit values far from the signal's), so that
// a read outside it changes the result.
#include "GridShockAdvection.h"
#include "TestSignals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <random>
#include <type_traits>
#include <vector>

namespace
{
using namespace shock;
using namespace shocktest;

/// What a run handed to its output (NaN where nothing was handed), its report and flow fields.
struct Outcome
{
  std::vector<double> values;
  AdvectionReport report;
  GridFlowFields fields;
  Status status;
};

SampleWriter Into(std::vector<double>& out, int C, std::mutex& lock)
{
  return [&out, C, &lock](std::int64_t first, std::int64_t count, const double* values) {
    const std::lock_guard<std::mutex> hold(lock);
    std::copy(values, values + count * C, out.begin() + first * C);
  };
}

/// Layers along the grid's last axis of more than one sample, and samples per layer.
void LayersOf(const GridShape& shape, std::int64_t& layers, std::int64_t& layerSamples)
{
  int axis = 0;
  for (int a = 0; a < 3; ++a)
  {
    axis = shape.dimensions[a] > 1 ? a : axis;
  }
  layers = shape.dimensions[axis];
  layerSamples = 1;
  for (int a = 0; a < axis; ++a)
  {
    layerSamples *= shape.dimensions[a];
  }
}

/// The arrays of a layered signal, each between `margin` layers of poison.
template <typename T>
struct Arrays
{
  std::vector<T> below, piece, above;
  LayeredSignal<T> signal;
};

template <typename T>
T Poison()
{
  if constexpr (std::is_floating_point_v<T>)
  {
    return std::numeric_limits<T>::quiet_NaN();
  }
  else
  {
    return static_cast<T>(251);
  }
}

/// Layers [first, end) of `all` (C per sample) in an array between poison layers; its first layer's address.
template <typename T>
const T* Store(const std::vector<T>& all, int C, std::int64_t layerSamples, std::int64_t first, std::int64_t end,
  std::vector<T>& into)
{
  const std::int64_t layer = layerSamples * C;
  const std::int64_t margin = 3 * layer;
  into.assign(static_cast<size_t>(2 * margin + (end - first) * layer), Poison<T>());
  std::copy(all.begin() + first * layer, all.begin() + end * layer, into.begin() + margin);
  return into.data() + margin;
}

template <typename T>
Arrays<T> Split(const GridShape& shape, int C, const std::vector<T>& all, std::int64_t first, std::int64_t end)
{
  std::int64_t n = 0;
  std::int64_t layerSamples = 0;
  LayersOf(shape, n, layerSamples);
  constexpr std::int64_t O = LayeredSignalOverlap;
  Arrays<T> a;
  a.signal.pieceFirst = first;
  a.signal.pieceEnd = end;
  a.signal.piece = Store(all, C, layerSamples, first, end, a.piece);
  if (first > 0)
  {
    a.signal.below = Store(all, C, layerSamples, 0, std::min(first + O, n), a.below);
  }
  if (end < n)
  {
    a.signal.above = Store(all, C, layerSamples, std::max<std::int64_t>(end - O, 0), n, a.above);
  }
  return a;
}

template <typename Input>
Outcome Advect(const GridShape& shape, int C, const Input& input, const AdvectionParameters& p)
{
  Outcome run;
  run.values.assign(static_cast<size_t>(shape.NumberOfSamples() * C), std::numeric_limits<double>::quiet_NaN());
  std::mutex lock;
  run.status = AdvectGridSignal(shape, C, input, Into(run.values, C, lock), p, &run.report, &run.fields);
  return run;
}

/// Bit for bit, NaN where nothing was written on both sides.
bool SameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// A signal with structure on every axis and channel, as T (8-bit: 0..250, so that the poison 251 is out of range).
template <typename T>
std::vector<T> Signal(const GridShape& shape, int C, unsigned seed)
{
  const std::vector<double> smooth = Noisy(Bumps(shape, C, 0.37 * seed), 0.05, seed);
  std::vector<T> values(smooth.size());
  const double low = *std::min_element(smooth.begin(), smooth.end());
  const double high = *std::max_element(smooth.begin(), smooth.end());
  for (size_t k = 0; k < smooth.size(); ++k)
  {
    const double unit = (smooth[k] - low) / (high - low);
    values[k] = std::is_floating_point_v<T> ? static_cast<T>(unit) : static_cast<T>(std::lround(250.0 * unit));
  }
  return values;
}

/// The box of layers [first, end) along the last axis of more than one sample.
std::array<std::int64_t, 6> PieceBox(const GridShape& shape, std::int64_t first, std::int64_t end)
{
  std::array<std::int64_t, 6> box{ { 0, -1, 0, -1, 0, -1 } };
  int axis = 0;
  for (int a = 0; a < 3; ++a)
  {
    axis = shape.dimensions[a] > 1 ? a : axis;
  }
  box[2 * axis] = first;
  box[2 * axis + 1] = end - 1;
  return box;
}

/**
 * Every piece position of `pieces` on `shape`: the layered run hands the same
 * values as the one-array run (the piece's samples, or every sample), with the
 * same report and flow fields, and the advection changed the piece.
 */
template <typename T>
void ExpectTheOneArrayRun(const GridShape& shape, int C, AdvectionParameters p,
  const std::vector<std::array<std::int64_t, 2>>& pieces, unsigned seed, bool writePiece = true)
{
  const std::vector<T> all = Signal<T>(shape, C, seed);
  for (const auto& piece : pieces)
  {
    SCOPED_TRACE(::testing::Message() << "piece layers " << piece[0] << " to " << piece[1]);
    if (writePiece)
    {
      p.writtenSamples = PieceBox(shape, piece[0], piece[1]);
    }
    const Outcome one = Advect(shape, C, all.data(), p);
    const Arrays<T> arrays = Split(shape, C, all, piece[0], piece[1]);
    const Outcome layered = Advect(shape, C, arrays.signal, p);
    ASSERT_TRUE(one.status.Ok()) << one.status.error;
    ASSERT_TRUE(layered.status.Ok()) << layered.status.error;
    EXPECT_TRUE(SameBits(one.values, layered.values));
    EXPECT_TRUE(SameBits(one.fields.flow, layered.fields.flow));
    EXPECT_TRUE(SameBits(one.fields.potential, layered.fields.potential));
    EXPECT_EQ(one.report.traceSteps, layered.report.traceSteps);
    EXPECT_EQ(one.report.haloReach, layered.report.haloReach);
    // Not the identity: the traces moved values of the piece.
    std::int64_t changed = 0;
    for (size_t k = 0; k < all.size(); ++k)
    {
      changed += !std::isnan(layered.values[k]) && layered.values[k] != static_cast<double>(all[k]);
    }
    EXPECT_GT(changed, 0);
  }
}

GridShape Irregular(int nx, int ny, int nz)
{
  GridShape shape = Grid(nx, ny, nz);
  shape.spacing = { 1.0, 1.3, 0.8 };
  return shape;
}

AdvectionParameters Parameters(double time)
{
  AdvectionParameters p;
  p.time = time;
  p.numberOfThreads = 2;
  return p;
}

} // namespace

TEST(GridLayeredSignal, AVolumePieceAnywhereGivesTheOneArrayResult)
{
  // The piece at the bottom, in the middle, at the top, one and two layers
  // thick (thinner than the arrays' overlap), and the whole grid.
  const GridShape shape = Irregular(9, 7, 14);
  ExpectTheOneArrayRun<float>(
    shape, 1, Parameters(6.0), { { 0, 6 }, { 4, 10 }, { 8, 14 }, { 6, 7 }, { 5, 7 }, { 1, 13 }, { 0, 14 } }, 1);
  ExpectTheOneArrayRun<double>(shape, 3, Parameters(3.0), { { 0, 5 }, { 5, 9 }, { 9, 14 }, { 13, 14 }, { 0, 1 } }, 2);
  ExpectTheOneArrayRun<unsigned char>(shape, 4, Parameters(4.0), { { 3, 8 }, { 0, 2 }, { 12, 14 } }, 3);
  // Every sample written, not only the piece's (the halo's results too).
  ExpectTheOneArrayRun<float>(shape, 2, Parameters(6.0), { { 4, 10 }, { 0, 3 } }, 4, false);
}

TEST(GridLayeredSignal, ImagesAndLinesGiveTheOneArrayResult)
{
  // 2D: layers are rows; 8-bit RGB and RGBA (the one-array run may read them
  // four bytes at a time), float and double; 1D: layers are samples.
  const GridShape image = Irregular(23, 17, 1);
  ExpectTheOneArrayRun<unsigned char>(image, 3, Parameters(12.0), { { 0, 7 }, { 6, 11 }, { 10, 17 }, { 8, 9 } }, 5);
  ExpectTheOneArrayRun<unsigned char>(image, 4, Parameters(40.0), { { 5, 12 } }, 6);
  ExpectTheOneArrayRun<float>(image, 1, Parameters(80.0), { { 2, 9 }, { 9, 17 } }, 7);
  ExpectTheOneArrayRun<double>(Grid(61, 1, 1), 2, Parameters(30.0), { { 0, 20 }, { 20, 40 }, { 40, 61 }, { 30, 31 } }, 8);
  // A flat grid whose layers run along y with z flat: the last axis of more than one sample.
  ExpectTheOneArrayRun<float>(Irregular(1, 19, 1), 1, Parameters(20.0), { { 4, 12 } }, 9);
  ExpectTheOneArrayRun<float>(Irregular(13, 1, 11), 1, Parameters(5.0), { { 3, 8 } }, 10);
}

TEST(GridLayeredSignal, EveryRoadOfTheAdvectionGivesTheOneArrayResult)
{
  const GridShape volume = Irregular(8, 9, 12);
  // Nearest sampling and the Composed flow (the paper's path, sample by sample).
  AdvectionParameters nearest = Parameters(60.0);
  nearest.sampling = Sampling::Nearest;
  ExpectTheOneArrayRun<float>(volume, 1, nearest, { { 3, 8 }, { 0, 4 } }, 11);
  AdvectionParameters composed = Parameters(5.0);
  composed.flowMode = FlowMode::Composed;
  composed.flowUpdates = 1;
  ExpectTheOneArrayRun<double>(volume, 2, composed, { { 4, 9 } }, 12);
  // Updates after the first read the last result from a buffer of their own.
  AdvectionParameters naive = Parameters(5.0);
  naive.flowMode = FlowMode::Naive;
  naive.flowUpdates = 3;
  ExpectTheOneArrayRun<float>(volume, 1, naive, { { 4, 9 } }, 13, false);
  // Two smoothing passes (a deeper stencil) and the stepped tracer.
  AdvectionParameters deep = Parameters(5.0);
  deep.smoothingPasses = 2;
  deep.tracing = Tracing::Stepped;
  ExpectTheOneArrayRun<float>(volume, 1, deep, { { 2, 10 } }, 14);
  // One flow slab per few layers: slabs that straddle the arrays are gathered.
  ExpectTheOneArrayRun<float>(Irregular(5, 4, 40), 1, Parameters(5.0), { { 13, 27 }, { 0, 20 } }, 15);
}

TEST(GridLayeredSignal, NonFiniteSamplesInThePieceAndTheHaloGiveTheOneArrayResult)
{
  const GridShape shape = Irregular(9, 8, 12);
  std::vector<double> all = Signal<double>(shape, 1, 16);
  const std::int64_t layer = 9 * 8;
  // A NaN below the piece, one in it, an infinity above it.
  all[static_cast<size_t>(2 * layer + 13)] = std::numeric_limits<double>::quiet_NaN();
  all[static_cast<size_t>(6 * layer + 30)] = std::numeric_limits<double>::quiet_NaN();
  all[static_cast<size_t>(10 * layer + 40)] = std::numeric_limits<double>::infinity();
  AdvectionParameters p = Parameters(4.0);
  p.writtenSamples = PieceBox(shape, 4, 9);
  const Outcome one = Advect(shape, 1, all.data(), p);
  const Arrays<double> arrays = Split(shape, 1, all, 4, 9);
  const Outcome layered = Advect(shape, 1, arrays.signal, p);
  ASSERT_TRUE(layered.status.Ok()) << layered.status.error;
  EXPECT_TRUE(SameBits(one.values, layered.values));
  EXPECT_TRUE(std::isnan(layered.values[static_cast<size_t>(6 * layer + 30)])); // kept, not spread
}

TEST(GridLayeredSignal, ArraysThatDoNotFitTheGridAreRefused)
{
  const GridShape shape = Grid(6, 5, 8);
  const std::vector<float> all = Signal<float>(shape, 1, 17);
  const Arrays<float> arrays = Split(shape, 1, all, 2, 6);
  const auto refused = [&](LayeredSignal<float> signal, AdvectionParameters p, const char* words) {
    const Outcome run = Advect(shape, 1, signal, p);
    EXPECT_FALSE(run.status.Ok());
    EXPECT_NE(run.status.error.find(words), std::string::npos) << run.status.error;
  };
  LayeredSignal<float> noBelow = arrays.signal;
  noBelow.below = nullptr;
  refused(noBelow, Parameters(1.0), "array below it");
  LayeredSignal<float> beyond = arrays.signal;
  beyond.pieceEnd = 9;
  refused(beyond, Parameters(1.0), "within the grid");
  LayeredSignal<float> empty = arrays.signal;
  empty.pieceEnd = empty.pieceFirst;
  refused(empty, Parameters(1.0), "within the grid");
  AdvectionParameters levels = Parameters(1.0);
  levels.hierarchyLevels = 2;
  refused(arrays.signal, levels, "coarser levels");
  // And the arrays as made are taken.
  EXPECT_TRUE(Advect(shape, 1, arrays.signal, Parameters(1.0)).status.Ok());
}
