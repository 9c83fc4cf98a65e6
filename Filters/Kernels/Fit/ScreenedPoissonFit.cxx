#include "ScreenedPoissonFit.h"

#include "FitSolve.h"
#include "Timer.h"
#include "Vec3.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace shock
{

namespace
{
using fit::Coordinates;

/// FitTarget::Shear and CentralProjection up to this tilt (cosine of 45 degrees: edges
/// stretched at most sqrt(2) and 2 times); more tilted triangles are rotated instead.
constexpr double MinShearCosine = 0.7071;
/// Target normals shorter than this are treated as missing.
constexpr double MinTargetLength = 1e-8;

/// Unit target normal of non-degenerate triangle f in n; false (n = the
/// triangle's own normal) when the target is not finite or too short.
bool TargetNormal(const TriangleMesh& mesh, const double* targets, std::int64_t f, double n[3])
{
  const Vec3 t = Load(targets + 3 * f);
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

/// Non-degenerate (owned) triangles whose target normal is invalid, over all pieces.
std::int64_t InvalidTargets(
  const TriangleMesh& mesh, const double* targets, const MeshPartition* partition, int threads)
{
  std::int64_t invalid = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : invalid)
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    double n[3];
    if (!mesh.Degenerate(f) && (!partition || partition->ownedTriangles[static_cast<size_t>(f)]) &&
      !TargetNormal(mesh, targets, f, n))
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
  return invalid;
}

/**
 * The right-hand sides b = alpha M c0 + beta D w, row by row in parallel: the
 * mass term of the system plus the divergence of the target gradients,
 * (D w)_p = sum_f A_f grad(phi_p) . w_k (normalised: s A g.w). The same sums
 * as the assembly's (FillRows), for a system kept from an earlier fit.
 */
Coordinates RightHandSides(const TriangleMesh& mesh, const double* targets, FitTarget target,
  const FitSystemData& system, int threads)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const CompressedLists& around = mesh.PointTriangles();
  const double weight = system.beta * system.frame.scale;
  Coordinates b(np, 3);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < np; ++i)
  {
    const std::int64_t p = system.visit[static_cast<size_t>(i)];
    const std::int64_t r = system.rank[static_cast<size_t>(p)];
    double divergence[3] = { 0.0, 0.0, 0.0 };
    for (std::int64_t a = around.Begin(p); a < around.End(p); ++a)
    {
      const std::int64_t f = around.items[static_cast<size_t>(a)];
      if (!mesh.Degenerate(f))
      {
        const std::int64_t* t = mesh.Corners(f);
        fit::AddTargetDivergence(mesh, targets, target, f,
          mesh.HatGradient(f, t[0] == p ? 0 : (t[1] == p ? 1 : 2)), divergence);
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      b(r, k) = system.massTerm(r, k) + weight * divergence[k];
    }
  }
  return b;
}

} // namespace

void fit::TargetGradients(const TriangleMesh& mesh, const double* normals, FitTarget target,
  std::int64_t f, double w[9])
{
  double n[3];
  TargetNormal(mesh, normals, f, n);
  FitTargetGradients(mesh, f, n, target, w);
}

double fit::TargetTurnCosine(const TriangleMesh& mesh, const double* normals, std::int64_t f)
{
  double n[3];
  if (!TargetNormal(mesh, normals, f, n))
  {
    return 1.0; // replaced by the own normal: not turned
  }
  return std::max(-1.0, std::min(1.0, Dot(Load(n), Load(mesh.Normal(f)))));
}

void fit::AnchorUnturnedPoints(const TriangleMesh& mesh, const double* normals, double weight,
  double angle, FitSystemData& system, Coordinates& b, int threads)
{
  const bool anchoring = weight > 0.0 && angle > 0.0;
  if (!anchoring && !system.anchored)
  {
    return; // the paper's system, as assembled
  }
  RowMatrix& A = system.matrix;
  const auto np = static_cast<std::int64_t>(system.order.size());
  if (system.baseDiagonal.empty())
  {
    system.baseDiagonal.resize(static_cast<size_t>(np));
  }
  const bool firstAnchor = !system.anchored;
  const CompressedLists& around = mesh.PointTriangles();
  const double degrees = 180.0 / 3.14159265358979323846;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t r = 0; r < np; ++r)
  {
    if (!system.fitted[static_cast<size_t>(r)])
    {
      continue; // an identity row: the point keeps its position anyway
    }
    // The row's diagonal entry (columns are sorted within a row).
    const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[r];
    const int* end = A.innerIndexPtr() + A.outerIndexPtr()[r + 1];
    const std::ptrdiff_t slot = std::lower_bound(begin, end, static_cast<int>(r)) - begin;
    double& diagonal = A.valuePtr()[A.outerIndexPtr()[r] + slot];
    double& base = system.baseDiagonal[static_cast<size_t>(r)];
    if (firstAnchor)
    {
      base = diagonal;
    }
    double kappa = 0.0;
    if (anchoring)
    {
      // The largest turn the fit asks of a triangle around the point.
      const std::int64_t p = system.order[static_cast<size_t>(r)];
      double leastCosine = 1.0;
      for (std::int64_t a = around.Begin(p); a < around.End(p); ++a)
      {
        const std::int64_t f = around.items[static_cast<size_t>(a)];
        if (!mesh.Degenerate(f))
        {
          leastCosine = std::min(leastCosine, TargetTurnCosine(mesh, normals, f));
        }
      }
      const double turn = std::acos(leastCosine) * degrees;
      kappa = weight * base * std::max(0.0, 1.0 - turn / angle);
    }
    diagonal = base + kappa;
    system.inverseDiagonal[static_cast<size_t>(r)] = 1.0 / diagonal;
    for (int k = 0; k < 3; ++k)
    {
      b(r, k) += kappa * system.original(r, k);
    }
  }
  system.anchored = anchoring;
}

void fit::AddTargetDivergence(const TriangleMesh& mesh, const double* normals, FitTarget target,
  std::int64_t f, const double gp[3], double out[3])
{
  double w[9];
  TargetGradients(mesh, normals, target, f, w);
  AddDivergence(mesh, f, gp, w, out);
}

namespace
{
/// Check the parameters (a message for the first invalid one).
Status CheckFitParameters(const TriangleMesh& mesh, const FitParameters& parameters)
{
  if (!(std::isfinite(parameters.screeningWeight) && parameters.screeningWeight > 0.0))
  {
    return { "the screening weight must be finite and > 0" };
  }
  if (!(std::isfinite(parameters.anchorWeight) && parameters.anchorWeight >= 0.0) ||
    !(parameters.anchorAngle >= 0.0 && parameters.anchorAngle <= 180.0))
  {
    return { "the anchor weight must be finite and >= 0, the anchor angle in [0, 180]" };
  }
  if (!(std::isfinite(parameters.driftRadius) && parameters.driftRadius >= 0.0))
  {
    return { "the drift radius must be finite and >= 0" };
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
      partition->ownedPoints.size() != static_cast<size_t>(mesh.NumberOfPoints()) ||
      partition->ownedTriangles.size() != static_cast<size_t>(mesh.NumberOfTriangles()) ||
      !partition->globalSum || !partition->exchangePoints))
  {
    return { parameters.solver == FitSolver::Exact
        ? "the exact solver cannot solve a mesh split into pieces: use conjugate gradients"
        : "incomplete mesh partition" };
  }
  return {};
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
  const double c = Dot(Load(n), Load(N));
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
    const double along = Dot(Load(W[k]), Load(n));
    for (int j = 0; j < 3; ++j)
    {
      gradients[3 * k + j] = W[k][j] - along * n[j];
    }
  }
}

namespace
{
/// Every point at its input position: what the fit leaves where it changes nothing.
void CopyInputPositions(const TriangleMesh& mesh, double* positions, int threads)
{
  const std::int64_t np = mesh.NumberOfPoints();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    std::copy(mesh.Point(p), mesh.Point(p) + 3, positions + 3 * p);
  }
}

/**
 * The system and its right-hand sides b: the cached system when it was built
 * for this mesh and eps (out.reusedSystem; then only b is assembled), else
 * a new one, which comes with b from the same pass (its data stays null for a
 * mesh without area).
 */
Status SystemAndRightHandSides(const TriangleMesh& mesh, const double* targetNormals,
  const FitParameters& parameters, int threads, FitSystem& system, Coordinates& b, FitReport& out)
{
  out.reusedSystem = system.Matches(mesh, parameters.screeningWeight, parameters.rowsInMeshOrder);
  if (out.reusedSystem)
  {
    b = RightHandSides(mesh, targetNormals, parameters.target, *system.data, threads);
    return {};
  }
  return fit::BuildFitSystem(mesh, parameters.screeningWeight, parameters.partition, threads,
    { targetNormals, parameters.target }, system, b, parameters.rowsInMeshOrder);
}

/**
 * The fitted positions: the rows' solutions x, normalisation undone; unconstrained
 * points keep their exact input position.
 */
void WriteFittedPositions(
  const FitSystemData& data, const Coordinates& x, double* positions, int threads)
{
  const auto np = static_cast<std::int64_t>(data.order.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t r = 0; r < np; ++r)
  {
    if (data.fitted[static_cast<size_t>(r)])
    {
      const std::int64_t p = data.order[static_cast<size_t>(r)];
      for (int k = 0; k < 3; ++k)
      {
        positions[3 * p + k] = data.frame.center[k] + x(r, k) / data.frame.scale;
      }
    }
  }
}

/**
 * The edge length of the normalised mesh (unit area): the side of an
 * equilateral triangle of its mean triangle area, over all pieces.
 */
double EdgeLengthOfUnitArea(const TriangleMesh& mesh, const MeshPartition* partition, int threads)
{
  const auto count = fit::BlockSums<1>(mesh.NumberOfTriangles(), threads,
    partition ? &partition->ownedTriangles : nullptr, partition,
    [&](std::int64_t f, std::array<double, 1>& s) { s[0] += mesh.Degenerate(f) ? 0.0 : 1.0; });
  return count[0] > 0.0 ? std::sqrt(4.0 / (std::sqrt(3.0) * count[0])) : 0.0;
}

/**
 * Step 5 of ScreenedPoissonFit.h, the drift's removal: with d = x - c0 the
 * fitted displacement (normalised rows of `fitted`), solves
 * (eps_d M + S) d_low = eps_d M_L d, eps_d = 1 / (driftRadius l)^2 (l: the edge
 * length of unit area, M_L the lumped mass), and returns x - d_low. The drift
 * system is kept in `system` beside the fit's. d_low of a constant d is d, so
 * the area-weighted mean (the lumped mass's) of the displacement becomes 0.
 */
Status RemoveDrift(const TriangleMesh& mesh, const FitParameters& parameters, int threads,
  FitSystem& system, Coordinates& x, FitReport& out)
{
  const MeshPartition* partition = parameters.partition;
  const double length = parameters.driftRadius * EdgeLengthOfUnitArea(mesh, partition, threads);
  if (!(length > 0.0))
  {
    return {};
  }
  const double weight = 1.0 / (length * length);
  if (!system.drift || system.driftWeight != weight)
  {
    FitSystem drift;
    Status status = BuildFitSystem(mesh, weight, partition, threads, drift, parameters.rowsInMeshOrder);
    if (!status.Ok() || !drift.data)
    {
      return status;
    }
    system.drift = drift.data;
    system.driftWeight = weight;
  }
  const FitSystemData& fitted = *system.data;
  const FitSystemData& drift = *system.drift;
  const auto rows = static_cast<std::int64_t>(drift.order.size());
  // d in the drift system's rows, and b = alpha M_L d: the rows of S sum to 0,
  // so a row of A = alpha M + beta S sums to alpha times its lumped mass.
  Coordinates d(rows, 3), b(rows, 3);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t r = 0; r < rows; ++r)
  {
    const auto f = fitted.rank[static_cast<size_t>(drift.order[static_cast<size_t>(r)])];
    double mass = 0.0;
    for (fit::RowMatrix::InnerIterator it(drift.matrix, r); it; ++it)
    {
      mass += it.value();
    }
    for (int k = 0; k < 3; ++k)
    {
      d(r, k) = drift.fitted[static_cast<size_t>(r)] ? x(f, k) - fitted.original(f, k) : 0.0;
      b(r, k) = mass * d(r, k);
    }
  }
  Coordinates low;
  FitReport report;
  Status status = fit::Solve(drift, b, parameters, threads, low, report, &d);
  out.driftIterations = report.iterations;
  if (!status.Ok())
  {
    return status;
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t r = 0; r < rows; ++r)
  {
    const auto f = fitted.rank[static_cast<size_t>(drift.order[static_cast<size_t>(r)])];
    for (int k = 0; k < 3; ++k)
    {
      x(f, k) -= drift.fitted[static_cast<size_t>(r)] ? low(r, k) : 0.0;
    }
  }
  return {};
}
} // namespace

Status FitPositionsToNormals(const TriangleMesh& mesh, const double* targetNormals,
  double* positions, const FitParameters& parameters, FitReport* report, FitSystem* cache)
{
  const std::int64_t np = mesh.NumberOfPoints();
  if ((np > 0 && !positions) || (mesh.NumberOfTriangles() > 0 && !targetNormals))
  {
    return { "null positions or target normals" };
  }
  const int threads = ThreadsForWork(parameters.numberOfThreads, np);
  CopyInputPositions(mesh, positions, threads);
  Status status = CheckFitParameters(mesh, parameters);
  if (!status.Ok())
  {
    return status;
  }
  const auto setupStart = Clock::now();
  FitReport local;
  FitReport& out = report ? *report : local;
  out = FitReport{};
  const MeshPartition* partition = parameters.partition;
  out.invalidTargets = InvalidTargets(mesh, targetNormals, partition, threads);

  // The matrix and mass term: the cached ones when they were built for this mesh and eps.
  FitSystem own;
  FitSystem& system = cache && !partition ? *cache : own;
  Coordinates b;
  status = SystemAndRightHandSides(mesh, targetNormals, parameters, threads, system, b, out);
  if (!status.Ok() || !system.data)
  {
    // No area, nothing to fit: every point keeps its position.
    out.converged = status.Ok();
    out.setupSeconds = SecondsSince(setupStart);
    return status;
  }
  fit::AnchorUnturnedPoints(
    mesh, targetNormals, parameters.anchorWeight, parameters.anchorAngle, *system.data, b, threads);
  const FitSystemData& data = *system.data;
  out.setupSeconds = SecondsSince(setupStart);

  const auto solveStart = Clock::now();
  Coordinates x;
  status = fit::Solve(data, b, parameters, threads, x, out);
  if (status.Ok())
  {
    out.residual = fit::RelativeResidual(data, b, x, partition, threads);
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
  if (parameters.driftRadius > 0.0)
  {
    const auto driftStart = Clock::now();
    status = RemoveDrift(mesh, parameters, threads, system, x, out);
    out.solveSeconds += SecondsSince(driftStart);
    if (!status.Ok() || !x.allFinite())
    {
      out.converged = false;
      return status.Ok() ? Status{ "the drift's removal produced non-finite positions" } : status;
    }
  }
  WriteFittedPositions(data, x, positions, threads);
  return {};
}

} // namespace shock
