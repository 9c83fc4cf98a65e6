/**
 * @file FitParameters.h
 * @brief The parameters and report of the screened Poisson fit (ScreenedPoissonFit.h),
 * shared by its assembly (FitSystem.h) and its solvers (FitSolve.h).
 */
#ifndef FitParameters_h
#define FitParameters_h

#include <cstdint>

namespace shock
{

struct MeshPartition;

/**
 * How the screened Poisson system is solved. The conjugate gradients iterate the
 * three coordinates together, so that each pass over the matrix serves all three.
 */
enum class FitSolver : int
{
  /// The paper's solver: a fixed number of Jacobi-preconditioned conjugate-gradient
  /// iterations started from the original positions (FitParameters::iterations).
  ConjugateGradient = 0,
  /// Jacobi-preconditioned conjugate gradients started from the original positions,
  /// until the relative residual is below FitParameters::tolerance
  /// (at most FitParameters::maxIterations iterations).
  ConjugateGradientTolerance = 1,
  /// Sparse Cholesky (LDL^T) factorisation: the exact solution up to rounding.
  Exact = 2
};

/// What each triangle's edges are asked to become in the fit (see the file comment).
enum class FitTarget : int
{
  Projection = 0, ///< projected onto the target plane: the paper's w = v - N <N, v>
  Rotation = 1,    ///< rotated onto the target plane: lengths kept
  Shear = 2,       ///< moved along the own normal onto the target plane: footprint kept
  CentralProjection = 3 ///< centrally projected from the centre of curvature (the default)
};

/// Parameters of FitPositionsToNormals.
struct FitParameters
{
  /// The target gradients; FitTarget::Projection reproduces the paper.
  FitTarget target = FitTarget::CentralProjection;
  /// Screening weight eps (> 0, finite), for the mesh normalised to unit area
  /// (eps / total area in the mesh's own units). Larger values keep the positions
  /// closer to the original ones; the paper uses 1.
  double screeningWeight = 1.0;
  /**
   * Not the paper's: the anchor of the points the sharpening did not turn
   * (ScreenedPoissonFit.h, step 4). A point whose triangles' target normals all
   * lie within anchorAngle degrees of their own normals is held at its
   * original position by anchorWeight times its row's diagonal, fading to
   * nothing at anchorAngle. 0 (either) is the paper's fit: the screening
   * weight alone anchors the surface. anchorWeight >= 0 and finite,
   * anchorAngle in [0, 180].
   */
  double anchorWeight = 1.0;
  double anchorAngle = 5.0;
  /**
   * Not the paper's: the drift removed after the fit (ScreenedPoissonFit.h,
   * step 5), in edge lengths (the side of an equilateral triangle of the
   * mesh's mean triangle area). The part of the displacement smoother than
   * this radius (its heat diffusion over driftRadius^2 squared edge lengths)
   * is taken away, so that the sharpening keeps the surface's local mean
   * position. 0 is the paper's fit; the default 8 is the filter's
   * (docs/sharpening.md, "Keeping the local mean: DriftRadius"). Finite and >= 0.
   */
  double driftRadius = 8.0;
  FitSolver solver = FitSolver::ConjugateGradient;
  /// Iterations of FitSolver::ConjugateGradient (>= 0; the paper uses 25).
  int iterations = 25;
  /// Relative residual ||b - A x|| / ||b|| to reach with FitSolver::ConjugateGradientTolerance
  /// (>= 0); for every solver, FitReport::converged says whether the result meets it.
  double tolerance = 1e-6;
  /// Iteration cap of FitSolver::ConjugateGradientTolerance (>= 0).
  int maxIterations = 1000;
  /// OpenMP threads for assembly and the conjugate gradients; 0 uses all cores.
  /// Small meshes use fewer threads (ThreadsForWork of the points). The result
  /// does not depend on the number of threads (the parallel sums are ordered).
  int numberOfThreads = 0;
  /// When set, the mesh is one piece of a distributed mesh: normalisation, sums and
  /// the conjugate gradients run over all pieces (same preconditioner and iterations
  /// as serial; the result equals the serial one up to summation order). Only the
  /// owned points' positions are fitted; the others (ghosts) are set from their owners
  /// where the piece needs them. Not for FitSolver::Exact.
  const MeshPartition* partition = nullptr;
  /**
   * Whether the mesh's numbering already keeps neighbours near in memory (a mesh
   * renumbered by LocalityNumbering, as the surface filters do): the system's
   * rows then follow the points' numbering instead of a breadth-first
   * renumbering of their own (FitSystem.h). The solution is the same up to the
   * rounding of sums taken in another order.
   */
  bool rowsInMeshOrder = false;
};

/// What a fit did. The residual is that of the normalised system (unit area).
struct FitReport
{
  /// Conjugate-gradient iterations done (the three coordinates are iterated together;
  /// one that reaches the tolerance stops changing); 0 for Exact.
  int iterations = 0;
  /// Final relative residual ||b - A x|| / ||b||, the largest over the three coordinates
  /// (a coordinate with b = 0 counts with its absolute residual ||A x||).
  double residual = 0.0;
  /// Whether residual <= FitParameters::tolerance.
  bool converged = false;
  /// Normalisation and assembly of the matrix (unless reused) and of the right-hand sides.
  double setupSeconds = 0.0;
  /// The matrix and mass term came from the FitSystem given (built for an earlier fit).
  bool reusedSystem = false;
  double solveSeconds = 0.0; ///< solve (factorisation for Exact) and the residual check
  /// Conjugate-gradient iterations of the drift's removal (step 5; 0 when not removed or Exact).
  int driftIterations = 0;
  /// Non-degenerate triangles whose target normal was invalid (replaced by their own normal).
  std::int64_t invalidTargets = 0;
};

} // namespace shock

#endif
