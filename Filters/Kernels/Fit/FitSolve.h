/**
 * @file FitSolve.h
 * @brief Internal to the screened Poisson fit: the assembled system
 * (FitSystemData) and its solvers (Jacobi-preconditioned conjugate gradients
 * on the three coordinates at once, sparse Cholesky).
 */
#ifndef ShockFitSolve_h
#define ShockFitSolve_h

#include "MeshPartition.h"
#include "FitParameters.h"
#include "FitSystem.h"
#include "TriangleMesh.h"
#include "ShockTypes.h"
#include "Vec3.h"

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace shock
{

namespace fit
{
/// Compressed rows: built row by row in parallel, and multiplied row by row.
using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
/// One column per coordinate (x, y, z); a row's three values are adjacent in memory.
using Coordinates = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Rows or triangles per block of the parallel sums; fixed so that the sums,
/// hence the results, do not depend on the number of threads.
constexpr std::int64_t SumBlock = 4096;

/**
 * Sums over the items 0..n-1, Count at once: term(i, sums) adds item i's terms
 * (and may update row i's values). Items are summed in fixed blocks, so the
 * result does not depend on the number of threads. Items with owned[i] == 0
 * are skipped (owned may be null); with a partition the sums are added over all pieces.
 */
template <int Count, typename Term>
std::array<double, Count> BlockSums(std::int64_t n, int threads, const std::vector<char>* owned,
  const MeshPartition* partition, Term term)
{
  const std::int64_t blocks = (n + SumBlock - 1) / SumBlock;
  std::vector<std::array<double, Count>> partial(static_cast<size_t>(blocks));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    std::array<double, Count> sums{};
    for (std::int64_t i = b * SumBlock; i < std::min(n, (b + 1) * SumBlock); ++i)
    {
      if (!owned || (*owned)[static_cast<size_t>(i)])
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

/// The normalisation x -> scale (x - center) that gives the mesh unit area.
struct Frame
{
  double center[3] = { 0.0, 0.0, 0.0 };
  double scale = 0.0; ///< 0 when the mesh has no area
};
} // namespace fit

/**
 * The assembled system of the normalised mesh (see FitSystem.h); row r is point
 * order[r]: breadth-first, so that the solver's products read nearby rows. The
 * assembly visits the points in the order the triangles first use them, so
 * that it reads the triangles' data nearly in order.
 */
struct FitSystemData
{
  fit::Frame frame;
  double alpha = 1.0; ///< A = alpha M + beta S, b = alpha M c0 + beta D w (scaled eps M + S)
  double beta = 1.0;
  fit::RowMatrix matrix;
  std::vector<double> inverseDiagonal;
  fit::Coordinates original; ///< normalised original positions: the initial guess
  fit::Coordinates massTerm; ///< alpha M c0; the original position on rows without triangles
  std::vector<std::int64_t> order; ///< point of each row
  std::vector<std::int64_t> rank;  ///< row of each point
  /// The points in the order the assembly visits them (each fills its own row).
  std::vector<std::int64_t> visit;
  std::vector<char> fitted;        ///< per row: its point is used by a non-degenerate triangle
  /// Per row, the diagonal entry without an anchor: empty until a fit anchors
  /// (AnchorUnturnedPoints), which writes base + its own anchor each time.
  std::vector<double> baseDiagonal;
  bool anchored = false; ///< the diagonal holds the last fit's anchor
};

namespace fit
{
/**
 * Add triangle f's term of the divergence of the target gradients at the
 * point whose hat gradient in f is gp: out_k += A_f gp . w_k (w: FitTargetGradients
 * of the valid target normal, else of the triangle's own normal).
 */
void AddTargetDivergence(const TriangleMesh& mesh, const double* normals, FitTarget target,
  std::int64_t f, const double gp[3], double out[3]);

/**
 * The cosine of the angle between triangle f's own normal and its target
 * normal (the valid one: 1 when the target is replaced by the own normal).
 */
double TargetTurnCosine(const TriangleMesh& mesh, const double* normals, std::int64_t f);

/**
 * Step 4 of ScreenedPoissonFit.h, the anchor of the points the sharpening did
 * not turn: for each row's point p, with theta_p the largest angle between a
 * non-degenerate triangle's own and target normals around p,
 * kappa_p = weight * A_pp * max(0, 1 - theta_p / angle) (A_pp the diagonal
 * without anchor) is added to the diagonal and kappa_p c0_p to b. Writes the
 * diagonal (and inverse diagonal) of every row: a weight of 0 restores the
 * unanchored system. Rows without a non-degenerate triangle are left alone.
 */
void AnchorUnturnedPoints(const TriangleMesh& mesh, const double* normals, double weight,
  double angle, FitSystemData& system, Coordinates& b, int threads);

/// The target gradients w (FitTargetGradients, 9 values) of triangle f for its target normal.
void TargetGradients(const TriangleMesh& mesh, const double* normals, FitTarget target,
  std::int64_t f, double w[9]);

/// out += A_f (gp . w_k) for k = 0, 1, 2: AddTargetDivergence with the gradients w at hand.
inline void AddDivergence(const TriangleMesh& mesh, std::int64_t f, const double gp[3],
  const double w[9], double out[3])
{
  for (int k = 0; k < 3; ++k)
  {
    out[k] += mesh.Area(f) * Dot(Load(gp), Load(w + 3 * k));
  }
}

/// The target normals whose divergence the assembly adds to the right-hand sides.
struct Targets
{
  const double* normals = nullptr;
  FitTarget target = FitTarget::CentralProjection;
};

/**
 * BuildFitSystem (FitSystem.h) that also fills the right-hand sides
 * b = alpha M c0 + beta s D w of `targets` in the same pass over the rows (b
 * is left empty for a mesh without area).
 */
Status BuildFitSystem(const TriangleMesh& mesh, double screeningWeight,
  const MeshPartition* partition, int threads, const Targets& targets, FitSystem& system,
  Coordinates& b, bool rowsInMeshOrder = false);

/**
 * Solve A x = b for the three coordinates with the chosen solver, from
 * x = start (system.original when null) for conjugate gradients. On a piece
 * (parameters.partition) only the owned rows are computed and the halo takes
 * its owners' values; start must hold the halo's values too. Fills report.iterations.
 */
Status Solve(const FitSystemData& system, const Coordinates& b, const FitParameters& parameters,
  int threads, Coordinates& x, FitReport& report, const Coordinates* start = nullptr);

/// Largest relative residual ||b - A x|| / ||b|| over the coordinates (absolute when b = 0).
double RelativeResidual(const FitSystemData& system, const Coordinates& b, const Coordinates& x,
  const MeshPartition* partition, int threads);
} // namespace fit

} // namespace shock

#endif
