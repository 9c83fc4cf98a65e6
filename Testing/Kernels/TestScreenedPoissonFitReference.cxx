// Unit test of the screened Poisson fit of positions to target normals against
// an independent solution: the system built from the classical cotangent formula
// for every fit target, solved densely (the other tests:
// TestScreenedPoissonFit.cxx, TestScreenedPoissonFitThreads.cxx).
#include "TestScreenedPoissonFit.h"

namespace
{

using Vec3 = std::array<double, 3>;
Vec3 Sub(const Vec3& a, const Vec3& b) { return { a[0] - b[0], a[1] - b[1], a[2] - b[2] }; }
double Dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

/// Solve a small dense system by Gaussian elimination with partial pivoting.
std::vector<double> SolveDense(std::vector<std::vector<double>> a, std::vector<double> b)
{
  const size_t n = b.size();
  for (size_t c = 0; c < n; ++c)
  {
    size_t pivot = c;
    for (size_t r = c + 1; r < n; ++r)
    {
      pivot = std::abs(a[r][c]) > std::abs(a[pivot][c]) ? r : pivot;
    }
    std::swap(a[c], a[pivot]);
    std::swap(b[c], b[pivot]);
    for (size_t r = c + 1; r < n; ++r)
    {
      const double factor = a[r][c] / a[c][c];
      for (size_t k = c; k < n; ++k)
      {
        a[r][k] -= factor * a[c][k];
      }
      b[r] -= factor * b[c];
    }
  }
  std::vector<double> x(n);
  for (size_t r = n; r-- > 0;)
  {
    double sum = b[r];
    for (size_t k = r + 1; k < n; ++k)
    {
      sum -= a[r][k] * x[k];
    }
    x[r] = sum / a[r][r];
  }
  return x;
}

TEST(ScreenedPoissonFit, MatchesAnIndependentCotangentSolution)
{
  // Two random triangles sharing an edge, random targets: the exact fit must equal
  // the solution of the system built here from the classical cotangent formula,
  // barycentric gradients from the Gram matrix, and the unit-area screening weight,
  // for each fit target T: the target Jacobian is T J (J the position's Jacobian),
  // with T = I - N N^T (the paper's projection), the rotation about n x N by the
  // angle between them (axis-angle form), or (I - n N^T / c) / c^p for the shear
  // (p = 0) and the central projection (p = 1), c = <n, N> (tilts below 45 degrees).
  // The anchor: with theta_p the largest angle between a triangle's own and target
  // normals at point p, kappa_p = weight * a_pp * max(0, 1 - theta_p / angle) is
  // added to the diagonal a_pp and kappa_p x0_p to the right-hand side (0 for
  // the paper's fit: every fifth trial; small tilts make partial anchors).
  // The drift's removal (step 5 of ScreenedPoissonFit.h) after it, with random
  // radii (none every fourth trial).
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int partialAnchors = 0; // points held by a part of the anchor weight (0 < kappa < weight a_pp)
  int driftMoves = 0;     // coordinates the drift's removal moved by more than 1e-6
  for (int trial = 0; trial < 80; ++trial)
  {
    const FitTarget target = static_cast<FitTarget>(trial % 4);
    Mesh m;
    for (int i = 0; i < 12; ++i)
    {
      m.points.push_back(3.0 * uniform(random));
    }
    m.triangles = { 0, 1, 2, 0, 2, 3 };
    const TriangleMesh mesh = Build(m);
    ASSERT_FALSE(mesh.Degenerate(0) || mesh.Degenerate(1));
    // Targets tilted from the triangles' normals by less than 45 degrees; every
    // third trial by less than 2 degrees, for a partial anchor.
    const double tilt = trial % 3 == 0 ? 0.015 : 0.4;
    std::vector<double> targets;
    for (int f = 0; f < 2; ++f)
    {
      for (int k = 0; k < 3; ++k)
      {
        targets.push_back(mesh.Normal(f)[k] + tilt * uniform(random));
      }
    }
    const double anchorWeight = trial % 5 == 0 ? 0.0 : 0.1 + 5.0 * (uniform(random) + 1.0);
    const double anchorAngle = trial % 3 == 0 ? 1.0 + 2.0 * (uniform(random) + 1.0) : 60.0;
    const double weight = trial % 2 ? 1.0 : 0.1 + 10.0 * (uniform(random) + 1.0);
    const double driftRadius = trial % 4 == 1 ? 0.0 : 0.3 + 3.0 * (uniform(random) + 1.0);

    auto point = [&](std::int64_t p) {
      return Vec3{ m.points[3 * p], m.points[3 * p + 1], m.points[3 * p + 2] };
    };
    std::vector<std::vector<double>> stiffness(4, std::vector<double>(4, 0.0));
    std::vector<std::vector<double>> mass = stiffness;
    std::vector<std::vector<double>> divergence(4, std::vector<double>(3, 0.0));
    double totalArea = 0.0;
    std::vector<double> turn(4, 0.0); // degrees: the largest at each point
    for (int f = 0; f < 2; ++f)
    {
      const std::int64_t* t = &m.triangles[static_cast<size_t>(3 * f)];
      const Vec3 x[3] = { point(t[0]), point(t[1]), point(t[2]) };
      const Vec3 e1 = Sub(x[1], x[0]), e2 = Sub(x[2], x[0]);
      const double area = 0.5 * std::sqrt(Dot(Cross(e1, e2), Cross(e1, e2)));
      totalArea += area;
      for (int c = 0; c < 3; ++c)
      {
        // The angle at corner c weighs the opposite edge (i, j): S_ij = -cot/2.
        const int i = (c + 1) % 3, j = (c + 2) % 3;
        const Vec3 a = Sub(x[i], x[c]), b = Sub(x[j], x[c]);
        const Vec3 axb = Cross(a, b);
        const double cot = Dot(a, b) / std::sqrt(Dot(axb, axb));
        stiffness[t[i]][t[j]] -= 0.5 * cot;
        stiffness[t[j]][t[i]] -= 0.5 * cot;
        stiffness[t[i]][t[i]] += 0.5 * cot;
        stiffness[t[j]][t[j]] += 0.5 * cot;
        for (int d = 0; d < 3; ++d)
        {
          mass[t[c]][t[d]] += area / 12.0 * (c == d ? 2.0 : 1.0);
        }
      }
      // Gradients of the barycentric coordinates: E (E^T E)^-1, E = [e1 e2].
      const double g11 = Dot(e1, e1), g12 = Dot(e1, e2), g22 = Dot(e2, e2);
      const double det = g11 * g22 - g12 * g12;
      Vec3 grad[3];
      for (int k = 0; k < 3; ++k)
      {
        grad[1][k] = (g22 * e1[k] - g12 * e2[k]) / det;
        grad[2][k] = (g11 * e2[k] - g12 * e1[k]) / det;
        grad[0][k] = -grad[1][k] - grad[2][k];
      }
      Vec3 n = { targets[3 * f], targets[3 * f + 1], targets[3 * f + 2] };
      const double length = std::sqrt(Dot(n, n));
      for (double& v : n)
      {
        v /= length;
      }
      // Jacobian of the position, J[k] = grad x_k, and the target map T.
      const Vec3 own = [&] {
        const Vec3 c = Cross(e1, e2);
        const double l = std::sqrt(Dot(c, c));
        return Vec3{ c[0] / l, c[1] / l, c[2] / l };
      }();
      const double cosine = Dot(own, n);
      for (int c = 0; c < 3; ++c)
      {
        turn[t[c]] = std::max(turn[t[c]], std::acos(std::min(1.0, cosine)) * 180.0 / 3.14159265358979323846);
      }
      double map[3][3];
      const Vec3 axis = Cross(own, n);
      const double sine = std::sqrt(Dot(axis, axis));
      for (int i = 0; i < 3; ++i)
      {
        for (int j = 0; j < 3; ++j)
        {
          const double delta = i == j ? 1.0 : 0.0;
          switch (target)
          {
            case FitTarget::Projection:
              map[i][j] = delta - n[i] * n[j];
              break;
            case FitTarget::Rotation:
            {
              const double u[3] = { axis[0] / sine, axis[1] / sine, axis[2] / sine };
              const double k[3][3] = { { 0, -u[2], u[1] }, { u[2], 0, -u[0] }, { -u[1], u[0], 0 } };
              map[i][j] = cosine * delta + sine * k[i][j] + (1.0 - cosine) * u[i] * u[j];
              break;
            }
            case FitTarget::Shear:
              map[i][j] = delta - own[i] * n[j] / cosine;
              break;
            case FitTarget::CentralProjection:
              map[i][j] = (delta - own[i] * n[j] / cosine) / cosine;
              break;
          }
        }
      }
      Vec3 jacobian[3] = {};
      for (int k = 0; k < 3; ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          for (int d = 0; d < 3; ++d)
          {
            jacobian[k][d] += x[c][k] * grad[c][d];
          }
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        Vec3 w = {};
        for (int j = 0; j < 3; ++j)
        {
          for (int d = 0; d < 3; ++d)
          {
            w[d] += map[k][j] * jacobian[j][d];
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          divergence[t[c]][k] += area * Dot(grad[c], w);
        }
      }
    }
    // Unit-area normalisation: eps on the normalised mesh is eps / area here.
    const double screening = weight / totalArea;
    std::vector<std::vector<double>> a(4, std::vector<double>(4));
    for (int i = 0; i < 4; ++i)
    {
      for (int j = 0; j < 4; ++j)
      {
        a[i][j] = screening * mass[i][j] + stiffness[i][j];
      }
    }
    std::vector<double> anchor(4);
    for (int i = 0; i < 4; ++i)
    {
      const double share = std::max(0.0, 1.0 - turn[i] / anchorAngle);
      anchor[i] = anchorWeight * a[i][i] * share;
      a[i][i] += anchor[i];
      partialAnchors += anchorWeight > 0.0 && share > 0.0 && share < 1.0 ? 1 : 0;
    }
    FitParameters p = WithSolver(FitSolver::Exact);
    p.screeningWeight = weight;
    p.target = target;
    p.anchorWeight = anchorWeight;
    p.anchorAngle = anchorAngle;
    p.driftRadius = driftRadius;
    const auto fitted = Fit(mesh, targets, p);
    // The drift's removal: d = c1 - c0, (eps_d M + S) y = eps_d M_L d with
    // eps_d = 1 / (r l)^2 on the unit-area mesh, l the side of an equilateral
    // triangle of the mean area (1 / 2 there), M_L the rows' sums of M; c = c1 - y.
    const double side = std::sqrt(4.0 / (std::sqrt(3.0) * 2.0));
    const double drift = driftRadius > 0.0 ? 1.0 / (driftRadius * side * driftRadius * side) / totalArea : 0.0;
    std::vector<std::vector<double>> heat(4, std::vector<double>(4));
    std::vector<double> lumped(4, 0.0);
    for (int i = 0; i < 4; ++i)
    {
      for (int j = 0; j < 4; ++j)
      {
        heat[i][j] = drift * mass[i][j] + stiffness[i][j];
        lumped[i] += mass[i][j];
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      std::vector<double> b(4, 0.0);
      for (int i = 0; i < 4; ++i)
      {
        for (int j = 0; j < 4; ++j)
        {
          b[i] += screening * mass[i][j] * m.points[3 * j + k];
        }
        b[i] += divergence[i][k] + anchor[i] * m.points[3 * i + k];
      }
      auto expected = SolveDense(a, b);
      if (drift > 0.0)
      {
        std::vector<double> mean(4);
        for (int i = 0; i < 4; ++i)
        {
          mean[i] = drift * lumped[i] * (expected[i] - m.points[3 * i + k]);
        }
        const auto low = SolveDense(heat, mean);
        for (int i = 0; i < 4; ++i)
        {
          expected[i] -= low[i];
          driftMoves += std::abs(low[i]) > 1e-6 ? 1 : 0;
        }
      }
      for (int i = 0; i < 4; ++i)
      {
        EXPECT_NEAR(fitted[3 * i + k], expected[i], 1e-9) << "trial " << trial << ", target " << static_cast<int>(target);
      }
    }
  }
  EXPECT_GT(partialAnchors, 20);
  EXPECT_GT(driftMoves, 300);
}

} // namespace
