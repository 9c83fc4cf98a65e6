#include "MeshSharpening.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace shock
{

namespace
{
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Normalise v in place; false (v unchanged) when its length is zero or not finite.
bool Normalise(double* v)
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0.0) || !std::isfinite(n))
  {
    return false;
  }
  v[0] /= n;
  v[1] /= n;
  v[2] /= n;
  return true;
}

/// Laplacian smoothing of face normals over edge neighbours, area-weighted, positions fixed.
void SmoothNormals(const TriangleMesh& mesh, std::vector<double>& normals, int passes, int threads)
{
  std::vector<double> smoothed(normals.size());
  for (int pass = 0; pass < passes; ++pass)
  {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
    {
      double* out = &smoothed[static_cast<size_t>(3 * f)];
      const double* self = &normals[static_cast<size_t>(3 * f)];
      std::copy(self, self + 3, out);
      if (mesh.Degenerate(f))
      {
        continue;
      }
      for (int k = 0; k < 3; ++k)
      {
        out[k] *= mesh.Area(f);
      }
      for (int e = 0; e < 3; ++e)
      {
        const std::int64_t g = mesh.Neighbour(f, e);
        if (g >= 0)
        {
          for (int k = 0; k < 3; ++k)
          {
            out[k] += mesh.Area(g) * normals[static_cast<size_t>(3 * g + k)];
          }
        }
      }
      if (!Normalise(out))
      {
        std::copy(self, self + 3, out); // opposite neighbours cancelled: keep the normal
      }
    }
    normals.swap(smoothed);
  }
}

/// Unit normal of triangle f with the given positions; zero when degenerate there.
void TriangleNormal(const TriangleMesh& mesh, const double* positions, std::int64_t f, double* n)
{
  const std::int64_t* t = mesh.Corners(f);
  const double* a = positions + 3 * t[0];
  const double* b = positions + 3 * t[1];
  const double* c = positions + 3 * t[2];
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  if (!Normalise(n))
  {
    n[0] = n[1] = n[2] = 0.0;
  }
}

/// Flipped triangles and the largest displacement relative to the bounding-box diagonal.
void Measure(const TriangleMesh& mesh, const double* positions, const MeshPartition* partition,
  int threads, SharpeningReport& report)
{
  std::int64_t flipped = 0;
#pragma omp parallel for num_threads(threads) reduction(+ : flipped) schedule(static)
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    if (mesh.Degenerate(f) || (partition && !partition->ownedTriangles[static_cast<size_t>(f)]))
    {
      continue;
    }
    double n[3];
    TriangleNormal(mesh, positions, f, n);
    const double* before = mesh.Normal(f);
    flipped += (n[0] * before[0] + n[1] * before[1] + n[2] * before[2] <= 0.0) ? 1 : 0;
  }
  double low[3], high[3];
  std::fill(low, low + 3, std::numeric_limits<double>::infinity());
  std::fill(high, high + 3, -std::numeric_limits<double>::infinity());
  double largest = 0.0;
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const double* x = mesh.Point(p);
    const double* y = positions + 3 * p;
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      low[k] = std::min(low[k], x[k]);
      high[k] = std::max(high[k], x[k]);
      d2 += (y[k] - x[k]) * (y[k] - x[k]);
    }
    largest = std::max(largest, d2);
  }
  double diagonal2 = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    diagonal2 += mesh.NumberOfPoints() > 0 ? (high[k] - low[k]) * (high[k] - low[k]) : 0.0;
  }
  if (partition)
  {
    double count = static_cast<double>(flipped);
    partition->globalSum(&count, 1); // the displacement stays the piece's own
    flipped = static_cast<std::int64_t>(count);
  }
  report.flippedTriangles = flipped;
  report.maxDisplacement = diagonal2 > 0.0 ? std::sqrt(largest / diagonal2) : 0.0;
}
} // namespace

Status SharpenMeshGeometry(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  double* positions, double* normals, SharpeningReport* report, MeshFlowFields* fields,
  const ProgressFunction& progress)
{
  if (!positions)
  {
    return { "the output positions must not be null" };
  }
  if (parameters.normalSmoothingPasses < 0)
  {
    return { "the number of normal smoothing passes must be >= 0" };
  }
  const Status valid = CheckAdvectionParameters(parameters.advection);
  if (!valid.Ok())
  {
    return valid;
  }
  SharpeningReport localReport;
  SharpeningReport& r = report ? *report : localReport;
  r = SharpeningReport();
  const int threads = ResolveThreadCount(parameters.advection.numberOfThreads);
  const std::int64_t nt = mesh.NumberOfTriangles();
  if (mesh.NumberOfPoints() == 0)
  {
    return {};
  }
  std::copy(mesh.Point(0), mesh.Point(0) + 3 * mesh.NumberOfPoints(), positions);

  const auto normalsStart = Clock::now();
  std::vector<double> input(static_cast<size_t>(3 * nt));
  for (std::int64_t f = 0; f < nt; ++f)
  {
    std::copy(mesh.Normal(f), mesh.Normal(f) + 3, &input[static_cast<size_t>(3 * f)]);
  }
  SmoothNormals(mesh, input, parameters.normalSmoothingPasses, threads);
  r.normalsSeconds = SecondsSince(normalsStart);

  MeshSignal signal;
  signal.location = MeshLocation::Triangles;
  signal.components = 3;
  signal.values = input.data();
  signal.valueScale = 2.0; // unit normals: components span [-1, 1]
  signal.lengthScale = parameters.lengthScale;
  signal.sampleAtTimeZero = true;
  std::vector<double> target(input.size());
  const Status advected =
    AdvectMeshSignal(mesh, signal, target.data(), parameters.advection, &r.advection, fields, progress);
  if (!advected.Ok())
  {
    return advected;
  }
  if (r.advection.aborted)
  {
    return {};
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    double* n = &target[static_cast<size_t>(3 * f)];
    if (!Normalise(n))
    {
      std::copy(mesh.Normal(f), mesh.Normal(f) + 3, n); // cancelled average: keep the input normal
    }
  }
  if (normals)
  {
    std::copy(target.begin(), target.end(), normals);
  }

  FitParameters fit = parameters.fit;
  fit.numberOfThreads = parameters.advection.numberOfThreads;
  const Status fitted = FitPositionsToNormals(mesh, target.data(), positions, fit, &r.fit);
  if (!fitted.Ok())
  {
    std::copy(mesh.Point(0), mesh.Point(0) + 3 * mesh.NumberOfPoints(), positions);
    return fitted;
  }
  Measure(mesh, positions, fit.partition, threads, r);
  return {};
}

} // namespace shock
