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
 *     (S_ij = sum_f A_f grad(phi_i) . grad(phi_j)) and (D w)_i = sum_f A_f grad(phi_i) . w_f;
 *  4. not the paper's (FitParameters::anchorWeight, 0 gives the paper's fit):
 *     the points the sharpening did not turn are held where they were. With
 *     theta_p the largest angle between a triangle's own normal and its target
 *     around point p, kappa_p = anchorWeight * A_pp * max(0, 1 - theta_p / anchorAngle)
 *     (A_pp the diagonal of eps M + S) is added to the diagonal and kappa_p c0_p
 *     to the right-hand side: the energy gains sum_p kappa_p |c_p - c0_p|^2 / 2.
 *     The uniform screening of step 3 lets the whole surface drift while the
 *     creases move; the anchor keeps flat and smooth parts whose normals stayed
 *     (docs/sharpening.md, "Points the sharpening did not turn stay");
 *  5. not the paper's either (FitParameters::driftRadius > 0, 8 by default;
 *     0 skips it): the drift is removed. With d = c1 - c0 the fitted displacement,
 *     d_low solves (eps_d M + S) d_low = eps_d M_L d (M_L the lumped mass,
 *     eps_d = 1 / (driftRadius l)^2, l the side of an equilateral triangle of
 *     the mean triangle area): d's heat diffusion over driftRadius edges, its
 *     part smoother than that. The result is c1 - d_low: the sharpening moves
 *     points against each other within a few edges (a crease forms) but no
 *     region moves as a whole, and the area-weighted mean position
 *     (sum M_L c) is kept exactly, as volume-keeping blurs keep it
 *     (docs/sharpening.md, "Keeping the local mean: DriftRadius").
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
#include "FitParameters.h"
#include "FitSystem.h"
#include "MeshPartition.h"
#include "ShockTypes.h"
#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace shock
{

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
