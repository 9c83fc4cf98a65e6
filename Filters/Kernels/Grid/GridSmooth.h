/**
 * @file GridSmooth.h
 * @brief Step 1 of the flow on a regular grid (GridFlow.h): umbrella smoothing
 * with Gaussian weights exp(-|(v-w)/l|^2) over the grid one-ring, before each
 * gradient (section 3.3 of Prada and Kazhdan 2015). SmoothPass is the step;
 * SmoothRowFused and SmoothBlockAllValid give its bits faster where every
 * sample is valid. Loops use OpenMP: include only from translation units built
 * with it.
 */
#ifndef GridSmooth_h
#define GridSmooth_h

#include "GridLattice.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

#include <omp.h>

namespace shock
{
namespace grid
{

/**
 * SmoothPass on a block of one row when every sample is valid: the block's
 * `count` values (C per sample), with K neighbour rows along the other axes at
 * sample offsets `offset` and weights `weight`, each value in one pass. The
 * operations are the masked path's in its order (the value, plus its left and
 * right neighbours' terms where they exist, plus the rows' terms, times the
 * weight total's share), so the results are its bits. The weight total is the
 * same along the row except at its ends (`rowStart`, `rowEnd`: the block holds
 * them; a row has >= 2 samples).
 */
template <int K, size_t N, typename T>
void SmoothRowFused(int C, const T* in, double scale, double* out, std::int64_t count,
  bool rowStart, bool rowEnd, double alphaX, const std::array<std::int64_t, N>& offset,
  const std::array<double, N>& weight)
{
  static_assert(K <= static_cast<int>(N), "more neighbour rows than offsets");
  std::array<const T*, K> rows{};
  std::array<double, K> w{};
  double total = 1.0 + alphaX + alphaX;
  double edgeTotal = 1.0 + alphaX;
  for (int r = 0; r < K; ++r)
  {
    rows[r] = in + offset[r] * C;
    w[r] = weight[r];
  }
  for (int r = 0; r < K; ++r)
  {
    total += w[r];
    edgeTotal += w[r];
  }
  const double inner = scale / total;
  const double edge = scale / edgeTotal;
  // A value at the row's start or end: the neighbour it has, along x.
  const auto endValue = [&](std::int64_t v, bool left) {
    double o = static_cast<double>(in[v]);
    o += alphaX * (left ? in[v - C] : in[v + C]);
    for (int r = 0; r < K; ++r)
    {
      o += w[r] * rows[r][v];
    }
    out[v] = o * edge;
  };
  const std::int64_t innerBegin = rowStart ? C : 0;
  const std::int64_t innerEnd = rowEnd ? count - C : count;
  for (std::int64_t v = 0; v < innerBegin; ++v)
  {
    endValue(v, false);
  }
  for (std::int64_t v = innerBegin; v < innerEnd; ++v)
  {
    double o = static_cast<double>(in[v]);
    o += alphaX * in[v - C];
    o += alphaX * in[v + C];
    for (int r = 0; r < K; ++r)
    {
      o += w[r] * rows[r][v];
    }
    out[v] = o * inner;
  }
  for (std::int64_t v = innerEnd; v < count; ++v)
  {
    endValue(v, true);
  }
}

/// SmoothRowFused for a block of `length` samples with `neighbours` (0 .. N, at most 4) rows.
template <size_t N, typename T>
void SmoothBlockAllValid(int C, const T* in, double scale, double* out,
  std::int64_t length, bool rowStart, bool rowEnd, double alphaX, int neighbours,
  const std::array<std::int64_t, N>& offset, const std::array<double, N>& weight)
{
  const std::int64_t count = length * C;
  assert(neighbours >= 0 && neighbours <= std::min<int>(static_cast<int>(N), 4));
  switch (neighbours)
  {
    case 0:
      SmoothRowFused<0>(C, in, scale, out, count, rowStart, rowEnd, alphaX, offset, weight);
      break;
    case 1:
      SmoothRowFused<1>(C, in, scale, out, count, rowStart, rowEnd, alphaX, offset, weight);
      break;
    case 2:
      SmoothRowFused<2>(C, in, scale, out, count, rowStart, rowEnd, alphaX, offset, weight);
      break;
    case 3:
      if constexpr (N >= 3)
      {
        SmoothRowFused<3>(C, in, scale, out, count, rowStart, rowEnd, alphaX, offset, weight);
      }
      break;
    default:
      if constexpr (N >= 4)
      {
        SmoothRowFused<4>(C, in, scale, out, count, rowStart, rowEnd, alphaX, offset, weight);
      }
      break;
  }
}

/**
 * One pass of the Appendix A umbrella smoothing with Gaussian weights
 * exp(-|(v-w)/l|^2) over the grid one-ring (the 2D neighbours along the active
 * axes), scaled: out = scale x smooth(in). Invalid samples (`valid` non-null and
 * 0) neither change nor contribute.
 */
template <int D, typename T>
void SmoothPass(const Lattice<D>& L, int C, const T* in, double scale, double* out,
  const unsigned char* valid, int threads)
{
  std::array<double, D> alpha{};
  for (int d = 0; d < D; ++d)
  {
    alpha[d] = std::exp(-L.h2[d]);
  }
  ForEachSampleBlock<D>(L, threads, [=, &L](const auto& i, std::int64_t s0, std::int64_t length) {
    // The neighbours along the other axes are the same for the whole block.
    std::array<std::int64_t, 2 * D> offset{};
    std::array<double, 2 * D> weight{};
    int neighbours = 0;
    for (int d = 1; d < D; ++d)
    {
      for (int dir = -1; dir <= 1; dir += 2)
      {
        if (i[d] + dir >= 0 && i[d] + dir < L.n[d])
        {
          offset[neighbours] = dir * L.sampleStride[d];
          weight[neighbours] = alpha[d];
          ++neighbours;
        }
      }
    }
    if (!valid)
    {
      SmoothBlockAllValid(C, in + s0 * C, scale, out + s0 * C, length, i[0] == 0,
        i[0] + length == L.n[0], alpha[0], neighbours, offset, weight);
      return;
    }
    for (std::int64_t j = 0; j < length; ++j)
    {
      const std::int64_t x = i[0] + j;
      const std::int64_t s = s0 + j;
      double* o = out + s * C;
      std::copy(in + s * C, in + (s + 1) * C, o);
      double total = 1.0;
      const auto add = [&](std::int64_t w, double a) {
        if (valid[w])
        {
          total += a;
          for (int c = 0; c < C; ++c)
          {
            o[c] += a * in[w * C + c];
          }
        }
      };
      if (valid[s])
      {
        if (x > 0)
        {
          add(s - 1, alpha[0]);
        }
        if (x + 1 < L.n[0])
        {
          add(s + 1, alpha[0]);
        }
        for (int r = 0; r < neighbours; ++r)
        {
          add(s + offset[r], weight[r]);
        }
      }
      const double factor = scale / total;
      for (int c = 0; c < C; ++c)
      {
        o[c] *= factor;
      }
    }
  });
}

/**
 * `passes` smoothing passes (SmoothPass) of scale x in, into out; passes = 0 gives
 * the scaled copy. `scratch`, of the size of out, is used when passes >= 2.
 * `in` is float, double or 8-bit; the passes compute in double.
 */
template <int D, typename T>
void UmbrellaSmooth(const Lattice<D>& L, int C, const T* in, double scale, double* out,
  double* scratch, const unsigned char* valid, int passes, int threads)
{
  if (passes == 0)
  {
    const std::int64_t count = L.numSamples * C;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t v = 0; v < count; ++v)
    {
      out[v] = scale * in[v];
    }
    return;
  }
  // Alternate between the buffers so that the last pass writes `out`.
  double* target = (passes - 1) % 2 == 0 ? out : scratch;
  SmoothPass<D>(L, C, in, scale, target, valid, threads);
  for (int pass = 1; pass < passes; ++pass)
  {
    const double* source = target;
    target = (passes - 1 - pass) % 2 == 0 ? out : scratch;
    SmoothPass<D>(L, C, source, 1.0, target, valid, threads);
  }
}
} // namespace grid
} // namespace shock

#endif
