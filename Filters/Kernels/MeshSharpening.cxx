#include "MeshSharpening.h"

#include "SharpFeatures.h"

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
/**
 * The mesh without repeated and degenerate triangles, in `reduced` (all points
 * kept); `kept` lists the triangles kept, `source` maps every triangle to the
 * kept triangle whose result it takes (-1 for degenerate ones). Returns false
 * (nothing built) when every triangle is kept.
 */
bool WithoutRepeatedTriangles(const TriangleMesh& mesh, int threads, TriangleMesh& reduced,
  std::vector<std::int64_t>& source, SharpeningReport& report, Status& status)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  const std::vector<std::int64_t> first = FindRepeatedTriangles(mesh, threads);
  source.assign(static_cast<size_t>(nt), -1);
  std::vector<std::int64_t> corners;
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t original = first[static_cast<size_t>(f)];
    if (original >= 0)
    {
      ++report.repeatedTriangles;
      source[static_cast<size_t>(f)] = source[static_cast<size_t>(original)];
    }
    else if (mesh.Degenerate(f))
    {
      ++report.degenerateTriangles;
    }
    else
    {
      source[static_cast<size_t>(f)] = static_cast<std::int64_t>(corners.size() / 3);
      corners.insert(corners.end(), mesh.Corners(f), mesh.Corners(f) + 3);
    }
  }
  if (report.repeatedTriangles == 0 && report.degenerateTriangles == 0)
  {
    return false;
  }
  TriangleMeshView view;
  view.numberOfPoints = mesh.NumberOfPoints();
  view.points = mesh.NumberOfPoints() > 0 ? mesh.Point(0) : nullptr;
  view.numberOfTriangles = static_cast<std::int64_t>(corners.size() / 3);
  view.triangles = corners.data();
  status = reduced.Build(view, threads);
  return true;
}

/**
 * Shock-filter advection of the face normals `input` into `target` (renormalised),
 * on the mesh split along its feature edges (SharpFeatures) when it has any.
 */
Status AdvectNormals(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  const std::vector<double>& input, std::vector<double>& target, SharpeningReport& r,
  MeshFlowFields* fields, const ProgressFunction& progress, int threads)
{
  const auto splitStart = Clock::now();
  FeatureSplitMesh split;
  const Status splitStatus =
    SplitAtFeatureEdges(mesh, input.data(), parameters.featureAngle, threads, split);
  r.normalsSeconds += SecondsSince(splitStart);
  if (!splitStatus.Ok())
  {
    return splitStatus;
  }
  r.featureEdges = split.featureEdges;
  const TriangleMesh& advected = split.featureEdges > 0 ? split.mesh : mesh;

  MeshSignal signal;
  signal.location = MeshLocation::Triangles;
  signal.components = 3;
  signal.values = input.data();
  signal.valueScale = 2.0; // unit normals: components span [-1, 1]
  signal.sampleAtTimeZero = true;
  signal.lengthScale = parameters.lengthScale > 0.0 ? parameters.lengthScale : mesh.MeanEdgeLength();
  target.resize(input.size());
  const Status status =
    AdvectMeshSignal(advected, signal, target.data(), parameters.advection, &r.advection, fields, progress);
  if (!status.Ok() || r.advection.aborted)
  {
    return status;
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    double* n = &target[static_cast<size_t>(3 * f)];
    if (!Normalise(n))
    {
      std::copy(mesh.Normal(f), mesh.Normal(f) + 3, n); // cancelled average: keep the input normal
    }
  }
  if (fields && split.featureEdges > 0)
  {
    // Potential per original point: the mean over its copies, weighted by their triangles.
    std::vector<double> potential(static_cast<size_t>(mesh.NumberOfPoints()), 0.0);
    std::vector<double> weight(potential.size(), 0.0);
    const CompressedLists& around = advected.PointTriangles();
    for (std::int64_t q = 0; q < advected.NumberOfPoints(); ++q)
    {
      const size_t p = static_cast<size_t>(split.original[static_cast<size_t>(q)]);
      const double count = static_cast<double>(around.End(q) - around.Begin(q));
      potential[p] += count * fields->potential[static_cast<size_t>(q)];
      weight[p] += count;
    }
    for (size_t p = 0; p < potential.size(); ++p)
    {
      potential[p] = weight[p] > 0.0 ? potential[p] / weight[p] : 0.0;
    }
    fields->potential.swap(potential);
  }
  return {};
}

/// SharpenMeshGeometry on a mesh without repeated or degenerate triangles.
Status SharpenCleanMesh(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  double* positions, std::vector<double>& target, SharpeningReport& r, MeshFlowFields* fields,
  const ProgressFunction& progress)
{
  const int threads = ResolveThreadCount(parameters.advection.numberOfThreads);
  const std::int64_t nt = mesh.NumberOfTriangles();
  const auto normalsStart = Clock::now();
  std::vector<double> input(static_cast<size_t>(3 * nt));
  for (std::int64_t f = 0; f < nt; ++f)
  {
    std::copy(mesh.Normal(f), mesh.Normal(f) + 3, &input[static_cast<size_t>(3 * f)]);
  }
  SmoothNormals(mesh, input, parameters.normalSmoothingPasses, threads);
  r.normalsSeconds += SecondsSince(normalsStart);

  const Status advected = AdvectNormals(mesh, parameters, input, target, r, fields, progress, threads);
  if (!advected.Ok() || r.advection.aborted)
  {
    return advected;
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
  if (!(parameters.featureAngle >= 0.0 && parameters.featureAngle <= 180.0))
  {
    return { "the feature angle must be in [0, 180] degrees" };
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
  if (mesh.NumberOfPoints() == 0)
  {
    return {};
  }
  std::copy(mesh.Point(0), mesh.Point(0) + 3 * mesh.NumberOfPoints(), positions);

  // Repeated and degenerate triangles are removed: the result is that of the mesh without them.
  TriangleMesh reduced;
  std::vector<std::int64_t> source;
  Status status;
  const auto cleanStart = Clock::now();
  // (Not for a piece of a distributed fit: its partition numbers the piece's triangles.)
  const bool removed = !parameters.fit.partition &&
    WithoutRepeatedTriangles(mesh, threads, reduced, source, r, status);
  r.normalsSeconds = SecondsSince(cleanStart);
  if (!status.Ok())
  {
    return status;
  }
  const TriangleMesh& clean = removed ? reduced : mesh;
  std::vector<double> target;
  MeshFlowFields cleanFields;
  status = SharpenCleanMesh(clean, parameters, positions, target, r,
    fields ? (removed ? &cleanFields : fields) : nullptr, progress);
  if (!status.Ok() || r.advection.aborted)
  {
    return status;
  }
  if (!removed)
  {
    if (normals)
    {
      std::copy(target.begin(), target.end(), normals);
    }
    return {};
  }
  // Back to the input's triangles: a repeated triangle takes its first occurrence's values.
  const std::int64_t nt = mesh.NumberOfTriangles();
  if (fields)
  {
    fields->potential.swap(cleanFields.potential);
    fields->flow.assign(static_cast<size_t>(3 * nt), 0.0);
  }
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t g = source[static_cast<size_t>(f)];
    for (int k = 0; k < 3; ++k)
    {
      if (normals)
      {
        normals[3 * f + k] = g >= 0 ? target[static_cast<size_t>(3 * g + k)] : 0.0;
      }
      if (fields && g >= 0 && !mesh.Degenerate(f))
      {
        fields->flow[static_cast<size_t>(3 * f + k)] = cleanFields.flow[static_cast<size_t>(3 * g + k)];
      }
    }
  }
  return {};
}

} // namespace shock
