// The operators of the screened Poisson fit (section 4.1: mass matrix M,
// stiffness matrix S, divergence D) against independent computations on a small
// curved mesh with triangles of unequal areas: M by exact quadrature of
// products of linear functions, S by the cotangent formula, D by gradients of
// the hat functions solved from their interpolation conditions. Then the fit
// itself: its exact solution satisfies (eps M + S) c = eps M c0 + D w.
#include "ScreenedPoissonFit.h"
#include "TestMeshSteps.h" // V3 arithmetic and SmallMesh, shared with the mesh-step tests
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace
{
using namespace meshsteps;
using Case = SmallMesh;

/// A curved, jittered 5 x 4 sheet with random diagonals.
Case Sheet()
{
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  Case c;
  const int nx = 5, ny = 4;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const double x = i + jitter(random), y = 0.9 * j + jitter(random);
      c.points.insert(c.points.end(), { x, y, 0.4 * std::sin(x) * std::cos(0.8 * y) });
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
    {
      const std::int64_t a = j * nx + i, b = a + 1, d = a + nx, e = d + 1;
      if (random() % 2)
        c.triangles.insert(c.triangles.end(), { a, b, e, a, e, d });
      else
        c.triangles.insert(c.triangles.end(), { a, b, d, b, e, d });
    }
  c.Build();
  return c;
}

using Dense = std::vector<std::vector<double>>;

Dense ToDense(const std::vector<SparseEntry>& entries, int n)
{
  Dense d(n, std::vector<double>(n, 0.0));
  for (const auto& e : entries)
    d[e.row][e.column] += e.value;
  return d;
}

double Form(const Dense& m, const std::vector<double>& a, const std::vector<double>& b)
{
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j)
      s += a[i] * m[i][j] * b[j];
  return s;
}

/// Gradient of the linear interpolant of values f on triangle (x0, x1, x2), in its plane.
V3 Gradient(const V3& x0, const V3& x1, const V3& x2, double f0, double f1, double f2)
{
  const V3 e1 = Sub(x1, x0), e2 = Sub(x2, x0);
  const double g11 = Dot3(e1, e1), g12 = Dot3(e1, e2), g22 = Dot3(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  const double a = ((f1 - f0) * g22 - (f2 - f0) * g12) / det;
  const double b = ((f2 - f0) * g11 - (f1 - f0) * g12) / det;
  return Add(Mul(a, e1), Mul(b, e2));
}

V3 HatGradient(const Case& c, int f, int corner)
{
  const auto t = c.T(f);
  return Gradient(c.P(t[0]), c.P(t[1]), c.P(t[2]), corner == 0, corner == 1, corner == 2);
}

/// Selects the paper's projection target where FitParameters offers a choice of
/// targets (value 0 of FitParameters::target); nothing to do where it does not.
template <typename Parameters>
auto UsePaperTarget(Parameters& p, int) -> decltype(p.target, void())
{
  p.target = static_cast<decltype(p.target)>(0);
}
template <typename Parameters>
void UsePaperTarget(Parameters&, long)
{
}

TEST(FitOperators, MassMatrixIntegratesProductsOfLinearFunctions)
{
  Case c = Sheet();
  const Dense M = ToDense(MassMatrix(c.mesh), c.Points());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial)
  {
    std::vector<double> f(c.Points()), g(c.Points());
    for (int p = 0; p < c.Points(); ++p)
    {
      f[p] = u(random);
      g[p] = u(random);
    }
    // The integral of the product of two linear functions over a triangle: the
    // three edge-midpoint rule, exact for quadratics.
    double integral = 0.0;
    for (int t = 0; t < c.Triangles(); ++t)
    {
      const auto v = c.T(t);
      double sum = 0.0;
      for (int e = 0; e < 3; ++e)
      {
        const std::int64_t a = v[e], b = v[(e + 1) % 3];
        sum += 0.25 * (f[a] + f[b]) * (g[a] + g[b]);
      }
      integral += c.Area(t) / 3.0 * sum;
    }
    EXPECT_NEAR(Form(M, f, g), integral, 1e-12);
  }
  // The rows sum to the integrals of the hat functions, a third of the area around each point.
  for (int p = 0; p < c.Points(); ++p)
  {
    double row = 0.0, third = 0.0;
    for (int q = 0; q < c.Points(); ++q)
      row += M[p][q];
    for (int t = 0; t < c.Triangles(); ++t)
      for (std::int64_t v : c.T(t))
        third += v == p ? c.Area(t) / 3.0 : 0.0;
    EXPECT_NEAR(row, third, 1e-13);
  }
}

TEST(FitOperators, StiffnessMatrixIsTheCotangentLaplacian)
{
  Case c = Sheet();
  const Dense S = ToDense(StiffnessMatrix(c.mesh), c.Points());
  // S_ij = -1/2 (cot alpha + cot beta) over the angles opposite edge ij; S_ii = -sum_j S_ij.
  Dense expected(c.Points(), std::vector<double>(c.Points(), 0.0));
  for (int t = 0; t < c.Triangles(); ++t)
  {
    const auto v = c.T(t);
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t o = v[k], i = v[(k + 1) % 3], j = v[(k + 2) % 3];
      const V3 a = Sub(c.P(i), c.P(o)), b = Sub(c.P(j), c.P(o));
      const double cot = Dot3(a, b) / Norm3(Cross3(a, b));
      expected[i][j] -= 0.5 * cot;
      expected[j][i] -= 0.5 * cot;
      expected[i][i] += 0.5 * cot;
      expected[j][j] += 0.5 * cot;
    }
  }
  for (int i = 0; i < c.Points(); ++i)
    for (int j = 0; j < c.Points(); ++j)
      EXPECT_NEAR(S[i][j], expected[i][j], 1e-12) << i << "," << j;
}

TEST(FitOperators, DivergenceIntegratesTheFieldAgainstHatGradients)
{
  Case c = Sheet();
  std::mt19937 random(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> w(9 * c.Triangles());
  for (double& x : w)
    x = u(random);
  const auto divergence = Divergence(c.mesh, w.data());
  std::vector<double> expected(3 * c.Points(), 0.0);
  for (int t = 0; t < c.Triangles(); ++t)
    for (int corner = 0; corner < 3; ++corner)
    {
      const V3 g = HatGradient(c, t, corner);
      for (int k = 0; k < 3; ++k)
        expected[3 * c.T(t)[corner] + k] +=
          c.Area(t) * Dot3(g, { w[9 * t + 3 * k], w[9 * t + 3 * k + 1], w[9 * t + 3 * k + 2] });
    }
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_NEAR(divergence[i], expected[i], 1e-12) << i;
  // Integration by parts: D of the gradient of a linear function f is S f.
  const Dense S = ToDense(StiffnessMatrix(c.mesh), c.Points());
  std::vector<double> f(c.Points());
  for (double& x : f)
    x = u(random);
  std::vector<double> grad(9 * c.Triangles(), 0.0);
  for (int t = 0; t < c.Triangles(); ++t)
  {
    const auto v = c.T(t);
    const V3 g = Gradient(c.P(v[0]), c.P(v[1]), c.P(v[2]), f[v[0]], f[v[1]], f[v[2]]);
    std::copy(g.begin(), g.end(), grad.begin() + 9 * t); // coordinate 0 only
  }
  const auto df = Divergence(c.mesh, grad.data());
  for (int i = 0; i < c.Points(); ++i)
  {
    double sf = 0.0;
    for (int j = 0; j < c.Points(); ++j)
      sf += S[i][j] * f[j];
    EXPECT_NEAR(df[3 * i], sf, 1e-12);
    EXPECT_EQ(df[3 * i + 1], 0.0);
  }
}

TEST(FitOperators, TheExactFitSolvesTheScreenedPoissonSystem)
{
  // The paper's fit: c1 = argmin eps ||c - c0||^2_M + ||grad c - w||^2, i.e.
  // (eps M + S) c1 = eps M c0 + D w, with w_k = v_k - N_k <N, v> (v = grad c0).
  // The mesh is first brought to unit area with its area centroid at the
  // origin, the frame the fit solves in, so that its positions are c1 itself.
  Case raw = Sheet();
  double area = 0.0;
  V3 centroid{ 0.0, 0.0, 0.0 };
  for (int t = 0; t < raw.Triangles(); ++t)
  {
    const auto v = raw.T(t);
    area += raw.Area(t);
    centroid = Add(centroid, Mul(raw.Area(t) / 3.0, Add(Add(raw.P(v[0]), raw.P(v[1])), raw.P(v[2]))));
  }
  centroid = Mul(1.0 / area, centroid);
  Case c = raw;
  for (int p = 0; p < c.Points(); ++p)
  {
    const V3 x = Mul(1.0 / std::sqrt(area), Sub(raw.P(p), centroid));
    std::copy(x.begin(), x.end(), c.points.begin() + 3 * p);
  }
  TriangleMeshView view{ c.Points(), c.points.data(), c.Triangles(), c.triangles.data() };
  ASSERT_TRUE(c.mesh.Build(view, 1).Ok());

  // Target normals: each triangle's own normal tilted towards +z and renormalised.
  std::vector<double> normals(3 * c.Triangles());
  std::vector<double> w(9 * c.Triangles());
  for (int t = 0; t < c.Triangles(); ++t)
  {
    const auto v = c.T(t);
    const V3 own = Cross3(Sub(c.P(v[1]), c.P(v[0])), Sub(c.P(v[2]), c.P(v[0])));
    V3 n = Add(Mul(1.0 / Norm3(own), own), { 0.3 * std::sin(t), 0.0, 0.5 });
    n = Mul(1.0 / Norm3(n), n);
    std::copy(n.begin(), n.end(), normals.begin() + 3 * t);
    V3 grad[3];
    for (int k = 0; k < 3; ++k)
      grad[k] = Gradient(c.P(v[0]), c.P(v[1]), c.P(v[2]), c.P(v[0])[k], c.P(v[1])[k], c.P(v[2])[k]);
    for (int k = 0; k < 3; ++k)
    {
      // <N, v> = sum_j N_j v_j, a vector; w_k = v_k - N_k <N, v>.
      V3 nv{ 0.0, 0.0, 0.0 };
      for (int j = 0; j < 3; ++j)
        nv = Add(nv, Mul(n[j], grad[j]));
      const V3 wk = Sub(grad[k], Mul(n[k], nv));
      std::copy(wk.begin(), wk.end(), w.begin() + 9 * t + 3 * k);
    }
  }
  FitParameters p;
  UsePaperTarget(p, 0);
  p.anchorWeight = 0.0; // the paper's fit: no anchor of the unturned points
  p.driftRadius = 0.0;  // nor drift removal
  p.solver = FitSolver::Exact;
  p.screeningWeight = 0.7;
  std::vector<double> fitted(c.points.size());
  ASSERT_TRUE(FitPositionsToNormals(c.mesh, normals.data(), fitted.data(), p).Ok());

  const Dense M = ToDense(MassMatrix(c.mesh), c.Points());
  const Dense S = ToDense(StiffnessMatrix(c.mesh), c.Points());
  const auto Dw = Divergence(c.mesh, w.data());
  double worst = 0.0, scale = 0.0, moved = 0.0;
  for (int i = 0; i < c.Points(); ++i)
    for (int k = 0; k < 3; ++k)
    {
      double lhs = 0.0, rhs = Dw[3 * i + k];
      for (int j = 0; j < c.Points(); ++j)
      {
        lhs += (p.screeningWeight * M[i][j] + S[i][j]) * fitted[3 * j + k];
        rhs += p.screeningWeight * M[i][j] * c.points[3 * j + k];
      }
      worst = std::max(worst, std::abs(lhs - rhs));
      scale = std::max(scale, std::abs(rhs));
      moved = std::max(moved, std::abs(fitted[3 * i + k] - c.points[3 * i + k]));
    }
  EXPECT_LT(worst, 1e-9 * scale);
  EXPECT_GT(moved, 1e-3); // the fit moved the points
}

TEST(FitOperators, OnlyTheJacobianReadingOfTheTargetCanBendAFlatMesh)
{
  // The paper's w = v - N <N, v> read two ways on a flat mesh (z = 0) with
  // tilted targets. Per coordinate gradient, w_k = v_k - <v_k, N> N: v_z = 0
  // gives w_z = 0, so D w_z = 0 and the z equation (eps M + S) c_z = 0 keeps
  // the mesh flat. As the Jacobian, w_k = v_k - N_k <N, v>: w_z = -N_z <N, v>
  // is not zero, so the mesh can bend.
  Case c = Sheet();
  for (int p = 0; p < c.Points(); ++p)
    c.points[3 * p + 2] = 0.0;
  TriangleMeshView view{ c.Points(), c.points.data(), c.Triangles(), c.triangles.data() };
  ASSERT_TRUE(c.mesh.Build(view, 1).Ok());
  std::vector<double> perCoordinate(9 * c.Triangles()), jacobian(9 * c.Triangles());
  for (int t = 0; t < c.Triangles(); ++t)
  {
    const auto v = c.T(t);
    V3 n = { 0.4 * std::cos(t), 0.3, 1.0 };
    n = Mul(1.0 / Norm3(n), n);
    V3 grad[3];
    for (int k = 0; k < 3; ++k)
      grad[k] = Gradient(c.P(v[0]), c.P(v[1]), c.P(v[2]), c.P(v[0])[k], c.P(v[1])[k], c.P(v[2])[k]);
    V3 nv{ 0.0, 0.0, 0.0 };
    for (int j = 0; j < 3; ++j)
      nv = Add(nv, Mul(n[j], grad[j]));
    for (int k = 0; k < 3; ++k)
    {
      const V3 a = Sub(grad[k], Mul(Dot3(grad[k], n), n));
      const V3 b = Sub(grad[k], Mul(n[k], nv));
      std::copy(a.begin(), a.end(), perCoordinate.begin() + 9 * t + 3 * k);
      std::copy(b.begin(), b.end(), jacobian.begin() + 9 * t + 3 * k);
    }
  }
  const auto flat = Divergence(c.mesh, perCoordinate.data());
  const auto bent = Divergence(c.mesh, jacobian.data());
  double largestFlat = 0.0, largestBent = 0.0;
  for (int p = 0; p < c.Points(); ++p)
  {
    largestFlat = std::max(largestFlat, std::abs(flat[3 * p + 2]));
    largestBent = std::max(largestBent, std::abs(bent[3 * p + 2]));
  }
  EXPECT_LT(largestFlat, 1e-15);
  EXPECT_GT(largestBent, 0.05);
}

} // namespace
