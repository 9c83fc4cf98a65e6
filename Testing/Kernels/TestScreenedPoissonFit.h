// The synthetic meshes, target normals and measurements shared by the tests of
// the screened Poisson fit (TestScreenedPoissonFit.cxx: properties on any mesh;
// TestScreenedPoissonFitThreads.cxx: thread counts and row orders;
// TestScreenedPoissonFitReference.cxx: an independent cotangent solution).
// Each test file gets its own copy (an unnamed namespace).
#ifndef TestScreenedPoissonFit_h
#define TestScreenedPoissonFit_h

#include "ScreenedPoissonFit.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace
{
using namespace shock;

struct Mesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  std::int64_t NumberOfPoints() const { return static_cast<std::int64_t>(this->points.size() / 3); }
};

TriangleMesh Build(const Mesh& m, int threads = 0)
{
  TriangleMesh mesh;
  const Status status = mesh.Build({ m.NumberOfPoints(), m.points.data(),
                                     static_cast<std::int64_t>(m.triangles.size() / 3),
                                     m.triangles.data() },
    threads);
  EXPECT_TRUE(status.Ok()) << status.error;
  return mesh;
}

/// Unit sphere: an icosahedron subdivided `levels` times (10 * 4^levels + 2 points).
Mesh Icosphere(int levels)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.points = { -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, t,
    0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1 };
  m.triangles = { 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10,
    7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6,
    7, 9, 8, 1 };
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> midpoints;
    auto midpoint = [&](std::int64_t a, std::int64_t b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoints.find(key);
      if (found != midpoints.end())
      {
        return found->second;
      }
      const std::int64_t id = m.NumberOfPoints();
      for (int k = 0; k < 3; ++k)
      {
        m.points.push_back(0.5 * (m.points[3 * a + k] + m.points[3 * b + k]));
      }
      midpoints.emplace(key, id);
      return id;
    };
    std::vector<std::int64_t> finer;
    for (size_t f = 0; f < m.triangles.size(); f += 3)
    {
      const std::int64_t a = m.triangles[f], b = m.triangles[f + 1], c = m.triangles[f + 2];
      const std::int64_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), { a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca });
    }
    m.triangles = std::move(finer);
  }
  for (size_t p = 0; p < m.points.size(); p += 3)
  {
    const double r = std::sqrt(m.points[p] * m.points[p] + m.points[p + 1] * m.points[p + 1] +
      m.points[p + 2] * m.points[p + 2]);
    for (int k = 0; k < 3; ++k)
    {
      m.points[p + k] /= r;
    }
  }
  return m;
}

/// Flat nx x ny grid of points on [0,1]^2 at z = 0, normals +z.
Mesh FlatGrid(int nx, int ny)
{
  Mesh m;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      m.points.insert(m.points.end(), { i / (nx - 1.0), j / (ny - 1.0), 0.0 });
    }
  }
  for (int j = 0; j + 1 < ny; ++j)
  {
    for (int i = 0; i + 1 < nx; ++i)
    {
      const std::int64_t a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      m.triangles.insert(m.triangles.end(), { a, b, c, a, c, d });
    }
  }
  return m;
}

/// Surface of the cube [-1,1]^3, n x n squares per face, welded, outward normals;
/// faceNormals receives the outward axis normal of each triangle.
Mesh Box(int n, std::vector<double>* faceNormals = nullptr)
{
  Mesh m;
  std::map<std::array<int, 3>, std::int64_t> ids;
  auto point = [&](const std::array<int, 3>& lattice) {
    const auto found = ids.find(lattice);
    if (found != ids.end())
    {
      return found->second;
    }
    const std::int64_t id = m.NumberOfPoints();
    for (int k = 0; k < 3; ++k)
    {
      m.points.push_back(2.0 * lattice[k] / n - 1.0);
    }
    ids.emplace(lattice, id);
    return id;
  };
  for (int a = 0; a < 3; ++a)
  {
    for (int side : { -1, 1 })
    {
      const int b = (a + 1) % 3, c = (a + 2) % 3; // e_b x e_c = e_a
      for (int i = 0; i < n; ++i)
      {
        for (int j = 0; j < n; ++j)
        {
          std::int64_t q[4];
          const int corners[4][2] = { { i, j }, { i + 1, j }, { i + 1, j + 1 }, { i, j + 1 } };
          for (int k = 0; k < 4; ++k)
          {
            std::array<int, 3> lattice;
            lattice[a] = side > 0 ? n : 0;
            lattice[b] = corners[k][0];
            lattice[c] = corners[k][1];
            q[k] = point(lattice);
          }
          if (side > 0)
          {
            m.triangles.insert(m.triangles.end(), { q[0], q[1], q[2], q[0], q[2], q[3] });
          }
          else
          {
            m.triangles.insert(m.triangles.end(), { q[0], q[2], q[1], q[0], q[3], q[2] });
          }
          if (faceNormals)
          {
            for (int t = 0; t < 2; ++t)
            {
              for (int k = 0; k < 3; ++k)
              {
                faceNormals->push_back(k == a ? side : 0.0);
              }
            }
          }
        }
      }
    }
  }
  return m;
}

std::vector<double> OwnNormals(const TriangleMesh& mesh)
{
  std::vector<double> normals;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    normals.insert(normals.end(), mesh.Normal(f), mesh.Normal(f) + 3);
  }
  return normals;
}

/// Smoothly perturbed unit normals: a target field that differs from the mesh's.
std::vector<double> PerturbedNormals(const TriangleMesh& mesh, double amount)
{
  std::vector<double> normals;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double* n = mesh.Normal(f);
    const shock::Vec3 c = mesh.Centroid(f);
    double t[3] = { n[0] + amount * std::sin(3.0 * c[1]), n[1] + amount * std::cos(2.0 * c[2]),
      n[2] + amount * std::sin(5.0 * c[0]) };
    const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (double v : t)
    {
      normals.push_back(v / length);
    }
  }
  return normals;
}

std::vector<double> Fit(const TriangleMesh& mesh, const std::vector<double>& targets,
  const FitParameters& parameters = {}, FitReport* report = nullptr)
{
  std::vector<double> positions(static_cast<size_t>(3 * mesh.NumberOfPoints()));
  const Status status =
    FitPositionsToNormals(mesh, targets.data(), positions.data(), parameters, report);
  EXPECT_TRUE(status.Ok()) << status.error;
  return positions;
}

FitParameters WithSolver(FitSolver solver)
{
  FitParameters p;
  p.solver = solver;
  return p;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst;
}

bool AllFinite(const std::vector<double>& values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

/// Area-weighted mean angle (radians) between the normals of `m` with new positions and targets.
double MeanNormalError(const Mesh& m, const std::vector<double>& positions,
  const std::vector<double>& targets)
{
  Mesh moved = m;
  moved.points = positions;
  const TriangleMesh mesh = Build(moved);
  double sum = 0.0, area = 0.0;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const double* n = mesh.Normal(f);
    const double* t = &targets[static_cast<size_t>(3 * f)];
    const double cosine = std::clamp(n[0] * t[0] + n[1] * t[1] + n[2] * t[2], -1.0, 1.0);
    sum += mesh.Area(f) * std::acos(cosine);
    area += mesh.Area(f);
  }
  return sum / area;
}

const FitSolver AllSolvers[] = { FitSolver::ConjugateGradient,
  FitSolver::ConjugateGradientTolerance, FitSolver::Exact };

} // namespace

#endif
