#include "MeshOrder.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace shock
{

namespace
{
constexpr int BitsPerAxis = 10;
constexpr std::uint32_t Cells = 1u << BitsPerAxis;

/// The 10 bits of v spread to every third bit (bit k to bit 3k).
std::uint32_t Spread(std::uint32_t v)
{
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

/**
 * Stable sort of the indices 0..n-1 by their 30-bit keys: two passes of 15
 * bits (least significant first), each stable, so equal keys keep their order.
 */
IdVector SortByKeys(const CodeVector& keys)
{
  constexpr int Bits = 15;
  constexpr std::uint32_t Buckets = 1u << Bits;
  const auto n = static_cast<std::int64_t>(keys.size());
  IdVector order(static_cast<size_t>(n));
  IdVector next(static_cast<size_t>(n));
  std::vector<std::int64_t> start(Buckets + 1);
  for (int pass = 0; pass < 2; ++pass)
  {
    const int shift = Bits * pass;
    std::fill(start.begin(), start.end(), 0);
    for (std::int64_t i = 0; i < n; ++i)
    {
      ++start[((keys[static_cast<size_t>(i)] >> shift) & (Buckets - 1)) + 1];
    }
    for (std::uint32_t b = 0; b < Buckets; ++b)
    {
      start[b + 1] += start[b];
    }
    for (std::int64_t i = 0; i < n; ++i)
    {
      const std::int64_t item = pass == 0 ? i : order[static_cast<size_t>(i)];
      const std::uint32_t bucket = (keys[static_cast<size_t>(item)] >> shift) & (Buckets - 1);
      next[static_cast<size_t>(start[bucket]++)] = item;
    }
    order.swap(next);
  }
  return order;
}
} // namespace

std::uint32_t MortonCode(const double* point, const double lower[3], const double side[3])
{
  std::uint32_t code = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double cell = side[a] > 0.0 ? std::floor(Cells * (point[a] - lower[a]) / side[a]) : 0.0;
    // Clamped; NaN (an infinite side) to cell 0.
    const auto index =
      static_cast<std::uint32_t>(cell >= 0.0 ? std::min(cell, static_cast<double>(Cells - 1)) : 0.0);
    code |= Spread(index) << a;
  }
  return code;
}

MeshNumbering MortonOrder(std::int64_t numberOfPoints, const double* points, int threads, const double* box)
{
  MeshNumbering numbering;
  const std::int64_t np = numberOfPoints;
  threads = ThreadsForWork(threads, np);
  // The bounding box, and the scale that maps it onto the grid's cells.
  double lx = std::numeric_limits<double>::infinity();
  double ly = lx;
  double lz = lx;
  double ux = -lx;
  double uy = -lx;
  double uz = -lx;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(min : lx, ly, lz) reduction(max : ux, uy, uz)
  for (std::int64_t p = 0; p < np; ++p)
  {
    lx = std::min(lx, points[3 * p]);
    ly = std::min(ly, points[3 * p + 1]);
    lz = std::min(lz, points[3 * p + 2]);
    ux = std::max(ux, points[3 * p]);
    uy = std::max(uy, points[3 * p + 1]);
    uz = std::max(uz, points[3 * p + 2]);
  }
  if (box)
  {
    lx = box[0], ux = box[1], ly = box[2], uy = box[3], lz = box[4], uz = box[5];
  }
  const double lower[3] = { lx, ly, lz };
  const double side[3] = { ux - lx, uy - ly, uz - lz };
  CodeVector& codes = numbering.codes;
  codes.resize(static_cast<size_t>(np));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    codes[static_cast<size_t>(p)] = MortonCode(points + 3 * p, lower, side);
  }
  numbering.points = SortByKeys(codes);
  numbering.rank.resize(static_cast<size_t>(np));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < np; ++i)
  {
    numbering.rank[static_cast<size_t>(numbering.points[static_cast<size_t>(i)])] = i;
  }
  return numbering;
}

std::vector<std::int64_t> CoincidentPoints(const MeshNumbering& numbering, const double* points, int threads)
{
  const auto np = static_cast<std::int64_t>(numbering.points.size());
  const IdVector& order = numbering.points;
  const CodeVector& codes = numbering.codes;
  std::vector<std::int64_t> representative(static_cast<size_t>(np));
  auto same = [points](std::int64_t a, std::int64_t b) {
    return points[3 * a] == points[3 * b] && points[3 * a + 1] == points[3 * b + 1] &&
      points[3 * a + 2] == points[3 * b + 2];
  };
  auto codeAt = [&](std::int64_t i) { return codes[static_cast<size_t>(order[static_cast<size_t>(i)])]; };
  constexpr std::int64_t LongRun = 32;
  threads = ThreadsForWork(threads, np);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4096)
  for (std::int64_t i = 0; i < np; ++i)
  {
    if (i > 0 && codeAt(i) == codeAt(i - 1))
    {
      continue; // not the start of a run of equal codes
    }
    std::int64_t end = i + 1;
    while (end < np && codeAt(end) == codeAt(i))
    {
      ++end;
    }
    // Coincident points share a cell, so a run holds every copy of its points,
    // in their old order: the first copy found is the one with the smallest index.
    if (end - i <= LongRun)
    {
      for (std::int64_t j = i; j < end; ++j)
      {
        const std::int64_t p = order[static_cast<size_t>(j)];
        std::int64_t first = p;
        for (std::int64_t k = i; k < j; ++k)
        {
          const std::int64_t q = order[static_cast<size_t>(k)];
          if (representative[static_cast<size_t>(q)] == q && same(p, q))
          {
            first = q;
            break;
          }
        }
        representative[static_cast<size_t>(p)] = first;
      }
      continue;
    }
    // A long run (many points in one cell): sorted by coordinates, then index.
    std::vector<std::int64_t> run(order.begin() + i, order.begin() + end);
    std::sort(run.begin(), run.end(), [points](std::int64_t a, std::int64_t b) {
      for (int k = 0; k < 3; ++k)
      {
        if (points[3 * a + k] != points[3 * b + k])
        {
          return points[3 * a + k] < points[3 * b + k];
        }
      }
      return a < b;
    });
    for (size_t k = 0; k < run.size(); ++k)
    {
      const bool copy = k > 0 && same(run[k], run[k - 1]);
      representative[static_cast<size_t>(run[k])] = copy ? representative[static_cast<size_t>(run[k - 1])] : run[k];
    }
  }
  return representative;
}

void OrderTriangles(MeshNumbering& numbering, std::int64_t numberOfTriangles, const std::int64_t* ids, int threads)
{
  const auto np = static_cast<std::int64_t>(numbering.points.size());
  const std::int64_t nt = numberOfTriangles;
  threads = ThreadsForWork(threads, std::max(np, nt));

  // Triangles by their smallest corner's new index: a stable counting sort,
  // in parallel over chunks of triangles (each chunk's slots follow the earlier
  // chunks' in every key, so the order is the serial one).
  const std::int64_t* rank = numbering.rank.data();
  auto key = [&](std::int64_t f) {
    const std::int64_t* t = ids + 3 * f;
    return std::min({ rank[t[0]], rank[t[1]], rank[t[2]] });
  };
  // A few chunks: each holds a count per point.
  const int chunks = std::min(threads, 4);
  auto chunkBegin = [&](std::int64_t chunk) {
    return nt / chunks * chunk + std::min<std::int64_t>(chunk, nt % chunks);
  };
  IdVector slots(static_cast<size_t>(chunks) * static_cast<size_t>(np));
  IdVector start(static_cast<size_t>(np) + 1);
  numbering.triangles.resize(static_cast<size_t>(nt));
#pragma omp parallel num_threads(threads)
  {
#pragma omp for schedule(static)
    for (int chunk = 0; chunk < chunks; ++chunk)
    {
      std::int64_t* count = slots.data() + static_cast<size_t>(chunk) * static_cast<size_t>(np);
      std::fill(count, count + np, 0);
      for (std::int64_t f = chunkBegin(chunk); f < chunkBegin(chunk + 1); ++f)
      {
        ++count[key(f)];
      }
    }
    // Per key: the chunks' first slots relative to the key's, and the key's total.
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < np; ++p)
    {
      std::int64_t total = 0;
      for (int chunk = 0; chunk < chunks; ++chunk)
      {
        std::int64_t& slot = slots[static_cast<size_t>(chunk) * static_cast<size_t>(np) + static_cast<size_t>(p)];
        const std::int64_t mine = slot;
        slot = total;
        total += mine;
      }
      start[static_cast<size_t>(p) + 1] = total;
    }
#pragma omp single
    {
      start[0] = 0;
      for (std::int64_t p = 0; p < np; ++p)
      {
        start[static_cast<size_t>(p) + 1] += start[static_cast<size_t>(p)];
      }
    }
#pragma omp for schedule(static)
    for (int chunk = 0; chunk < chunks; ++chunk)
    {
      std::int64_t* slot = slots.data() + static_cast<size_t>(chunk) * static_cast<size_t>(np);
      for (std::int64_t f = chunkBegin(chunk); f < chunkBegin(chunk + 1); ++f)
      {
        const std::int64_t k = key(f);
        numbering.triangles[static_cast<size_t>(start[static_cast<size_t>(k)] + slot[k]++)] = f;
      }
    }
  }
}

MeshNumbering LocalityNumbering(std::int64_t numberOfPoints, const double* points,
  std::int64_t numberOfTriangles, const std::int64_t* ids, int threads)
{
  MeshNumbering numbering = MortonOrder(numberOfPoints, points, threads);
  OrderTriangles(numbering, numberOfTriangles, ids, threads);
  return numbering;
}

} // namespace shock
