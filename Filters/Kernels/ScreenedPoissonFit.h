/**
 * @file ScreenedPoissonFit.h
 * @brief Fit mesh positions to target per-triangle normals (screened Poisson equation).
 *
 * The last step of geometry sharpening in Prada and Kazhdan (2015), section 4.1,
 * after Yu et al. (2004). With c0 the original coordinate functions (x, y and z,
 * each piecewise linear over the mesh) and N the target unit normal of each
 * triangle:
 *
 *  1. v = grad c0 on each triangle: the gradients v_x, v_y, v_z of the three
 *     coordinates (vectors in the triangle's plane), i.e. the 3x3 Jacobian of
 *     the position;
 *  2. the target gradients w (FitTargetGradients), chosen by FitParameters::target:
 *     - FitTarget::Projection, the paper's w = v - N <N, v>, i.e.
 *       w_k = v_k - N_k (N_x v_x + N_y v_y + N_z v_z): the component along N is
 *       removed from the position's values, so that each edge e is asked to
 *       become its projection e - <e, N> N onto the target plane (whose normal
 *       is N). Removing <v_k, N> N from each v_k separately would only shrink the
 *       triangles within their own planes (a flat mesh could never bend), so the
 *       paper's <v, N> is read as this contraction. A projection shortens every
 *       edge that is not parallel to the target plane: a rounded crease
 *       sharpens to its chord and the shape shrinks;
 *     - FitTarget::Rotation: each edge e is asked to become R e, with R the
 *       smallest rotation taking the triangle's own normal n to N (about the
 *       axis n x N). The target has the normal N, like the projection, but
 *       every edge keeps its length. When N = -n the rotation is not defined
 *       and the triangle keeps its gradients (w = v);
 *     - FitTarget::Shear: each edge e is moved along the triangle's own normal
 *       n onto the target plane, e - n <N, e> / <N, n>: its component in the
 *       triangle's plane (its footprint) is kept and only its height changes,
 *       so an edge lengthens by up to 1 / cos of the tilt between n and N;
 *     - FitTarget::CentralProjection (the default): the shear divided by
 *       <N, n>, which is the differential of the central projection onto the
 *       target plane from the centre of curvature. A crease rounded with a
 *       constant radius (the offset of a sharp crease, a Minkowski rounding)
 *       is mapped exactly onto the two planes of the sharp crease: each half
 *       of a rounded right angle of radius r becomes a leg of length r, where
 *       a projection gives 0.71 r, a rotation 0.79 r and the shear 0.88 r, so
 *       those shrink the shape as they sharpen it (docs/sharpening.md).
 *     Shear and CentralProjection rotate triangles tilted by more than 45
 *     degrees (whose edges would stretch more than sqrt(2) or 2 times);
 *  3. c1 = argmin_c  eps ||c - c0||^2_M + ||grad c - w||^2, i.e.
 *         (eps M + S) c1 = eps M c0 + D w,
 *     with M the consistent finite-element mass matrix (A/12 [2 1 1; 1 2 1; 1 1 2]
 *     per triangle), S the cotangent stiffness matrix
 *     (S_ij = sum_f A_f grad(phi_i) . grad(phi_j)) and (D w)_i = sum_f A_f grad(phi_i) . w_f.
 *
 * Scale and position: before assembling, the mesh is translated so that its
 * area-weighted centroid is at the origin and scaled uniformly so that its total
 * (non-degenerate) surface area is 1; the system is solved there and the result
 * mapped back. The screening weight eps therefore means the same on any mesh, and
 * the fit of a translated or uniformly scaled mesh is the translated or scaled fit.
 *
 * Boundaries: boundary vertices are unknowns like the others. The energy is
 * integrated over the mesh only, which gives natural (Neumann) boundary conditions:
 * nothing is pinned, the screening term alone anchors the surface.
 *
 * Conventions on meshes as users have them:
 *  - degenerate triangles (see TriangleMesh) contribute nothing;
 *  - points used by no non-degenerate triangle keep their position exactly;
 *  - a target normal that is not finite or has length <= 1e-8 is replaced by
 *    the triangle's own normal (its gradients are kept as they are) and counted;
 *    other targets are normalised to unit length.
 */
#ifndef ScreenedPoissonFit_h
#define ScreenedPoissonFit_h

#include "FitOperators.h"
#include "FitSystem.h"
#include "MeshPartition.h"
#include "ShockTypes.h"
#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace shock
{

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
  /// Non-degenerate triangles whose target normal was invalid (replaced by their own normal).
  std::int64_t invalidTargets = 0;
};

/**
 * The target gradients w of non-degenerate triangle f for the unit target normal
 * N (step 2 of the file comment): gradients[3 k .. 3 k + 2] = w_k, the target
 * gradient of coordinate k, a vector in the triangle's plane. Equivalently, the
 * 3x3 matrix W with rows w_k maps each edge e of the triangle to its target
 * W e (R e for Rotation, e - <e, N> N for Projection). Zero for degenerate
 * triangles.
 */
void FitTargetGradients(const TriangleMesh& mesh, std::int64_t f, const double normal[3],
  FitTarget target, double gradients[9]);

/**
 * Fit the positions of a mesh to target normals (see the file comment).
 *
 * @param mesh          built TriangleMesh holding the original positions c0.
 * @param targetNormals 3 components per triangle (unit length expected; see the
 *                      file comment for invalid ones); entries of degenerate
 *                      triangles are not read.
 * @param positions     output, 3 coordinates per point, in the mesh's units; must
 *                      not alias targetNormals. Never contains NaN or infinity.
 * @param parameters    see FitParameters.
 * @param report        optional: iterations, residual, timings, counters.
 * @param system        optional: the system of this mesh, screening weight and row order
 *                      (FitSystem.h), reused when it matches and (re)built into
 *                      it otherwise; not used for a piece (parameters.partition).
 *                      The caller clears it when the mesh changes.
 * @return an error message for invalid arguments or a failed factorisation; on
 *         an error other than a null pointer, positions holds the original positions.
 */
Status FitPositionsToNormals(const TriangleMesh& mesh, const double* targetNormals,
  double* positions, const FitParameters& parameters, FitReport* report = nullptr,
  FitSystem* system = nullptr);

} // namespace shock

#endif
