#include "ScreenedPoissonFit.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace shock
{

namespace
{
/// Compressed rows: built row by row in parallel, and multiplied row by row.
using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
/// One column per coordinate (x, y, z); a point's three values are adjacent in memory.
using Coordinates = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Clock = std::chrono::steady_clock;

/// FitTarget::Shear and CentralProjection up to this tilt (cosine of 45 degrees: edges
/// stretched at most sqrt(2) and 2 times); more tilted triangles are rotated instead.
constexpr double MinShearCosine = 0.7071;
/// Target normals shorter than this are treated as missing.
constexpr double MinTargetLength = 1e-8;
/// Triangles or rows per block of the parallel sums; fixed so that the sums,
/// hence the results, do not depend on the number of threads.
constexpr std::int64_t SumBlock = 4096;
/// Fewer points per thread run on fewer threads: the conjugate gradients open
/// four parallel regions per iteration, and on small meshes their synchronisation
/// costs more than the work (much more when the cores are shared).
constexpr std::int64_t MinPointsPerThread = 16384;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Unit target normal of non-degenerate triangle f in n; false (n = the
/// triangle's own normal) when the target is not finite or too short.
bool TargetNormal(const TriangleMesh& mesh, const double* targets, std::int64_t f, double n[3])
{
  const double* t = targets + 3 * f;
  const double length = std::sqrt(Dot(t, t));
  if (std::isfinite(length) && length > MinTargetLength)
  {
    for (int k = 0; k < 3; ++k)
    {
      n[k] = t[k] / length;
    }
    return true;
  }
  const double* own = mesh.Normal(f);
  std::copy(own, own + 3, n);
  return false;
}

/// The normalisation x -> scale (x - center) that gives the mesh unit area.
struct Frame
{
  double center[3] = { 0.0, 0.0, 0.0 };
  double scale = 0.0; ///< 0 when the mesh has no area
};

Frame UnitAreaFrame(const TriangleMesh& mesh, const MeshPartition* partition, int threads)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  const std::int64_t blocks = (nt + SumBlock - 1) / SumBlock;
  std::vector<double> partial(static_cast<size_t>(4 * blocks), 0.0);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    double* sum = &partial[static_cast<size_t>(4 * b)];
    for (std::int64_t f = b * SumBlock; f < std::min(nt, (b + 1) * SumBlock); ++f)
    {
      if (partition && !partition->ownedTriangles[static_cast<size_t>(f)])
      {
        continue; // a ghost triangle: its owner adds it
      }
      const double a = mesh.Area(f); // 0 for degenerate triangles
      const double* c = mesh.Centroid(f);
      sum[0] += a;
      for (int k = 0; k < 3; ++k)
      {
        sum[k + 1] += a * c[k];
      }
    }
  }
  double total[4] = { 0.0, 0.0, 0.0, 0.0 };
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    for (int k = 0; k < 4; ++k)
    {
      total[k] += partial[static_cast<size_t>(4 * b + k)];
    }
  }
  if (partition)
  {
    partition->globalSum(total, 4);
  }
  Frame frame;
  if (total[0] > 0.0)
  {
    frame.scale = 1.0 / std::sqrt(total[0]);
    for (int k = 0; k < 3; ++k)
    {
      frame.center[k] = total[k + 1] / total[0];
    }
  }
  return frame;
}

/// The screened Poisson system of the normalised mesh, one right-hand side per coordinate.
struct System
{
  RowMatrix matrix;
  Coordinates rhs;
  Coordinates original;     ///< normalised original positions: the initial guess
  std::vector<char> fitted; ///< per point: used by a non-degenerate triangle
};

Status Assemble(const TriangleMesh& mesh, const double* targets, FitTarget target,
  const Frame& frame, double screening, int threads, System& system)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const CompressedLists& ring = mesh.OneRing();
  const CompressedLists& around = mesh.PointTriangles();
  const std::int64_t nnz = np + static_cast<std::int64_t>(ring.items.size());
  if (nnz > std::numeric_limits<int>::max())
  {
    return { "mesh too large for the sparse solver's 32-bit indices" };
  }
  // A = alpha M + beta S and b = alpha M c0 + beta D w have the solution of
  // (eps M + S) c = eps M c0 + D w; dividing by max(1, eps) keeps every entry
  // bounded, so any finite eps > 0 is safe from overflow.
  const double alpha = std::min(screening, 1.0);
  const double beta = 1.0 / std::max(screening, 1.0);
  // Normalised areas are s^2 A; hat gradients g/s; coordinate gradients v are
  // scale invariant: stiffness A g.g, mass s^2 A/12, divergence s A g.w.
  const double s = frame.scale;

  system.original.resize(np, 3);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    const double* x = mesh.Point(p);
    for (int k = 0; k < 3; ++k)
    {
      system.original(p, k) = s * (x[k] - frame.center[k]);
    }
  }

  // The CSR pattern is each point's one-ring plus itself, so row p starts at
  // p + ring.Begin(p): built in parallel straight from the mesh's adjacency.
  RowMatrix& A = system.matrix;
  A.resize(static_cast<Eigen::Index>(np), static_cast<Eigen::Index>(np));
  A.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* values = A.valuePtr();
  system.rhs.resize(np, 3);
  system.fitted.assign(static_cast<size_t>(np), 0);

#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
  for (std::int64_t p = 0; p < np; ++p)
  {
    const std::int64_t begin = p + ring.Begin(p);
    const std::int64_t end = p + 1 + ring.End(p);
    outer[p] = static_cast<int>(begin);
    int* cols = inner + begin;
    const auto* ringBegin = ring.items.data() + ring.Begin(p);
    const auto* ringEnd = ring.items.data() + ring.End(p);
    const auto* split = std::lower_bound(ringBegin, ringEnd, p);
    int* out = std::copy(ringBegin, split, cols);
    *out++ = static_cast<int>(p);
    std::copy(split, ringEnd, out);
    double* row = values + begin;
    std::fill(row, row + (end - begin), 0.0);
    auto entry = [&](std::int64_t column) -> double& {
      return row[std::lower_bound(cols, cols + (end - begin), static_cast<int>(column)) - cols];
    };

    double b[3] = { 0.0, 0.0, 0.0 };
    bool fitted = false;
    for (std::int64_t a = around.Begin(p); a < around.End(p); ++a)
    {
      const std::int64_t f = around.items[static_cast<size_t>(a)];
      if (mesh.Degenerate(f))
      {
        continue;
      }
      fitted = true;
      const std::int64_t* t = mesh.Corners(f);
      const int self = t[0] == p ? 0 : (t[1] == p ? 1 : 2);
      const double area = mesh.Area(f);
      const double mass = alpha * s * s * area / 12.0;
      const double* gp = mesh.HatGradient(f, self);
      double gg[3]; // grad(phi_p) . grad(phi_c)
      for (int c = 0; c < 3; ++c)
      {
        gg[c] = Dot(gp, mesh.HatGradient(f, c));
        entry(t[c]) += (c == self ? 2.0 : 1.0) * mass + beta * area * gg[c];
      }

      // The target gradients w_k enter through (D w)_p = sum_f A_f grad(phi_p) . w_k.
      double n[3], w[9];
      TargetNormal(mesh, targets, f, n);
      FitTargetGradients(mesh, f, n, target, w);
      for (int k = 0; k < 3; ++k)
      {
        double massSum = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          massSum += (c == self ? 2.0 : 1.0) * system.original(t[c], k);
        }
        b[k] += mass * massSum + beta * s * area * Dot(gp, w + 3 * k);
      }
    }
    if (!fitted)
    {
      // Nothing constrains the point: an identity row keeps it where it is.
      entry(p) = 1.0;
      for (int k = 0; k < 3; ++k)
      {
        b[k] = system.original(p, k);
      }
    }
    system.fitted[static_cast<size_t>(p)] = fitted ? 1 : 0;
    for (int k = 0; k < 3; ++k)
    {
      system.rhs(p, k) = b[k];
    }
  }
  outer[np] = static_cast<int>(nnz);
  return {};
}

/**
 * Count sums over the rows 0..n-1 at once: term(i, sums) adds row i's terms (and
 * may update row i's values). The rows are summed in fixed blocks, so the result
 * does not depend on the number of threads. On a piece (partition), only the
 * owned rows are visited and the sums are added over all pieces.
 */
template <int Count, typename Term>
std::array<double, Count> RowSums(
  std::int64_t n, int threads, const MeshPartition* partition, Term term)
{
  const std::int64_t blocks = (n + SumBlock - 1) / SumBlock;
  std::vector<std::array<double, Count>> partial(static_cast<size_t>(blocks));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    std::array<double, Count> sums{};
    for (std::int64_t i = b * SumBlock; i < std::min(n, (b + 1) * SumBlock); ++i)
    {
      if (!partition || partition->ownedPoints[static_cast<size_t>(i)])
      {
        term(i, sums);
      }
    }
    partial[static_cast<size_t>(b)] = sums;
  }
  std::array<double, Count> total{};
  for (const auto& sums : partial)
  {
    for (int k = 0; k < Count; ++k)
    {
      total[k] += sums[k];
    }
  }
  if (partition)
  {
    partition->globalSum(total.data(), Count);
  }
  return total;
}

/// Row i of A y, for the three columns.
inline void MultiplyRow(const RowMatrix& A, const Coordinates& y, std::int64_t i, double out[3])
{
  out[0] = out[1] = out[2] = 0.0;
  const int* inner = A.innerIndexPtr();
  const double* values = A.valuePtr();
  for (int e = A.outerIndexPtr()[i]; e < A.outerIndexPtr()[i + 1]; ++e)
  {
    const double* yj = y.data() + 3 * static_cast<std::int64_t>(inner[e]);
    out[0] += values[e] * yj[0];
    out[1] += values[e] * yj[1];
    out[2] += values[e] * yj[2];
  }
}

/**
 * Jacobi-preconditioned conjugate gradients from x (the original positions),
 * the three coordinates side by side: each pass over the matrix serves the
 * three columns and every vector operation is parallel. A column stops when its
 * residual is below tolerance x ||b|| (tolerance 0 runs all the iterations);
 * returns the number of iterations done.
 */
int ConjugateGradients(const System& system, int maxIterations, double tolerance, int threads,
  const MeshPartition* partition, Coordinates& x)
{
  const RowMatrix& A = system.matrix;
  const Coordinates& b = system.rhs;
  const std::int64_t n = A.rows();
  std::vector<double> inverseDiagonal(static_cast<size_t>(n));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
  {
    inverseDiagonal[static_cast<size_t>(i)] = 1.0 / A.coeff(i, i); // > 0: see Assemble
  }
  // Zero start: on a piece, rows it does not own are never computed.
  Coordinates r = Coordinates::Zero(n, 3), p = Coordinates::Zero(n, 3), q = Coordinates::Zero(n, 3);
  // r = b - A x, p = z = D^-1 r; sums of r.r, r.z and b.b.
  const auto start = RowSums<9>(n, threads, partition, [&](std::int64_t i, std::array<double, 9>& sums) {
    double ax[3];
    MultiplyRow(A, x, i, ax);
    for (int k = 0; k < 3; ++k)
    {
      r(i, k) = b(i, k) - ax[k];
      p(i, k) = inverseDiagonal[static_cast<size_t>(i)] * r(i, k);
      sums[k] += r(i, k) * r(i, k);
      sums[k + 3] += r(i, k) * p(i, k);
      sums[k + 6] += b(i, k) * b(i, k);
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
    if (partition)
    {
      partition->exchangePoints(p.data()); // the owners' p on the halo of the owned rows
    }
    // q = A p and p.q.
    const auto pq = RowSums<3>(n, threads, partition, [&](std::int64_t i, std::array<double, 3>& sums) {
      double ap[3];
      MultiplyRow(A, p, i, ap);
      for (int k = 0; k < 3; ++k)
      {
        q(i, k) = ap[k];
        sums[k] += p(i, k) * ap[k];
      }
    });
    double step[3];
    for (int k = 0; k < 3; ++k)
    {
      // p.Ap > 0 unless p = 0, i.e. the column is solved exactly.
      active[k] = active[k] && pq[k] > 0.0;
      step[k] = active[k] ? rz[k] / pq[k] : 0.0;
    }
    // x += step p, r -= step q; sums of r.r and r.z (z = D^-1 r).
    const auto sums = RowSums<6>(n, threads, partition, [&](std::int64_t i, std::array<double, 6>& s) {
      for (int k = 0; k < 3; ++k)
      {
        x(i, k) += step[k] * p(i, k);
        r(i, k) -= step[k] * q(i, k);
        s[k] += r(i, k) * r(i, k);
        s[k + 3] += r(i, k) * inverseDiagonal[static_cast<size_t>(i)] * r(i, k);
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
        p(i, k) = inverseDiagonal[static_cast<size_t>(i)] * r(i, k) + ratio[k] * p(i, k);
      }
    }
  }
  return iteration;
}

/// Solve A x = b for the three coordinates; fills the iteration count.
Status Solve(const System& system, const FitParameters& parameters, int threads, Coordinates& x,
  FitReport& report)
{
  report.iterations = 0;
  if (parameters.solver == FitSolver::Exact)
  {
    Eigen::SimplicialLDLT<RowMatrix, Eigen::Lower> ldlt(system.matrix);
    if (ldlt.info() != Eigen::Success)
    {
      return { "the sparse Cholesky factorisation failed" };
    }
    x = ldlt.solve(system.rhs);
    return {};
  }
  const bool fixed = parameters.solver == FitSolver::ConjugateGradient;
  x = system.original;
  report.iterations = ConjugateGradients(system,
    fixed ? parameters.iterations : parameters.maxIterations,
    fixed ? 0.0 : parameters.tolerance, threads, parameters.partition, x);
  if (parameters.partition)
  {
    parameters.partition->exchangePoints(x.data()); // halo points take their owners' result
  }
  return {};
}

/// Largest relative residual ||b - A x|| / ||b|| over the coordinates (absolute when b = 0).
double RelativeResidual(
  const System& system, const Coordinates& x, const MeshPartition* partition, int threads)
{
  const auto sums = RowSums<6>(
    system.matrix.rows(), threads, partition, [&](std::int64_t i, std::array<double, 6>& s) {
      double ax[3];
      MultiplyRow(system.matrix, x, i, ax);
      for (int k = 0; k < 3; ++k)
      {
        const double r = system.rhs(i, k) - ax[k];
        s[k] += r * r;
        s[k + 3] += system.rhs(i, k) * system.rhs(i, k);
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
} // namespace

void FitTargetGradients(const TriangleMesh& mesh, std::int64_t f, const double normal[3],
  FitTarget target, double gradients[9])
{
  std::fill(gradients, gradients + 9, 0.0);
  if (mesh.Degenerate(f))
  {
    return;
  }
  // W maps each edge e (a tangent vector) to its target W e; its rows are the
  // target gradients, w_k = P W^T e_k with P = I - n n^T the projector onto the plane.
  const double* n = mesh.Normal(f);
  const double* N = normal;
  double W[3][3];
  const double c = Dot(n, N);
  const bool sheared = target == FitTarget::Shear || target == FitTarget::CentralProjection;
  if (sheared && c >= MinShearCosine)
  {
    // Shear: e -> e - n <N, e> / <N, n>, along n onto the target plane (the footprint in
    // the own plane is kept). The central projection from the centre of curvature
    // stretches that by 1 / <N, n> more.
    const double scale = target == FitTarget::CentralProjection ? 1.0 / c : 1.0;
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        W[i][j] = scale * ((i == j ? 1.0 : 0.0) - n[i] * N[j] / c);
      }
    }
  }
  else if (target != FitTarget::Projection && c > -1.0 + 1e-12)
  {
    // Rotation (and Shear beyond its tilt limit). Rodrigues: R = c I + [a]x + a a^T / (1 + c),
    // a = n x N, the smallest rotation taking n to N.
    const double a[3] = { n[1] * N[2] - n[2] * N[1], n[2] * N[0] - n[0] * N[2],
      n[0] * N[1] - n[1] * N[0] };
    const double cross[3][3] = { { 0.0, -a[2], a[1] }, { a[2], 0.0, -a[0] }, { -a[1], a[0], 0.0 } };
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        W[i][j] = (i == j ? c : 0.0) + cross[i][j] + a[i] * a[j] / (1.0 + c);
      }
    }
  }
  else if (target == FitTarget::Projection)
  {
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        W[i][j] = (i == j ? 1.0 : 0.0) - N[i] * N[j];
      }
    }
  }
  else
  {
    // N = -n: no smallest rotation; the triangle keeps its own gradients.
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        W[i][j] = i == j ? 1.0 : 0.0;
      }
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    const double along = Dot(W[k], n);
    for (int j = 0; j < 3; ++j)
    {
      gradients[3 * k + j] = W[k][j] - along * n[j];
    }
  }
}

Status FitPositionsToNormals(const TriangleMesh& mesh, const double* targetNormals,
  double* positions, const FitParameters& parameters, FitReport* report)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const std::int64_t nt = mesh.NumberOfTriangles();
  if ((np > 0 && !positions) || (nt > 0 && !targetNormals))
  {
    return { "null positions or target normals" };
  }
  const int threads = static_cast<int>(std::clamp<std::int64_t>(
    np / MinPointsPerThread, 1, ResolveThreadCount(parameters.numberOfThreads)));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    std::copy(mesh.Point(p), mesh.Point(p) + 3, positions + 3 * p);
  }
  if (!(std::isfinite(parameters.screeningWeight) && parameters.screeningWeight > 0.0))
  {
    return { "the screening weight must be finite and > 0" };
  }
  if (parameters.target != FitTarget::Projection && parameters.target != FitTarget::Rotation &&
    parameters.target != FitTarget::Shear && parameters.target != FitTarget::CentralProjection)
  {
    return { "unknown fit target" };
  }
  if (parameters.solver != FitSolver::ConjugateGradient &&
    parameters.solver != FitSolver::ConjugateGradientTolerance &&
    parameters.solver != FitSolver::Exact)
  {
    return { "unknown solver" };
  }
  if (parameters.iterations < 0 || parameters.maxIterations < 0 ||
    !(parameters.tolerance >= 0.0 && std::isfinite(parameters.tolerance)))
  {
    return { "iteration counts and tolerance must be >= 0 (tolerance finite)" };
  }
  const MeshPartition* partition = parameters.partition;
  if (partition &&
    (parameters.solver == FitSolver::Exact ||
      partition->ownedPoints.size() != static_cast<size_t>(np) ||
      partition->ownedTriangles.size() != static_cast<size_t>(nt) || !partition->globalSum ||
      !partition->exchangePoints))
  {
    return { parameters.solver == FitSolver::Exact
        ? "the exact solver cannot solve a mesh split into pieces: use conjugate gradients"
        : "incomplete mesh partition" };
  }

  const auto setupStart = Clock::now();
  FitReport local;
  FitReport& out = report ? *report : local;
  out = FitReport{};

  std::int64_t invalid = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : invalid)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    double n[3];
    if (!mesh.Degenerate(f) && (!partition || partition->ownedTriangles[static_cast<size_t>(f)]) &&
      !TargetNormal(mesh, targetNormals, f, n))
    {
      ++invalid;
    }
  }
  if (partition)
  {
    double count = static_cast<double>(invalid);
    partition->globalSum(&count, 1);
    invalid = static_cast<std::int64_t>(count);
  }
  out.invalidTargets = invalid;

  const Frame frame = UnitAreaFrame(mesh, partition, threads);
  if (frame.scale == 0.0)
  {
    // No area, nothing to fit: every point keeps its position.
    out.converged = true;
    out.setupSeconds = SecondsSince(setupStart);
    return {};
  }
  System system;
  Status status =
    Assemble(mesh, targetNormals, parameters.target, frame, parameters.screeningWeight, threads, system);
  out.setupSeconds = SecondsSince(setupStart);
  if (!status.Ok())
  {
    return status;
  }

  const auto solveStart = Clock::now();
  Coordinates x;
  status = Solve(system, parameters, threads, x, out);
  if (status.Ok())
  {
    out.residual = RelativeResidual(system, x, parameters.partition, threads);
    out.converged = out.residual <= parameters.tolerance;
  }
  out.solveSeconds = SecondsSince(solveStart);
  if (!status.Ok())
  {
    return status;
  }
  if (!x.allFinite())
  {
    out.converged = false;
    return { "the solve produced non-finite positions" };
  }

  // Undo the normalisation; unconstrained points keep their exact input position.
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    if (system.fitted[static_cast<size_t>(p)])
    {
      for (int k = 0; k < 3; ++k)
      {
        positions[3 * p + k] = frame.center[k] + x(p, k) / frame.scale;
      }
    }
  }
  return {};
}

namespace
{
/// Entries `value(f, i, j)` for every non-degenerate triangle f and corner pair (i, j).
template <typename Value>
std::vector<SparseEntry> TriangleEntries(const TriangleMesh& mesh, Value value)
{
  std::vector<SparseEntry> entries;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    if (mesh.Degenerate(f))
    {
      continue;
    }
    const std::int64_t* t = mesh.Corners(f);
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        entries.push_back({ t[i], t[j], value(f, i, j) });
      }
    }
  }
  return entries;
}
} // namespace

std::vector<SparseEntry> MassMatrix(const TriangleMesh& mesh)
{
  return TriangleEntries(mesh, [&](std::int64_t f, int i, int j) {
    return (i == j ? 2.0 : 1.0) * mesh.Area(f) / 12.0;
  });
}

std::vector<SparseEntry> StiffnessMatrix(const TriangleMesh& mesh)
{
  return TriangleEntries(mesh, [&](std::int64_t f, int i, int j) {
    return mesh.Area(f) * Dot(mesh.HatGradient(f, i), mesh.HatGradient(f, j));
  });
}

std::vector<double> Divergence(const TriangleMesh& mesh, const double* gradients)
{
  std::vector<double> divergence(static_cast<size_t>(3 * mesh.NumberOfPoints()), 0.0);
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    if (mesh.Degenerate(f))
    {
      continue;
    }
    const std::int64_t* t = mesh.Corners(f);
    for (int i = 0; i < 3; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        divergence[static_cast<size_t>(3 * t[i] + k)] +=
          mesh.Area(f) * Dot(mesh.HatGradient(f, i), gradients + 9 * f + 3 * k);
      }
    }
  }
  return divergence;
}

} // namespace shock
