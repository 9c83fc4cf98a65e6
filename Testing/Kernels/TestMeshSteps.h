// Shared by the mesh-step tests (TestMeshSteps.cxx, TestMeshTraceSteps.cxx) and
// the fit operators' (TestFitOperators.cxx): small irregular meshes and the
// independent references, written from the paper.
#ifndef TestMeshSteps_h
#define TestMeshSteps_h

#include "MeshAdvect.h"
#include "MeshFlow.h"
#include "MeshShockAdvection.h"
#include "MeshTrace.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace meshsteps
{
using namespace shock;
using V3 = std::array<double, 3>;


inline V3 Sub(const V3& a, const V3& b) { return { a[0] - b[0], a[1] - b[1], a[2] - b[2] }; }
inline V3 Add(const V3& a, const V3& b) { return { a[0] + b[0], a[1] + b[1], a[2] + b[2] }; }
inline V3 Mul(double s, const V3& a) { return { s * a[0], s * a[1], s * a[2] }; }
inline double Dot3(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 Cross3(const V3& a, const V3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
inline double Norm3(const V3& a) { return std::sqrt(Dot3(a, a)); }

/// A mesh as plain arrays, with its TriangleMesh.
struct SmallMesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  TriangleMesh mesh;

  int Points() const { return static_cast<int>(points.size() / 3); }
  int Triangles() const { return static_cast<int>(triangles.size() / 3); }
  V3 P(std::int64_t i) const { return { points[3 * i], points[3 * i + 1], points[3 * i + 2] }; }
  std::array<std::int64_t, 3> T(int f) const
  {
    return { triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2] };
  }
  double Area(int f) const
  {
    const auto t = T(f);
    return 0.5 * Norm3(Cross3(Sub(P(t[1]), P(t[0])), Sub(P(t[2]), P(t[0]))));
  }
  V3 Centre(int f) const
  {
    const auto t = T(f);
    return Mul(1.0 / 3.0, Add(Add(P(t[0]), P(t[1])), P(t[2])));
  }
  /// l-bar: each triangle's three edges, averaged (TriangleMesh's documented convention).
  double MeanEdge() const
  {
    double sum = 0.0;
    for (int f = 0; f < Triangles(); ++f)
    {
      const auto t = T(f);
      for (int e = 0; e < 3; ++e)
        sum += Norm3(Sub(P(t[(e + 1) % 3]), P(t[e])));
    }
    return sum / (3.0 * Triangles());
  }
  std::vector<std::set<std::int64_t>> Neighbours() const
  {
    std::vector<std::set<std::int64_t>> n(Points());
    for (int f = 0; f < Triangles(); ++f)
    {
      const auto t = T(f);
      for (int e = 0; e < 3; ++e)
      {
        n[t[e]].insert(t[(e + 1) % 3]);
        n[t[(e + 1) % 3]].insert(t[e]);
      }
    }
    return n;
  }
  void Build()
  {
    TriangleMeshView view;
    view.numberOfPoints = Points();
    view.points = points.data();
    view.numberOfTriangles = Triangles();
    view.triangles = triangles.data();
    ASSERT_TRUE(mesh.Build(view, 1).Ok());
  }
};

/// A jittered (nx x ny) sheet, diagonals chosen at random, height z(x, y).
inline SmallMesh Sheet(int nx, int ny, unsigned seed, double bend)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  SmallMesh m;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const bool inside = i > 0 && j > 0 && i + 1 < nx && j + 1 < ny;
      const double x = i + (inside ? jitter(random) : 0.0);
      const double y = 0.8 * j + (inside ? jitter(random) : 0.0);
      m.points.insert(m.points.end(), { x, y, bend * std::sin(0.9 * x) * std::cos(0.7 * y) });
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
    {
      const std::int64_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      if (random() % 2)
        m.triangles.insert(m.triangles.end(), { a, b, d, a, d, c });
      else
        m.triangles.insert(m.triangles.end(), { a, b, c, b, d, c });
    }
  return m;
}

/// Gradient of the linear interpolant of (f0, f1, f2) on a triangle: the vector g in
/// the triangle's plane with g . (x1 - x0) = f1 - f0 and g . (x2 - x0) = f2 - f0.
inline V3 RefGradient(const V3& x0, const V3& x1, const V3& x2, double f0, double f1, double f2)
{
  const V3 e1 = Sub(x1, x0), e2 = Sub(x2, x0);
  // g = a e1 + b e2 (in the plane); the Gram system.
  const double g11 = Dot3(e1, e1), g12 = Dot3(e1, e2), g22 = Dot3(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  const double a = ((f1 - f0) * g22 - (f2 - f0) * g12) / det;
  const double b = ((f2 - f0) * g11 - (f1 - f0) * g12) / det;
  return Add(Mul(a, e1), Mul(b, e2));
}

inline V3 RefTriangleGradient(const SmallMesh& m, const std::vector<double>& values, int C, int c, int f)
{
  const auto t = m.T(f);
  return RefGradient(m.P(t[0]), m.P(t[1]), m.P(t[2]), values[t[0] * C + c], values[t[1] * C + c],
    values[t[2] * C + c]);
}

inline std::vector<double> RefSmooth(const SmallMesh& m, int C, const std::vector<double>& in)
{
  const double l = m.MeanEdge();
  const auto ring = m.Neighbours();
  std::vector<double> out(in.size());
  for (int p = 0; p < m.Points(); ++p)
  {
    double total = 1.0;
    std::vector<double> sum(in.begin() + p * C, in.begin() + (p + 1) * C);
    for (std::int64_t w : ring[p])
    {
      const double d = Norm3(Sub(m.P(p), m.P(w))) / l;
      const double alpha = std::exp(-d * d);
      total += alpha;
      for (int c = 0; c < C; ++c)
        sum[c] += alpha * in[w * C + c];
    }
    for (int c = 0; c < C; ++c)
      out[p * C + c] = sum[c] / total;
  }
  return out;
}

inline std::vector<double> RefAreaAverage(const SmallMesh& m, const std::vector<double>& perTriangle)
{
  std::vector<double> sum(m.Points(), 0.0), area(m.Points(), 0.0);
  for (int f = 0; f < m.Triangles(); ++f)
    for (std::int64_t p : m.T(f))
    {
      sum[p] += m.Area(f) * perTriangle[f];
      area[p] += m.Area(f);
    }
  for (int p = 0; p < m.Points(); ++p)
    sum[p] /= area[p];
  return sum;
}

inline std::vector<double> Random(size_t count, unsigned seed, double low, double high)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(low, high);
  std::vector<double> v(count);
  for (double& x : v)
    x = u(random);
  return v;
}

/// The 3D point of a surface point.
inline V3 Position(const SmallMesh& m, const SurfacePoint& q)
{
  const auto t = m.T(static_cast<int>(q.triangle));
  V3 x{ 0.0, 0.0, 0.0 };
  for (int k = 0; k < 3; ++k)
    x = Add(x, Mul(q.barycentric[k], m.P(t[k])));
  return x;
}

/// Two triangles hinged on the y axis: A flat at z = 0 (x < 0), B leaning back over A.
inline SmallMesh Hinge()
{
  SmallMesh m;
  m.points = { 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, -1.0, 1.0, 0.0, -0.3, 1.0, 1.0 };
  m.triangles = { 0, 1, 2, 1, 0, 3 };
  return m;
}
} // namespace meshsteps

#endif
