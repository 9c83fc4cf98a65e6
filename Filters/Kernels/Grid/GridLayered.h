/**
 * @file GridLayered.h
 * @brief How the grid advection reads its signal: one array (`const T*`), or
 * the layers of a piece and its halo in up to three arrays (LayeredValues, from
 * a LayeredSignal of GridShockAdvection.h). Every read of the advection names
 * the lowest sample of what it reads (a cell's lower corner, a sample's 3^D
 * neighbourhood, one sample) and gets the array that holds it and the next
 * LayeredSignalOverlap layers (ValuesNear); for one array that is the array
 * itself, so the code built for it is the one-array code.
 */
#ifndef GridLayered_h
#define GridLayered_h

#include "GridShape.h"
#include "ShockTypes.h"

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace shock
{
namespace grid
{

/**
 * The arrays of a LayeredSignal as the kernel reads them: sample s of the grid
 * is at At(s) + s * C, where At picks `below` for the samples under `low`,
 * `above` from `high` on, `piece` between; each pointer is shifted back by the
 * samples before its array's first layer. Each array holds the
 * LayeredSignalOverlap layers after any sample it is picked for (GridShockAdvection.h).
 */
template <typename T>
struct LayeredValues
{
  const T* below = nullptr;
  const T* piece = nullptr;
  const T* above = nullptr;
  std::int64_t low = 0;  ///< samples [0, low) are read from `below`
  std::int64_t high = 0; ///< samples [high, end) from `above` (high >= low)

  SHOCK_ALWAYS_INLINE const T* At(std::int64_t s) const
  {
    return s < this->low ? this->below : (s >= this->high ? this->above : this->piece);
  }
};

/// The value type of a signal read through ValuesNear.
template <typename S>
struct SignalValueOf
{
  using Type = std::remove_cv_t<std::remove_pointer_t<S>>;
};
template <typename T>
struct SignalValueOf<LayeredValues<T>>
{
  using Type = T;
};
template <typename S>
using SignalValue = typename SignalValueOf<std::decay_t<S>>::Type;

/// Whether S is a signal in one array.
template <typename S>
constexpr bool IsOneArray = std::is_pointer_v<std::decay_t<S>>;

/// The array of sample s (and of the LayeredSignalOverlap layers after it): the array itself.
template <typename T>
SHOCK_ALWAYS_INLINE const T* ValuesNear(const T* values, std::int64_t)
{
  return values;
}

/// The array of sample s (and of the LayeredSignalOverlap layers after it).
template <typename T>
SHOCK_ALWAYS_INLINE const T* ValuesNear(const LayeredValues<T>& values, std::int64_t s)
{
  return values.At(s);
}

/// Calls run(first, count, values) once for samples [first, first + count) of one array.
template <typename T, typename Run>
void ForEachRun(const T* values, std::int64_t first, std::int64_t count, Run&& run)
{
  if (count > 0)
  {
    run(first, count, values);
  }
}

/**
 * Calls run(first, count, values) for the runs of samples [first, first + count)
 * that lie in one array, in order; values + s * C addresses each of a run's samples.
 */
template <typename T, typename Run>
void ForEachRun(const LayeredValues<T>& values, std::int64_t first, std::int64_t count, Run&& run)
{
  const std::int64_t end = first + count;
  const std::int64_t cuts[4] = { first, std::clamp(values.low, first, end), std::clamp(values.high, first, end), end };
  const T* arrays[3] = { values.below, values.piece, values.above };
  for (int k = 0; k < 3; ++k)
  {
    if (cuts[k + 1] > cuts[k])
    {
      run(cuts[k], cuts[k + 1] - cuts[k], arrays[k]);
    }
  }
}

/// Copies the C values of samples [first, first + count) into `to` as doubles.
template <typename S>
void CopySamples(const S& values, int C, std::int64_t first, std::int64_t count, double* to)
{
  ForEachRun(values, first, count, [&](std::int64_t from, std::int64_t n, const auto* array) {
    std::copy(array + from * C, array + (from + n) * C, to + (from - first) * C);
  });
}

/// Samples [first, first + count) of a signal in one array, as one array: in place.
template <typename T>
const T* SlabValues(const T* values, int C, std::int64_t first, std::int64_t, std::vector<T>&)
{
  return values + first * C;
}

/**
 * Samples [first, first + count) of a layered signal as one array (a slab of
 * the flow, GridFlow.h): in place when one array holds them all, else gathered
 * into `gathered`.
 */
template <typename T>
const T* SlabValues(const LayeredValues<T>& values, int C, std::int64_t first, std::int64_t count,
  std::vector<T>& gathered)
{
  int runs = 0;
  const T* array = nullptr;
  ForEachRun(values, first, count, [&](std::int64_t, std::int64_t, const T* a) {
    ++runs;
    array = a;
  });
  if (runs == 1)
  {
    return array + first * C;
  }
  gathered.resize(static_cast<size_t>(count * C));
  ForEachRun(values, first, count, [&](std::int64_t from, std::int64_t n, const T* a) {
    std::copy(a + from * C, a + (from + n) * C, gathered.begin() + (from - first) * C);
  });
  return gathered.data();
}

} // namespace grid
} // namespace shock

#endif
