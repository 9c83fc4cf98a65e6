/**
 * @file FitOperators.h
 * @brief The finite-element operators of the screened Poisson fit (Prada and
 * Kazhdan 2015, section 4.1), each as a list of entries: mass matrix M,
 * stiffness matrix S and the divergence D of a per-triangle gradient field.
 *
 * These are the paper's operators written one at a time, for inspection and
 * tests; the fit assembles eps M + S straight into compressed rows
 * (FitSystem.h) with the same per-triangle terms.
 */
#ifndef ShockFitOperators_h
#define ShockFitOperators_h

#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace shock
{

/// One entry of a sparse matrix; entries with the same row and column add up.
struct SparseEntry
{
  std::int64_t row = 0;
  std::int64_t column = 0;
  double value = 0.0;
};

/**
 * The consistent finite-element mass matrix M of the mesh's hat functions: per
 * non-degenerate triangle of area A, A/12 [2 1 1; 1 2 1; 1 1 2] on its corners
 * (one entry per triangle and corner pair, in triangle order).
 */
std::vector<SparseEntry> MassMatrix(const TriangleMesh& mesh);

/**
 * The stiffness matrix S_ij = sum_f A_f grad(phi_i) . grad(phi_j) (the cotangent
 * Laplacian), one entry per non-degenerate triangle and corner pair.
 */
std::vector<SparseEntry> StiffnessMatrix(const TriangleMesh& mesh);

/**
 * The divergence of a per-triangle gradient field: (D w)_i = sum_f A_f
 * grad(phi_i) . w_{f,k} for each coordinate k. `gradients` holds 9 values per
 * triangle, w_{f,k} = gradients[9 f + 3 k .. 9 f + 3 k + 2]; returns 3 values
 * per point. Degenerate triangles contribute nothing.
 */
std::vector<double> Divergence(const TriangleMesh& mesh, const double* gradients);

/// Entry (i, j) of the mass matrix of a triangle of area `area`: A/12 (2 on the diagonal, 1 off it).
inline double TriangleMass(double area, int i, int j)
{
  return (i == j ? 2.0 : 1.0) * area / 12.0;
}

} // namespace shock

#endif
