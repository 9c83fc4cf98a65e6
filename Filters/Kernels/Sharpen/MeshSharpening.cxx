#include "MeshSharpening.h"

#include "Timer.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shock
{

namespace
{
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
  const Vec3 a = Load(positions + 3 * t[0]);
  const Vec3 cross =
    Cross(Combine(1.0, Load(positions + 3 * t[1]), -1.0, a), Combine(1.0, Load(positions + 3 * t[2]), -1.0, a));
  std::copy(cross.begin(), cross.end(), n);
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
  // Minima and maxima do not depend on the order: a parallel reduction gives the serial result.
  const double inf = std::numeric_limits<double>::infinity();
  double low0 = inf, low1 = inf, low2 = inf, high0 = -inf, high1 = -inf, high2 = -inf;
  double largest = 0.0;
#pragma omp parallel for num_threads(threads) schedule(static) \
  reduction(min : low0, low1, low2) reduction(max : high0, high1, high2, largest)
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const double* x = mesh.Point(p);
    const double* y = positions + 3 * p;
    low0 = std::min(low0, x[0]);
    low1 = std::min(low1, x[1]);
    low2 = std::min(low2, x[2]);
    high0 = std::max(high0, x[0]);
    high1 = std::max(high1, x[1]);
    high2 = std::max(high2, x[2]);
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      d2 += (y[k] - x[k]) * (y[k] - x[k]);
    }
    largest = std::max(largest, d2);
  }
  const double low[3] = { low0, low1, low2 };
  const double high[3] = { high0, high1, high2 };
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
 * The mesh without repeated and degenerate triangles, into the cache (all
 * points kept): `source` maps every triangle to the kept triangle whose result
 * it takes (-1 for degenerate ones); `removed` is false (nothing built) when
 * every triangle is kept.
 */
Status WithoutRepeatedTriangles(const TriangleMesh& mesh, int threads, SharpeningCache& cache)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  const std::vector<std::int64_t> first = FindRepeatedTriangles(mesh, threads);
  cache.cleaned = true;
  bool any = false;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(|| : any)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    any = any || first[static_cast<size_t>(f)] >= 0 || mesh.Degenerate(f);
  }
  if (!any)
  {
    cache.removed = false; // every triangle kept: nothing to build
    cache.source.clear();
    return {};
  }
  cache.source.assign(static_cast<size_t>(nt), -1);
  std::vector<std::int64_t> corners;
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t original = first[static_cast<size_t>(f)];
    if (original >= 0)
    {
      ++cache.repeatedTriangles;
      cache.source[static_cast<size_t>(f)] = cache.source[static_cast<size_t>(original)];
    }
    else if (mesh.Degenerate(f))
    {
      ++cache.degenerateTriangles;
    }
    else
    {
      cache.source[static_cast<size_t>(f)] = static_cast<std::int64_t>(corners.size() / 3);
      corners.insert(corners.end(), mesh.Corners(f), mesh.Corners(f) + 3);
    }
  }
  cache.removed = cache.repeatedTriangles > 0 || cache.degenerateTriangles > 0;
  if (!cache.removed)
  {
    cache.source.clear();
    return {};
  }
  TriangleMeshView view;
  view.numberOfPoints = mesh.NumberOfPoints();
  view.points = mesh.NumberOfPoints() > 0 ? mesh.Point(0) : nullptr;
  view.numberOfTriangles = static_cast<std::int64_t>(corners.size() / 3);
  view.triangles = corners.data();
  return cache.reduced.Build(view, threads);
}

/// The face normals to advect: the smoothed ones kept in the cache, or the mesh's own.
const double* InputNormals(const TriangleMesh& mesh, const SharpeningCache& cache)
{
  return !cache.normals.empty() ? cache.normals.data()
                                : (mesh.NumberOfTriangles() > 0 ? mesh.Normal(0) : nullptr);
}

/**
 * The face normals of the clean mesh after the smoothing passes, and the mesh
 * split along its feature edges (SharpFeatures), into the cache unless it
 * holds them for these passes and this feature angle.
 */
Status SharpenedNormalsInput(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  int threads, SharpeningCache& cache, SharpeningReport& r)
{
  r.reusedFeatures = cache.smoothingPasses == parameters.normalSmoothingPasses &&
    cache.featureAngle == parameters.featureAngle;
  if (!r.reusedFeatures)
  {
    const auto start = Clock::now();
    cache.smoothingPasses = -1;
    const std::int64_t nt = mesh.NumberOfTriangles();
    cache.normals.clear(); // without smoothing, the mesh's own normals serve (no copy)
    if (parameters.normalSmoothingPasses > 0)
    {
      cache.normals.resize(static_cast<size_t>(3 * nt));
#pragma omp parallel for num_threads(threads) schedule(static)
      for (std::int64_t f = 0; f < nt; ++f)
      {
        std::copy(mesh.Normal(f), mesh.Normal(f) + 3, &cache.normals[static_cast<size_t>(3 * f)]);
      }
      SmoothNormals(mesh, cache.normals, parameters.normalSmoothingPasses, threads);
    }
    const Status split = SplitAtFeatureEdges(
      mesh, InputNormals(mesh, cache), parameters.featureAngle, threads, cache.split);
    r.normalsSeconds += SecondsSince(start);
    if (!split.Ok())
    {
      return split;
    }
    cache.smoothingPasses = parameters.normalSmoothingPasses;
    cache.featureAngle = parameters.featureAngle;
  }
  r.featureEdges = cache.split.featureEdges;
  return {};
}

/// The face normals as the advection's signal (values and length unit not set).
MeshSignal NormalsSignal(const SharpeningParameters& parameters)
{
  MeshSignal signal;
  signal.location = MeshLocation::Triangles;
  signal.components = 3;
  signal.valueScale = 2.0; // unit normals: components span [-1, 1]
  signal.sampleAtTimeZero = true;
  signal.potentialContrast = parameters.curvatureContrast;
  signal.contrastRings = parameters.contrastRings;
  // A corner whose averaged normal is more than the feature angle from one of
  // its faces' normals (a cone's apex) is read per face: unit normals that far
  // apart are 2 sin(angle / 2) apart. FeatureAngle 180 keeps the paper's averages.
  const double pi = 3.14159265358979323846;
  signal.cornerDeviation = parameters.featureAngle > 0.0 && parameters.featureAngle < 180.0
    ? 2.0 * std::sin(parameters.featureAngle * pi / 360.0)
    : 0.0;
  signal.wholeTriangles = parameters.wholeTriangles;
  return signal;
}

/**
 * Shock-filter advection of the (smoothed) face normals `input` into `target`
 * (renormalised). With feature edges, the normals are traced and sampled on
 * the mesh split along them (no trace crosses a sharp crease, no sampled
 * normal averages across one), and their potential and flow are computed on
 * the connected mesh, whose point normals do average across the creases: a
 * crease still sharper than the feature angle with bent faces beside it (a
 * Gaussian blur) is the peak the bent faces' normals flow away from, so its
 * faces take the flat sides' normals, where on the split mesh each side of
 * the crease would carry only its own small bend.
 */
Status AdvectNormals(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  const double* input, const unsigned char* triangleRing, const FeatureSplitMesh& split, ValueVector& target,
  SharpeningReport& r, MeshFlowFields* fields, const ProgressFunction& progress, int threads)
{
  const TriangleMesh& advected = split.featureEdges > 0 ? split.mesh : mesh;
  MeshSignal signal = NormalsSignal(parameters);
  signal.values = input;
  signal.lengthScale = parameters.lengthScale > 0.0 ? parameters.lengthScale : mesh.MeanEdgeLength();
  signal.triangleRing = triangleRing; // the split keeps the triangles and their order
  signal.flowMesh = &mesh;             // the flow of the connected mesh (this mesh's when not split)
  target.resize(static_cast<size_t>(3 * mesh.NumberOfTriangles())); // written in full by the advection
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
  return {};
}

/// A flow this small (normalised units: unit-range values, mean edge lengths)
/// is zero up to the rounding of the potential's differences: the triangle does not move.
constexpr double StillFlow = 1e-12;

/**
 * A triangle on which the fixed flow is zero (below StillFlow) is not moved
 * by the advection (its trace stays at its centre), nor is any at time 0: it
 * keeps its own normal, not the interpolated average of the point normals its
 * centre samples (SharpeningParameters::keepUnmovedNormals).
 */
void KeepUnmovedNormals(const TriangleMesh& mesh, const MeshFlowFields& fields, bool timeZero,
  ValueVector& target, int threads)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  const bool flowKnown = fields.flow.size() == static_cast<size_t>(3 * nt);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const double* u = flowKnown ? &fields.flow[static_cast<size_t>(3 * f)] : nullptr;
    if (timeZero || (u && Dot(Load(u), Load(u)) <= StillFlow * StillFlow))
    {
      std::copy(mesh.Normal(f), mesh.Normal(f) + 3, &target[static_cast<size_t>(3 * f)]);
    }
  }
}

/**
 * SharpenMeshGeometry on a mesh without repeated or degenerate triangles.
 * `keepFeatures`: the cache outlives the run (a caller's), so the smoothed
 * normals and the feature split stay in it for the next run; otherwise they
 * are released once the normals are advected, before the fit allocates its
 * system (the split is a second copy of the mesh's connectivity).
 */
Status SharpenCleanMesh(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  const unsigned char* triangleRing, double* positions, ValueVector& target, SharpeningReport& r,
  MeshFlowFields* fields, const ProgressFunction& progress, SharpeningCache& cache, bool keepFeatures)
{
  const int threads = ThreadsForWork(parameters.advection.numberOfThreads, mesh.NumberOfTriangles());
  Status status = SharpenedNormalsInput(mesh, parameters, threads, cache, r);
  // The flow tells which triangles the advection did not move (a fixed flow only).
  const bool keepUnmoved = parameters.keepUnmovedNormals && parameters.advection.flowMode == FlowMode::Fixed;
  MeshFlowFields ownFields;
  MeshFlowFields* used = fields ? fields : (keepUnmoved ? &ownFields : nullptr);
  if (status.Ok())
  {
    status = AdvectNormals(mesh, parameters, InputNormals(mesh, cache), triangleRing, cache.split, target, r,
      used, progress, threads);
  }
  if (status.Ok() && keepUnmoved && !r.advection.aborted)
  {
    KeepUnmovedNormals(mesh, *used, !(parameters.advection.time > 0.0), target, threads);
    ownFields = MeshFlowFields(); // released before the fit
  }
  const MeshPartition* partition = parameters.fit.partition;
  if (partition && partition->anyStopped &&
    partition->anyStopped(!status.Ok() || r.advection.aborted, r.advection.deepestRing) && status.Ok())
  {
    r.advection.aborted = true; // another piece stopped: this one stops with it
  }
  if (!status.Ok() || r.advection.aborted)
  {
    return status;
  }
  if (!keepFeatures)
  {
    cache.split = FeatureSplitMesh();
    cache.normals = std::vector<double>();
    cache.smoothingPasses = -1; // nothing kept for these passes and this angle
    cache.featureAngle = -1.0;
  }
  FitParameters fit = parameters.fit;
  fit.numberOfThreads = parameters.advection.numberOfThreads;
  status = FitPositionsToNormals(mesh, target.data(), positions, fit, &r.fit, &cache.fit);
  if (!status.Ok())
  {
    return status;
  }
  Measure(mesh, positions, fit.partition, threads, r);
  return {};
}

/// The normals and fields of the clean mesh back on the input's triangles (a repeat takes its first's).
void ToInputTriangles(const TriangleMesh& mesh, const SharpeningCache& cache,
  const ValueVector& target, MeshFlowFields& cleanFields, double* normals,
  MeshFlowFields* fields)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  if (fields)
  {
    fields->potential.swap(cleanFields.potential);
    fields->flow.assign(static_cast<size_t>(3 * nt), 0.0);
  }
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t g = cache.source[static_cast<size_t>(f)];
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
}

Status CheckSharpeningParameters(const SharpeningParameters& parameters)
{
  if (parameters.normalSmoothingPasses < 0)
  {
    return { "the number of normal smoothing passes must be >= 0" };
  }
  if (!(parameters.featureAngle >= 0.0 && parameters.featureAngle <= 180.0))
  {
    return { "the feature angle must be in [0, 180] degrees" };
  }
  if (!(parameters.curvatureContrast >= 0.0) || !std::isfinite(parameters.curvatureContrast) ||
    parameters.contrastRings < 1)
  {
    return { "the curvature contrast must be finite and >= 0, over >= 1 rings" };
  }
  return CheckAdvectionParameters(parameters.advection);
}
} // namespace

int SharpeningStencilRings(const SharpeningParameters& parameters)
{
  const int advection = MeshStencilRings(NormalsSignal(parameters), parameters.advection);
  return advection < 0 ? -1 : std::max(0, parameters.normalSmoothingPasses) + advection;
}

Status SharpenMeshGeometry(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  double* positions, double* normals, SharpeningReport* report, MeshFlowFields* fields,
  const ProgressFunction& progress, SharpeningCache* cache)
{
  if (!positions)
  {
    return { "the output positions must not be null" };
  }
  Status status = CheckSharpeningParameters(parameters);
  if (!status.Ok())
  {
    return status;
  }
  SharpeningReport localReport;
  SharpeningReport& r = report ? *report : localReport;
  r = SharpeningReport();
  if (mesh.NumberOfPoints() == 0)
  {
    return {};
  }
  // The fit writes every position; a run that stops before it ends or fails gives the input's.
  auto keepInput = [&]() {
    std::copy(mesh.Point(0), mesh.Point(0) + 3 * mesh.NumberOfPoints(), positions);
  };

  // Repeated and degenerate triangles are removed: the result is that of the mesh without
  // them. (Not for a piece of a distributed fit: its partition numbers the piece's triangles.)
  SharpeningCache localCache;
  SharpeningCache& kept = cache && !parameters.fit.partition ? *cache : localCache;
  r.reusedMesh = kept.cleaned;
  if (!kept.cleaned && !parameters.fit.partition)
  {
    const auto cleanStart = Clock::now();
    status = WithoutRepeatedTriangles(mesh, ResolveThreadCount(parameters.advection.numberOfThreads), kept);
    r.normalsSeconds = SecondsSince(cleanStart);
    if (!status.Ok())
    {
      kept.Clear();
      keepInput();
      return status;
    }
  }
  r.repeatedTriangles = kept.repeatedTriangles;
  r.degenerateTriangles = kept.degenerateTriangles;
  const TriangleMesh& clean = kept.removed ? kept.reduced : mesh;
  // A kept triangle is in the lowest ring of the triangles it stands for.
  std::vector<unsigned char> cleanRing;
  if (parameters.triangleRing && kept.removed)
  {
    cleanRing.assign(static_cast<size_t>(clean.NumberOfTriangles()), std::numeric_limits<unsigned char>::max());
    for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
    {
      const std::int64_t g = kept.source[static_cast<size_t>(f)];
      if (g >= 0)
      {
        cleanRing[static_cast<size_t>(g)] = std::min(cleanRing[static_cast<size_t>(g)], parameters.triangleRing[f]);
      }
    }
  }
  const unsigned char* rings = cleanRing.empty() ? parameters.triangleRing : cleanRing.data();
  ValueVector target;
  MeshFlowFields cleanFields;
  status = SharpenCleanMesh(clean, parameters, rings, positions, target, r,
    fields ? (kept.removed ? &cleanFields : fields) : nullptr, progress, kept, &kept != &localCache);
  if (!status.Ok() || r.advection.aborted)
  {
    keepInput();
    return status;
  }
  if (kept.removed)
  {
    ToInputTriangles(mesh, kept, target, cleanFields, normals, fields);
  }
  else if (normals)
  {
    std::copy(target.begin(), target.end(), normals);
  }
  return {};
}

} // namespace shock
