// fitbench: wall time of the screened Poisson fit of positions to target normals
// (shock::FitPositionsToNormals, VTK-free) on subdivided icospheres.
//
//   fitbench [--threads N] [--solver cg|tolerance|exact] [--iterations I] [--repeat R] LEVEL...
//
// Level L has 10 * 4^L + 2 points (8: 655,362; 9: 2,621,442). The targets are the
// sphere's normals tilted by a smooth field, so that the fit moves the surface.
// Prints one markdown row per level: the TriangleMesh build and the fit's
// set-up and solve times (best of R runs), iterations and relative residual.
#include "ScreenedPoissonFit.h"
#include "TriangleMesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

namespace
{
struct Sphere
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
};

Sphere Icosphere(int levels)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Sphere m;
  m.points = { -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, t,
    0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1 };
  m.triangles = { 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10,
    7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6,
    7, 9, 8, 1 };
  for (int level = 0; level < levels; ++level)
  {
    const std::int64_t np = static_cast<std::int64_t>(m.points.size() / 3);
    std::unordered_map<std::int64_t, std::int64_t> midpoints;
    midpoints.reserve(m.triangles.size());
    auto midpoint = [&](std::int64_t a, std::int64_t b) {
      const std::int64_t key = std::min(a, b) * np + std::max(a, b);
      const auto [found, inserted] =
        midpoints.emplace(key, static_cast<std::int64_t>(m.points.size() / 3));
      if (inserted)
      {
        for (int k = 0; k < 3; ++k)
        {
          m.points.push_back(0.5 * (m.points[3 * a + k] + m.points[3 * b + k]));
        }
      }
      return found->second;
    };
    std::vector<std::int64_t> finer;
    finer.reserve(4 * m.triangles.size());
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

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int Usage()
{
  std::fprintf(stderr,
    "usage: fitbench [--threads N] [--solver cg|tolerance|exact] [--iterations I] [--repeat R] "
    "LEVEL...\n");
  return 2;
}
} // namespace

int main(int argc, char** argv)
{
  shock::FitParameters parameters;
  parameters.numberOfThreads = 2;
  int repeat = 3;
  std::vector<int> levels;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
    {
      parameters.numberOfThreads = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--iterations") && i + 1 < argc)
    {
      // The fixed count (cg) or the cap (tolerance).
      parameters.iterations = parameters.maxIterations = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
    {
      repeat = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--solver") && i + 1 < argc)
    {
      const char* name = argv[++i];
      if (!std::strcmp(name, "cg"))
      {
        parameters.solver = shock::FitSolver::ConjugateGradient;
      }
      else if (!std::strcmp(name, "tolerance"))
      {
        parameters.solver = shock::FitSolver::ConjugateGradientTolerance;
      }
      else if (!std::strcmp(name, "exact"))
      {
        parameters.solver = shock::FitSolver::Exact;
      }
      else
      {
        return Usage();
      }
    }
    else if (argv[i][0] != '-')
    {
      levels.push_back(std::atoi(argv[i]));
    }
    else
    {
      return Usage();
    }
  }
  if (levels.empty())
  {
    return Usage();
  }

  std::printf("| level | points | triangles | threads | mesh build (s) | fit set-up (s) | "
              "fit solve (s) | fit total (s) | iterations | residual |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (int level : levels)
  {
    const Sphere sphere = Icosphere(level);
    const shock::TriangleMeshView view{ static_cast<std::int64_t>(sphere.points.size() / 3),
      sphere.points.data(), static_cast<std::int64_t>(sphere.triangles.size() / 3),
      sphere.triangles.data() };
    std::vector<double> positions(sphere.points.size());
    std::vector<double> targets;
    double build = std::numeric_limits<double>::infinity();
    double setup = build, solve = build, total = build;
    shock::FitReport report;
    for (int r = 0; r < repeat; ++r)
    {
      shock::TriangleMesh mesh;
      const auto start = std::chrono::steady_clock::now();
      const shock::Status built = mesh.Build(view, parameters.numberOfThreads);
      build = std::min(build, Seconds(start));
      if (!built.Ok())
      {
        std::fprintf(stderr, "mesh: %s\n", built.error.c_str());
        return 1;
      }
      if (targets.empty())
      {
        for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
        {
          const double* n = mesh.Normal(f);
          const shock::Vec3 c = mesh.Centroid(f);
          const double t[3] = { n[0] + 0.3 * std::sin(9.0 * c[1]), n[1] + 0.3 * std::cos(7.0 * c[2]),
            n[2] + 0.3 * std::sin(11.0 * c[0]) };
          const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
          targets.insert(targets.end(), { t[0] / length, t[1] / length, t[2] / length });
        }
      }
      const auto fitStart = std::chrono::steady_clock::now();
      const shock::Status fitted = shock::FitPositionsToNormals(
        mesh, targets.data(), positions.data(), parameters, &report);
      total = std::min(total, Seconds(fitStart));
      if (!fitted.Ok())
      {
        std::fprintf(stderr, "fit: %s\n", fitted.error.c_str());
        return 1;
      }
      setup = std::min(setup, report.setupSeconds);
      solve = std::min(solve, report.solveSeconds);
    }
    std::printf("| %d | %zu | %zu | %d | %.3f | %.3f | %.3f | %.3f | %d | %.2e |\n", level,
      sphere.points.size() / 3, sphere.triangles.size() / 3, parameters.numberOfThreads, build,
      setup, solve, total, report.iterations, report.residual);
    std::fflush(stdout);
  }
  return 0;
}
