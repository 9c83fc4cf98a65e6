#include "FitSolve.h"

#include <Eigen/SparseCholesky>

#include <cmath>
#include <limits>

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

/// q = A p and the sums p.q (on a piece, after the owners' p reached its halo).
std::array<double, 3> DirectionTimesA(
  const RowMatrix& A, int threads, const MeshPartition* partition, Vectors& v)
{
  if (partition)
  {
    partition->exchangePoints(v.p.data());
  }
  return BlockSums<3>(A.rows(), threads, Owned(partition), partition,
    [&](std::int64_t i, std::array<double, 3>& s) {
      double ap[3];
      MultiplyRow(A, i, [&](std::int64_t j, int k) { return v.p(j, k); }, ap);
      for (int k = 0; k < 3; ++k)
      {
        v.q(i, k) = ap[k];
        s[k] += v.p(i, k) * ap[k];
      }
    });
}

/**
 * Jacobi-preconditioned conjugate gradients from x (the original positions),
 * the three coordinates side by side: each pass over the matrix serves the
 * three columns and every vector operation is parallel. A column stops when its
 * residual is below tolerance x ||b|| (tolerance 0 runs all the iterations);
 * returns the number of iterations done.
 */
int ConjugateGradients(const FitSystemData& system, const Coordinates& b, int maxIterations,
  double tolerance, int threads, const MeshPartition* partition, Coordinates& x)
{
  const RowMatrix& A = system.matrix;
  const std::vector<double>& diag = system.inverseDiagonal;
  const std::int64_t n = A.rows();
  // Zero start: on a piece, rows it does not own are never computed.
  Vectors v;
  v.r = v.p = v.q = Coordinates::Zero(n, 3);
  // r = b - A x, p = z = D^-1 r; sums of r.r, r.z and b.b.
  const auto start = BlockSums<9>(n, threads, Owned(partition), partition, [&](std::int64_t i, std::array<double, 9>& s) {
    double ax[3];
    MultiplyRow(A, i, [&](std::int64_t j, int k) { return x(j, k); }, ax);
    for (int k = 0; k < 3; ++k)
    {
      v.r(i, k) = b(i, k) - ax[k];
      v.p(i, k) = diag[static_cast<size_t>(i)] * v.r(i, k);
      s[k] += v.r(i, k) * v.r(i, k);
      s[k + 3] += v.r(i, k) * v.p(i, k);
      s[k + 6] += b(i, k) * b(i, k);
    }
  });
  bool active[3];
  double threshold[3], rz[3];
  for (int k = 0; k < 3; ++k)
  {
    threshold[k] = std::max(tolerance * tolerance * start[k + 6], std::numeric_limits<double>::min());
    active[k] = start[k] >= threshold[k];
    rz[k] = start[k + 3];
  }
  int iteration = 0;
  while (iteration < maxIterations && (active[0] || active[1] || active[2]))
  {
    const auto pq = DirectionTimesA(A, threads, partition, v);
    double step[3];
    for (int k = 0; k < 3; ++k)
    {
      // p.Ap > 0 unless p = 0, i.e. the column is solved exactly.
      active[k] = active[k] && pq[k] > 0.0;
      step[k] = active[k] ? rz[k] / pq[k] : 0.0;
    }
    // x += step p, r -= step q; sums of r.r and r.z (z = D^-1 r).
    const auto sums = BlockSums<6>(n, threads, Owned(partition), partition, [&](std::int64_t i, std::array<double, 6>& s) {
      for (int k = 0; k < 3; ++k)
      {
        x(i, k) += step[k] * v.p(i, k);
        v.r(i, k) -= step[k] * v.q(i, k);
        s[k] += v.r(i, k) * v.r(i, k);
        s[k + 3] += v.r(i, k) * diag[static_cast<size_t>(i)] * v.r(i, k);
      }
    });
    ++iteration;
    double ratio[3];
    for (int k = 0; k < 3; ++k)
    {
      active[k] = active[k] && sums[k] >= threshold[k];
      ratio[k] = active[k] ? sums[k + 3] / rz[k] : 0.0;
      rz[k] = sums[k + 3];
    }
    // p = z + ratio p.
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t i = 0; i < n; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        v.p(i, k) = diag[static_cast<size_t>(i)] * v.r(i, k) + ratio[k] * v.p(i, k);
      }
    }
  }
  return iteration;
}
} // namespace

Status Solve(const FitSystemData& system, const Coordinates& b, const FitParameters& parameters,
  int threads, Coordinates& x, FitReport& report)
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
  x = system.original;
  report.iterations = ConjugateGradients(system, b,
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
        s[k + 3] += b(i, k) * b(i, k);
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
