#include "FitSolve.h"

#include <Eigen/SparseCholesky>

#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace shock
{
namespace fit
{
namespace
{
/// Rows owned by this piece (all rows without a partition).
const std::vector<char>* Owned(const MeshPartition* partition)
{
  return partition ? &partition->ownedPoints : nullptr;
}

/// Row i of A y for the three columns, with y's row j given by value(j, k).
template <typename Value>
inline void MultiplyRow(const RowMatrix& A, std::int64_t i, Value value, double out[3])
{
  const int* inner = A.innerIndexPtr();
  const double* values = A.valuePtr();
  const int begin = A.outerIndexPtr()[i];
  const int end = A.outerIndexPtr()[i + 1];
  double sum0 = 0.0, sum1 = 0.0, sum2 = 0.0;
  for (int e = begin; e < end; ++e)
  {
    const std::int64_t j = inner[e];
    const double a = values[e];
    sum0 += a * value(j, 0);
    sum1 += a * value(j, 1);
    sum2 += a * value(j, 2);
  }
  out[0] = sum0;
  out[1] = sum1;
  out[2] = sum2;
}

/// The vectors of the conjugate gradients, the three coordinates side by side.
struct Vectors
{
  Coordinates r, p, q; ///< residual, direction, A p
};

/**
 * What an iteration leaves to the next product's pass, row by row: the step
 * of x along the direction just used, x += step p (so that the pass of the
 * steps reads neither x nor p), then the next direction p = z + ratio p
 * (z = D^-1 r).
 */
struct DirectionUpdate
{
  double step[3];
  double ratio[3];
};

/// x_i += step p_i and p_i = z_i + ratio p_i; x_i only where `stepX`.
inline void UpdateRow(const std::vector<double>& diag, const DirectionUpdate& u, std::int64_t i,
  bool stepX, Vectors& v, Coordinates& x)
{
  for (int k = 0; k < 3; ++k)
  {
    if (stepX)
    {
      x(i, k) += u.step[k] * v.p(i, k);
    }
    v.p(i, k) = diag[static_cast<size_t>(i)] * v.r(i, k) + u.ratio[k] * v.p(i, k);
  }
}

/**
 * UpdateRow on rows [begin, end), x included: one tight loop over contiguous
 * rows; with `only`, the rows i with only[i] != 0 alone.
 */
void UpdateRows(const std::vector<double>& diag, const DirectionUpdate& u, std::int64_t begin,
  std::int64_t end, const char* only, Vectors& v, Coordinates& x)
{
  double* xs = x.data();
  double* ps = v.p.data();
  const double* rs = v.r.data();
  for (std::int64_t i = begin; i < end; ++i)
  {
    if (only && !only[i])
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const size_t e = static_cast<size_t>(3 * i + k);
      xs[e] += u.step[k] * ps[e];
      ps[e] = diag[static_cast<size_t>(i)] * rs[e] + u.ratio[k] * ps[e];
    }
  }
}

/**
 * How the product passes share the rows: one contiguous range of whole
 * SumBlock blocks per thread (so that the sums stay those of fixed blocks).
 * The shared rows of a range are those that other ranges' rows read,
 * conservatively: its head, up to the last column read by an earlier range,
 * and its tail, from the first column read by a later one. A range's shared
 * rows are updated before any range is multiplied (one barrier), its middle
 * rows a block at a time, just ahead of the block's products (up to the
 * block's reach, the last column its rows read): the update then costs no
 * pass of its own over memory.
 */
struct RowRanges
{
  int teams = 1;
  std::int64_t blocks = 0;
  std::vector<std::int64_t> firstBlock; ///< per thread + 1: the blocks of thread t are [firstBlock[t], firstBlock[t + 1])
  std::vector<std::int64_t> headEnd;    ///< per thread: rows [range begin, headEnd) are shared
  std::vector<std::int64_t> tailBegin;  ///< per thread: rows [max(headEnd, tailBegin), range end) are shared
  std::vector<std::int64_t> blockReach; ///< per block: 1 + the last row its rows read (their own included)

  RowRanges(const RowMatrix& A, int threads)
  {
    const std::int64_t n = A.rows();
    this->blocks = (n + SumBlock - 1) / SumBlock;
    this->teams = static_cast<int>(std::max<std::int64_t>(1, std::min<std::int64_t>(threads, this->blocks)));
    this->firstBlock.resize(static_cast<size_t>(this->teams) + 1);
    for (int t = 0; t <= this->teams; ++t)
    {
      this->firstBlock[static_cast<size_t>(t)] = this->blocks * t / this->teams;
    }
    // The lowest and highest column each range reads (the columns of a row are sorted).
    std::vector<std::int64_t> low(static_cast<size_t>(this->teams), n);
    std::vector<std::int64_t> high(static_cast<size_t>(this->teams), -1);
    this->blockReach.resize(static_cast<size_t>(this->blocks));
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
#pragma omp parallel for num_threads(this->teams) schedule(static, 1)
    for (int t = 0; t < this->teams; ++t)
    {
      for (std::int64_t b = this->firstBlock[static_cast<size_t>(t)];
           b < this->firstBlock[static_cast<size_t>(t) + 1]; ++b)
      {
        std::int64_t reach = 0;
        for (std::int64_t i = b * SumBlock; i < std::min(n, (b + 1) * SumBlock); ++i)
        {
          reach = std::max(reach, i + 1);
          if (outer[i] < outer[i + 1])
          {
            low[static_cast<size_t>(t)] = std::min<std::int64_t>(low[static_cast<size_t>(t)], inner[outer[i]]);
            high[static_cast<size_t>(t)] = std::max<std::int64_t>(high[static_cast<size_t>(t)], inner[outer[i + 1] - 1]);
            reach = std::max<std::int64_t>(reach, inner[outer[i + 1] - 1] + 1);
          }
        }
        this->blockReach[static_cast<size_t>(b)] = reach;
      }
    }
    this->headEnd.resize(static_cast<size_t>(this->teams));
    this->tailBegin.resize(static_cast<size_t>(this->teams));
    for (int t = 0; t < this->teams; ++t)
    {
      std::int64_t before = -1; // highest column read by an earlier range
      std::int64_t after = n;   // lowest column read by a later range
      for (int u = 0; u < this->teams; ++u)
      {
        before = u < t ? std::max(before, high[static_cast<size_t>(u)]) : before;
        after = u > t ? std::min(after, low[static_cast<size_t>(u)]) : after;
      }
      const std::int64_t begin = this->Begin(t, n);
      const std::int64_t end = this->End(t, n);
      this->headEnd[static_cast<size_t>(t)] = std::min(end, std::max(begin, before + 1));
      this->tailBegin[static_cast<size_t>(t)] = std::max(begin, std::min(end, after));
    }
  }
  std::int64_t Begin(int t, std::int64_t n) const
  {
    return std::min(n, this->firstBlock[static_cast<size_t>(t)] * SumBlock);
  }
  std::int64_t End(int t, std::int64_t n) const
  {
    return std::min(n, this->firstBlock[static_cast<size_t>(t) + 1] * SumBlock);
  }
};

/**
 * q = A p and the sums p.q, block by block as BlockSums does; with `update`,
 * the rows are first updated (DirectionUpdate), each once and before any row
 * reads its direction (RowRanges), in the same pass. On a piece, `updated`
 * names the rows this pass updates (the others are updated before it, or are
 * the halo, which the exchange before it wrote) and `owned` the rows whose
 * products and sums are the piece's (null: every row).
 */
std::array<double, 3> UpdateAndMultiply(const RowMatrix& A, const std::vector<double>& diag,
  const RowRanges& ranges, const DirectionUpdate* update, const char* updated, const char* owned,
  Vectors& v, Coordinates& x)
{
  const std::int64_t n = A.rows();
  std::vector<std::array<double, 3>> partial(static_cast<size_t>(ranges.blocks));
#pragma omp parallel num_threads(ranges.teams)
  {
    // Each thread takes its range; a team smaller than asked for (nested in
    // another parallel region) takes every team-th range.
#ifdef _OPENMP
    const int thread = omp_get_thread_num();
    const int team = omp_get_num_threads();
#else
    const int thread = 0;
    const int team = 1;
#endif
    for (int t = thread; t < ranges.teams && update; t += team)
    {
      const std::int64_t headEnd = ranges.headEnd[static_cast<size_t>(t)];
      UpdateRows(diag, *update, ranges.Begin(t, n), headEnd, updated, v, x);
      UpdateRows(
        diag, *update, std::max(headEnd, ranges.tailBegin[static_cast<size_t>(t)]), ranges.End(t, n), updated, v, x);
    }
#pragma omp barrier
    for (int t = thread; t < ranges.teams; t += team)
    {
      const std::int64_t headEnd = ranges.headEnd[static_cast<size_t>(t)];
      const std::int64_t middleEnd = std::max(headEnd, ranges.tailBegin[static_cast<size_t>(t)]);
      std::int64_t done = update ? headEnd : middleEnd; // the middle rows before this one are updated
      for (std::int64_t b = ranges.firstBlock[static_cast<size_t>(t)];
           b < ranges.firstBlock[static_cast<size_t>(t) + 1]; ++b)
      {
        const std::int64_t reach = std::min(middleEnd, ranges.blockReach[static_cast<size_t>(b)]);
        if (done < reach)
        {
          UpdateRows(diag, *update, done, reach, updated, v, x);
          done = reach;
        }
        std::array<double, 3> sums{};
        for (std::int64_t i = b * SumBlock; i < std::min(n, (b + 1) * SumBlock); ++i)
        {
          if (owned && !owned[i])
          {
            continue;
          }
          double ap[3];
          MultiplyRow(A, i, [&](std::int64_t j, int k) { return v.p(j, k); }, ap);
          for (int k = 0; k < 3; ++k)
          {
            v.q(i, k) = ap[k];
            sums[k] += v.p(i, k) * ap[k];
          }
        }
        partial[static_cast<size_t>(b)] = sums;
      }
    }
  }
  std::array<double, 3> total{};
  for (const auto& sums : partial)
  {
    for (int k = 0; k < 3; ++k)
    {
      total[k] += sums[k];
    }
  }
  return total;
}

/**
 * Which rows of a piece the conjugate gradients update where: `shared`, the
 * owned rows other pieces read, are updated before each exchange, so that it
 * sends their new directions; `inPass`, the other owned rows, in the pass of
 * the products, as in a serial solve. Rows the piece does not own are never
 * updated: the halo among them takes its owners' directions in the exchange,
 * and no owned row reads the others.
 */
struct PieceRows
{
  std::vector<std::int64_t> shared;
  std::vector<char> inPass;

  /// Nothing without a partition (a serial solve).
  explicit PieceRows(const MeshPartition* partition)
  {
    if (!partition)
    {
      return;
    }
    const std::vector<char>& owned = partition->ownedPoints;
    const bool known = partition->sharedPoints.size() == owned.size();
    this->inPass.assign(owned.size(), 0);
    for (size_t i = 0; i < owned.size(); ++i)
    {
      if (owned[i] && (!known || partition->sharedPoints[i]))
      {
        this->shared.push_back(static_cast<std::int64_t>(i));
      }
      else if (owned[i])
      {
        this->inPass[i] = 1;
      }
    }
  }
};

/**
 * On a piece: the update (when given) of the rows other pieces read, the
 * owners' p to the halo, then the update of the other owned rows fused with
 * q = A p on the owned rows and the sums p.q over all pieces.
 */
std::array<double, 3> UpdateAndMultiplyPiece(const RowMatrix& A, const std::vector<double>& diag,
  const RowRanges& ranges, int threads, const MeshPartition* partition, const PieceRows& rows,
  const DirectionUpdate* update, Vectors& v, Coordinates& x)
{
  if (update)
  {
    const std::int64_t count = static_cast<std::int64_t>(rows.shared.size());
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t s = 0; s < count; ++s)
    {
      UpdateRow(diag, *update, rows.shared[static_cast<size_t>(s)], true, v, x);
    }
  }
  partition->exchangePoints(v.p.data());
  std::array<double, 3> total =
    UpdateAndMultiply(A, diag, ranges, update, rows.inPass.data(), partition->ownedPoints.data(), v, x);
  partition->globalSum(total.data(), 3);
  return total;
}

/// The vectors r, p, q of n rows: zeroed on a piece, else left to be first touched in parallel.
Vectors AllocateVectors(std::int64_t n, const MeshPartition* partition)
{
  Vectors v;
  if (partition)
  {
    v.r = v.p = v.q = Coordinates::Zero(n, 3); // rows a piece does not own are never computed
  }
  else
  {
    v.r.resize(n, 3); // every row is written before it is read: first touched in parallel
    v.p.resize(n, 3);
    v.q.resize(n, 3);
  }
  return v;
}

/**
 * The start of the conjugate gradients: x = x0, r = b - A x0, p = z = D^-1 r;
 * returns the sums of r.r, r.z and b.b (the three columns of each).
 */
std::array<double, 9> StartingResidual(const FitSystemData& system, const Coordinates& b,
  const Coordinates& x0, int threads, const MeshPartition* partition, Vectors& v, Coordinates& x)
{
  const RowMatrix& A = system.matrix;
  const std::vector<double>& diag = system.inverseDiagonal;
  const std::int64_t n = A.rows();
  x.resize(n, 3);
  return BlockSums<9>(n, threads, nullptr, partition, [&](std::int64_t i, std::array<double, 9>& s) {
    for (int k = 0; k < 3; ++k)
    {
      x(i, k) = x0(i, k);
    }
    if (partition && !partition->ownedPoints[static_cast<size_t>(i)])
    {
      return;
    }
    double ax[3];
    MultiplyRow(A, i, [&](std::int64_t j, int k) { return x0(j, k); }, ax);
    for (int k = 0; k < 3; ++k)
    {
      v.r(i, k) = b(i, k) - ax[k];
      v.p(i, k) = diag[static_cast<size_t>(i)] * v.r(i, k);
      s[k] += v.r(i, k) * v.r(i, k);
      s[k + 3] += v.r(i, k) * v.p(i, k);
      // ||b|| over the fitted rows: an identity row (a point no triangle
      // constrains, e.g. an isolated point far away) only keeps its point.
      s[k + 6] += system.fitted[static_cast<size_t>(i)] ? b(i, k) * b(i, k) : 0.0;
    }
  });
}

/// The step of r: r -= step q; returns the sums of r.r and r.z (z = D^-1 r).
std::array<double, 6> StepResidual(const std::vector<double>& diag, const double step[3],
  int threads, const MeshPartition* partition, Vectors& v)
{
  return BlockSums<6>(v.r.rows(), threads, Owned(partition), partition,
    [&](std::int64_t i, std::array<double, 6>& s) {
      for (int k = 0; k < 3; ++k)
      {
        v.r(i, k) -= step[k] * v.q(i, k);
        s[k] += v.r(i, k) * v.r(i, k);
        s[k + 3] += v.r(i, k) * diag[static_cast<size_t>(i)] * v.r(i, k);
      }
    });
}

/// The last iteration's step of x (x += step p; the owned rows only, on a piece).
void LastStepOfX(
  const double step[3], int threads, const MeshPartition* partition, const Vectors& v, Coordinates& x)
{
  const std::int64_t n = x.rows();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3 && (!partition || partition->ownedPoints[static_cast<size_t>(i)]); ++k)
    {
      x(i, k) += step[k] * v.p(i, k);
    }
  }
}

/**
 * Jacobi-preconditioned conjugate gradients from x = start, the
 * three coordinates side by side: each pass over the matrix serves the three
 * columns and every vector operation is parallel. Two passes over the rows
 * per iteration: the step of x and the direction's update fused with the
 * product (and its sums), then the step of r (and its sums); on a piece, the
 * rows other pieces read are updated before the exchange that precedes the
 * product (PieceRows). A column stops when its
 * residual is below tolerance x ||b|| (tolerance 0 runs all the iterations);
 * returns the number of iterations done.
 */
int ConjugateGradients(const FitSystemData& system, const Coordinates& b, const Coordinates& start,
  int maxIterations, double tolerance, int threads, const MeshPartition* partition, Coordinates& x)
{
  const RowMatrix& A = system.matrix;
  const std::vector<double>& diag = system.inverseDiagonal;
  Vectors v = AllocateVectors(A.rows(), partition);
  const auto sums0 = StartingResidual(system, b, start, threads, partition, v, x);
  bool active[3];
  double threshold[3], rz[3];
  for (int k = 0; k < 3; ++k)
  {
    threshold[k] = tolerance > 0.0 ? std::max(tolerance * tolerance * sums0[k + 6], std::numeric_limits<double>::min())
                                   : std::numeric_limits<double>::min(); // all the iterations
    active[k] = sums0[k] >= threshold[k];
    rz[k] = sums0[k + 3];
  }
  const RowRanges ranges(A, threads);
  const PieceRows rows(partition);
  DirectionUpdate u;
  int iteration = 0;
  while (iteration < maxIterations && (active[0] || active[1] || active[2]))
  {
    // The first direction is z itself; later ones are z + ratio p, after x's step along p.
    const DirectionUpdate* update = iteration > 0 ? &u : nullptr;
    const auto pq = partition ? UpdateAndMultiplyPiece(A, diag, ranges, threads, partition, rows, update, v, x)
                              : UpdateAndMultiply(A, diag, ranges, update, nullptr, nullptr, v, x);
    for (int k = 0; k < 3; ++k)
    {
      // p.Ap > 0 unless p = 0, i.e. the column is solved exactly.
      active[k] = active[k] && pq[k] > 0.0;
      u.step[k] = active[k] ? rz[k] / pq[k] : 0.0;
    }
    // The step of r (x's step, x += step p, is in the next product's pass).
    const auto sums = StepResidual(diag, u.step, threads, partition, v);
    ++iteration;
    for (int k = 0; k < 3; ++k)
    {
      active[k] = active[k] && sums[k] >= threshold[k];
      u.ratio[k] = active[k] ? sums[k + 3] / rz[k] : 0.0;
      rz[k] = sums[k + 3];
    }
  }
  if (iteration > 0)
  {
    LastStepOfX(u.step, threads, partition, v, x);
  }
  return iteration;
}
} // namespace

Status Solve(const FitSystemData& system, const Coordinates& b, const FitParameters& parameters,
  int threads, Coordinates& x, FitReport& report, const Coordinates* start)
{
  report.iterations = 0;
  if (parameters.solver == FitSolver::Exact)
  {
    Eigen::SimplicialLDLT<RowMatrix, Eigen::Lower> ldlt(system.matrix);
    if (ldlt.info() != Eigen::Success)
    {
      return { "the sparse Cholesky factorisation failed" };
    }
    x = ldlt.solve(b);
    return {};
  }
  const bool fixed = parameters.solver == FitSolver::ConjugateGradient;
  report.iterations = ConjugateGradients(system, b, start ? *start : system.original,
    fixed ? parameters.iterations : parameters.maxIterations,
    fixed ? 0.0 : parameters.tolerance, threads, parameters.partition, x);
  if (parameters.partition)
  {
    parameters.partition->exchangePoints(x.data()); // halo points take their owners' result
  }
  return {};
}

double RelativeResidual(const FitSystemData& system, const Coordinates& b, const Coordinates& x,
  const MeshPartition* partition, int threads)
{
  const auto sums = BlockSums<6>(system.matrix.rows(), threads, Owned(partition), partition,
    [&](std::int64_t i, std::array<double, 6>& s) {
      double ax[3];
      MultiplyRow(system.matrix, i, [&](std::int64_t j, int k) { return x(j, k); }, ax);
      for (int k = 0; k < 3; ++k)
      {
        const double r = b(i, k) - ax[k];
        s[k] += r * r;
        s[k + 3] += system.fitted[static_cast<size_t>(i)] ? b(i, k) * b(i, k) : 0.0; // as the solver's ||b||
      }
    });
  double worst = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double rNorm = std::sqrt(sums[k]);
    const double bNorm = std::sqrt(sums[k + 3]);
    worst = std::max(worst, bNorm > 0.0 ? rNorm / bNorm : rNorm);
  }
  return worst;
}

} // namespace fit
} // namespace shock
