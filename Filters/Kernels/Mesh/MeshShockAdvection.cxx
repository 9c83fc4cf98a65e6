#include "MeshShockAdvection.h"
#include "MeshAdvect.h"
#include "MeshFlow.h"
#include "Timer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace shock
{

namespace
{

/// Everything one run needs, in normalised units, derived once from mesh and signal.
struct MeshRun
{
  const TriangleMesh& mesh;
  const MeshSignal& signal;
  const AdvectionParameters& p;
  int C;
  int threads;
  double length = 0.0; // length unit: the signal's lengthScale or the mean edge length
  double range = 0.0;
  double low = 0.0, high = 0.0; ///< the finite values' extremes
  std::vector<unsigned char> validPoint;    // point has a finite value (or, for cells, a finite neighbour)
  std::vector<unsigned char> validTriangle; // non-degenerate, finite corners (and value): carries flow
  ValueVector umbrellaWeight;               // per one-ring entry, exp(-|(v-w)/l|^2)
  std::vector<unsigned char> cellValid;     // cell signals: the triangle's value is finite

  std::int64_t Points() const { return this->mesh.NumberOfPoints(); }
  std::int64_t Triangles() const { return this->mesh.NumberOfTriangles(); }
  bool CellSignal() const { return this->signal.location == MeshLocation::Triangles; }

  /// Per-point values of a signal: itself, or a cell signal's area-weighted averages.
  std::vector<double> PointValues(const double* values) const
  {
    if (!this->CellSignal())
    {
      return std::vector<double>(values, values + this->Points() * this->C);
    }
    std::vector<double> points;
    TrianglesToPoints(this->mesh, this->C, values, this->cellValid, points, this->threads);
    return points;
  }

  /// What advection reads from `values` (with `points` its per-point values, `own` its corners read per triangle).
  MeshSource Source(const double* values, const std::vector<double>& points,
    const std::vector<unsigned char>& own) const
  {
    return { this->C, this->CellSignal() ? points.data() : values, this->CellSignal() ? values : nullptr,
      this->validPoint.data(), this->CellSignal() && !own.empty() ? own.data() : nullptr };
  }

  /**
   * A cell signal's points whose average `points` differs from one of their
   * valid triangles' `values` by more than signal.cornerDeviation (empty when
   * that is 0, or for a point signal).
   */
  std::vector<unsigned char> OwnCorners(const double* values, const std::vector<double>& points) const
  {
    const double most = this->signal.cornerDeviation;
    if (!this->CellSignal() || !(most > 0.0))
    {
      return {};
    }
    std::vector<unsigned char> own(static_cast<size_t>(this->Points()), 0);
    const CompressedLists& around = this->mesh.PointTriangles();
    const int C = this->C;
#pragma omp parallel for num_threads(this->threads) schedule(static)
    for (std::int64_t p = 0; p < this->Points(); ++p)
    {
      const double* average = points.data() + p * C;
      for (std::int64_t i = around.Begin(p); i < around.End(p) && !own[static_cast<size_t>(p)]; ++i)
      {
        const std::int64_t f = around.items[static_cast<size_t>(i)];
        if (!this->cellValid[static_cast<size_t>(f)])
        {
          continue;
        }
        double squared = 0.0;
        for (int c = 0; c < C; ++c)
        {
          const double d = values[f * C + c] - average[c];
          squared += d * d;
        }
        own[static_cast<size_t>(p)] = squared > most * most ? 1 : 0;
      }
    }
    return own;
  }
};

/**
 * Flow of a range-normalised point signal: smoothing, potential (|grad I|^2
 * summed over channels, area-averaged to points, smoothed), u = 1/2 grad P.
 * Returns the potential; `flow` receives u per triangle (normalised units).
 */
std::vector<double> ComputeFlow(const MeshRun& run, std::vector<double> signal, ValueVector& flow)
{
  UmbrellaSmooth(run.mesh, run.umbrellaWeight, run.validPoint, run.C, signal, run.p.smoothingPasses,
    run.threads);
  const ValueVector energy =
    TriangleEnergy(run.mesh, signal.data(), run.C, run.validTriangle, run.length, run.threads);
  std::vector<double> potential;
  TrianglesToPoints(run.mesh, 1, energy.data(), run.validTriangle, potential, run.threads);
  CurvatureContrast(run.mesh, run.validPoint, potential, run.signal.potentialContrast,
    run.signal.contrastRings, run.threads);
  UmbrellaSmooth(run.mesh, run.umbrellaWeight, run.validPoint, 1, potential,
    run.p.smoothingPasses, run.threads);
  flow = TriangleFlow(run.mesh, potential, run.validTriangle, run.length, run.threads);
  return potential;
}

/**
 * The flow of `current` (one update): fills the back-trace velocity -l u, returns the potential.
 * `currentPoints`, when not empty, holds the per-point values of a cell signal
 * `current` (taken: a caller that keeps them passes a copy). `flow`, when not
 * null, receives u itself (the velocity is made from u in place: one array
 * per triangle, not two, unless u is asked for).
 */
std::vector<double> UpdateFlow(const MeshRun& run, const double* current,
  std::vector<double> currentPoints, std::vector<double>* flow, ValueVector& velocity)
{
  std::vector<double> normalised =
    !currentPoints.empty() && run.CellSignal() ? std::move(currentPoints) : run.PointValues(current);
  const double range = run.range;
  const auto n = static_cast<std::int64_t>(normalised.size());
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
  {
    normalised[static_cast<size_t>(i)] /= range;
  }
  std::vector<double> potential = ComputeFlow(run, std::move(normalised), velocity);
  if (flow)
  {
    flow->assign(velocity.begin(), velocity.end());
  }
  // Back-trace velocity in world units per unit normalised time: -u scaled by l-bar.
  const double l = run.length;
  const auto m = static_cast<std::int64_t>(velocity.size());
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t i = 0; i < m; ++i)
  {
    velocity[static_cast<size_t>(i)] = -l * velocity[static_cast<size_t>(i)];
  }
  return potential;
}

/// AdvectVertices or AdvectFaces, as the signal's location asks.
bool Advect(AdvectionPass& pass, const MeshRun& run, const MeshSource& source, double* out,
  std::vector<SurfacePoint>* positions)
{
  return run.CellSignal() ? AdvectFaces(pass, source, out, positions)
                          : AdvectVertices(pass, source, out, positions);
}

/// Validity masks and range; returns false when there is nothing to filter.
bool Prepare(MeshRun& run)
{
  const TriangleMesh& mesh = run.mesh;
  const int C = run.C;
  const double* values = run.signal.values;
  const std::int64_t count = run.CellSignal() ? run.Triangles() : run.Points();
  std::vector<unsigned char> finite(static_cast<size_t>(count));
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
#pragma omp parallel for num_threads(run.threads) reduction(min : low) reduction(max : high)
  for (std::int64_t i = 0; i < count; ++i)
  {
    finite[static_cast<size_t>(i)] = AllFinite(values + i * C, C) ? 1 : 0;
    if (finite[static_cast<size_t>(i)])
    {
      for (int c = 0; c < C; ++c)
      {
        low = std::min(low, values[i * C + c]);
        high = std::max(high, values[i * C + c]);
      }
    }
  }
  run.low = low;
  run.high = high;
  run.range = run.signal.valueScale > 0.0 ? run.signal.valueScale : high - low;
  run.length = run.signal.lengthScale > 0.0 ? run.signal.lengthScale : mesh.MeanEdgeLength();
  if (!(run.range > 0.0) || !std::isfinite(run.range) || !(run.length > 0.0))
  {
    return false; // constant or entirely non-finite signal, or no edges: no flow
  }

  if (run.CellSignal())
  {
    run.validPoint.assign(static_cast<size_t>(run.Points()), 0);
    const CompressedLists& around = mesh.PointTriangles();
#pragma omp parallel for num_threads(run.threads) schedule(static)
    for (std::int64_t p = 0; p < run.Points(); ++p)
    {
      for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
      {
        const std::int64_t f = around.items[static_cast<size_t>(k)];
        if (!mesh.Degenerate(f) && finite[static_cast<size_t>(f)])
        {
          run.validPoint[static_cast<size_t>(p)] = 1;
          break;
        }
      }
    }
  }
  else
  {
    run.validPoint = finite;
  }
  run.validTriangle.assign(static_cast<size_t>(run.Triangles()), 0);
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t f = 0; f < run.Triangles(); ++f)
  {
    const std::int64_t* t = mesh.Corners(f);
    bool valid = !mesh.Degenerate(f) && (!run.CellSignal() || finite[static_cast<size_t>(f)]);
    for (int k = 0; k < 3 && valid; ++k)
    {
      valid = run.validPoint[static_cast<size_t>(t[k])] != 0;
    }
    run.validTriangle[static_cast<size_t>(f)] = valid ? 1 : 0;
  }
  return true;
}

/// The umbrella weights of the run whose mesh the flow is computed on (ComputeFlow's smoothing).
void PrepareSmoothing(MeshRun& run)
{
  run.umbrellaWeight = UmbrellaWeights(run.mesh, run.length, run.threads);
}

/// The state of a multi-step run: the signal the next flow is computed from.
struct MeshSteps
{
  std::vector<double> current;
  std::vector<double> next;                 // Naive: the resampled signal
  std::vector<SurfacePoint> positions;      // Composed: the composed back-traces
  std::vector<double> inputPoints;          // per-point values of the input (cell signals)
  std::vector<unsigned char> ownCorners;    // the input's corners read per triangle (advected cell signals; every update reads them)
};

/// One advection pass of flow update k; false when aborted.
bool AdvectStep(const MeshRun& run, MeshSteps& steps, AdvectionPass& pass, double* output)
{
  const double* input = run.signal.values;
  const MeshSource fromInput = run.Source(input, steps.inputPoints, steps.ownCorners);
  switch (run.p.flowMode)
  {
    case FlowMode::Fixed:
      return Advect(pass, run, fromInput, output, nullptr);
    case FlowMode::Composed:
      return Advect(pass, run, fromInput, steps.current.data(), &steps.positions);
    case FlowMode::Naive:
    default:
    {
      const std::vector<double> currentPoints =
        run.CellSignal() ? run.PointValues(steps.current.data()) : std::vector<double>();
      const bool completed =
        Advect(pass, run, run.Source(steps.current.data(), currentPoints, steps.ownCorners), steps.next.data(),
          nullptr);
      steps.current.swap(steps.next);
      return completed;
    }
  }
}

/// The output is the input: the copy when no advection pass wrote it whole.
void KeepTheInput(const MeshRun& run, double* output)
{
  const std::int64_t count = (run.CellSignal() ? run.Triangles() : run.Points()) * run.C;
  const double* input = run.signal.values;
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t i = 0; i < count; ++i)
  {
    output[i] = input[i];
  }
}

/**
 * The state the updates start from (the current signal, the resampled one, the
 * composed back-traces, the input's per-point values) and, for a cell signal,
 * which cells have a finite value (run.cellValid).
 */
MeshSteps StartSteps(MeshRun& run, bool advect)
{
  const AdvectionParameters& p = run.p;
  const std::int64_t count = (run.CellSignal() ? run.Triangles() : run.Points()) * run.C;
  const double* input = run.signal.values;
  MeshSteps steps;
  // The fixed flow reads only the input: no copy of it as the current signal.
  const bool fixed = p.flowMode == FlowMode::Fixed;
  if (!fixed)
  {
    steps.current.assign(input, input + count);
  }
  steps.next.resize(p.flowMode == FlowMode::Naive ? count : 0);
  if (p.flowMode == FlowMode::Composed && advect)
  {
    steps.positions = InitialPositions(run.mesh, run.CellSignal());
  }
  if (run.CellSignal())
  {
    run.cellValid.resize(static_cast<size_t>(run.Triangles()));
#pragma omp parallel for num_threads(run.threads) schedule(static)
    for (std::int64_t f = 0; f < run.Triangles(); ++f)
    {
      run.cellValid[static_cast<size_t>(f)] = AllFinite(input + f * run.C, run.C) ? 1 : 0;
    }
    steps.inputPoints = run.PointValues(input);
    if (advect)
    {
      steps.ownCorners = run.OwnCorners(input, steps.inputPoints); // read by the samples only
    }
  }
  return steps;
}

/**
 * The flow updates, each followed by its advection pass (none when `advect`
 * is false); sets report.aborted when the progress callback or a pass aborts.
 */
void RunUpdates(const MeshRun& run, MeshSteps& steps, const MeshRun* flowRun, MeshSteps& flowSteps,
  bool advect, double* output, AdvectionReport& report, MeshFlowFields* fields,
  const ProgressFunction& progress)
{
  const AdvectionParameters& p = run.p;
  const TriangleMesh& mesh = run.mesh;
  const bool fixed = p.flowMode == FlowMode::Fixed;
  const int updates = fixed ? 1 : std::max(1, p.flowUpdates);
  ValueVector velocity; // written whole by every flow update
  const std::int64_t traces = run.CellSignal() ? run.Triangles()
                                               : static_cast<std::int64_t>(mesh.PointTriangles().items.size());
  const int traceThreads = ThreadsForWork(p.numberOfThreads, traces);
  for (int k = 0; k < updates; ++k)
  {
    const auto flowStart = Clock::now();
    // The first update of every mode starts from the input, whose per-point values are at hand.
    const double* current = fixed ? run.signal.values : steps.current.data();
    // The last update's u goes to the fields, when asked for.
    std::vector<double>* flow = fields && k == updates - 1 ? &fields->flow : nullptr;
    // The flow mesh's per-point values serve this update only (taken); the advected
    // mesh's are read again by the samples (copied).
    std::vector<double> potential = flowRun
      ? UpdateFlow(*flowRun, current, k == 0 ? std::move(flowSteps.inputPoints) : std::vector<double>(), flow,
          velocity)
      : UpdateFlow(run, current, k == 0 ? steps.inputPoints : std::vector<double>(), flow, velocity);
    report.flowSeconds += SecondsSince(flowStart);
    if (flow)
    {
      fields->potential = std::move(potential);
    }
    const double progressStart = (k + 0.1) / updates;
    if (progress && !progress(progressStart))
    {
      report.aborted = true;
      break;
    }
    if (!advect)
    {
      continue;
    }
    const auto advectStart = Clock::now();
    const SurfaceTracer tracer(mesh, velocity.data(), p, run.length, run.signal.wholeTriangles);
    AdvectionPass pass{ mesh, tracer, p.time / updates, p.sampling, traceThreads, progress,
      progressStart, 0.9 / updates, report, run.signal.triangleRing };
    const bool completed = AdvectStep(run, steps, pass, output);
    report.advectionSeconds += SecondsSince(advectStart);
    if (!completed)
    {
      report.aborted = true;
      break;
    }
  }
}

/// The run: preparation, the state of the steps, the updates, and the output.
Status RunMesh(const TriangleMesh& mesh, const MeshSignal& signal, double* output,
  const AdvectionParameters& p, AdvectionReport& report, MeshFlowFields* fields,
  const ProgressFunction& progress)
{
  // Threads by work size: a small mesh is not slower on more threads.
  MeshRun run{ mesh, signal, p, signal.components,
    ThreadsForWork(p.numberOfThreads, std::max(mesh.NumberOfPoints(), mesh.NumberOfTriangles())) };
  if (fields)
  {
    // Per point of the mesh the flow is computed on.
    const std::int64_t flowPoints = signal.flowMesh ? signal.flowMesh->NumberOfPoints() : run.Points();
    fields->potential.assign(static_cast<size_t>(flowPoints), 0.0);
    fields->flow.assign(static_cast<size_t>(3 * run.Triangles()), 0.0);
  }
  const auto setupStart = Clock::now();
  if (!Prepare(run))
  {
    if (run.range == std::numeric_limits<double>::infinity())
    {
      return { ValueSpanError(run.low, run.high) };
    }
    KeepTheInput(run, output);
    return {};
  }
  report.flowSeconds += SecondsSince(setupStart);

  const bool advect = p.time > 0.0 || signal.sampleAtTimeZero; // t = 0: the input, exactly
  MeshSteps steps = StartSteps(run, advect);
  // The flow on another mesh with the same triangles (signal.flowMesh): its own
  // validity, range and per-point values of the input.
  std::unique_ptr<MeshRun> flowRun;
  MeshSteps flowSteps;
  if (signal.flowMesh && signal.flowMesh != &mesh)
  {
    flowRun.reset(new MeshRun{ *signal.flowMesh, signal, p, signal.components, run.threads });
    if (Prepare(*flowRun))
    {
      flowSteps = StartSteps(*flowRun, false);
    }
    else
    {
      flowRun.reset(); // nothing carries flow there: the mesh's own flow
    }
  }
  // Only the mesh the flow is computed on smooths: the advected mesh's weights
  // are not made when another mesh carries the flow.
  const auto smoothingStart = Clock::now();
  PrepareSmoothing(flowRun ? *flowRun : run);
  report.flowSeconds += SecondsSince(smoothingStart);
  RunUpdates(run, steps, flowRun.get(), flowSteps, advect, output, report, fields, progress);
  if (report.aborted || !advect)
  {
    KeepTheInput(run, output);
  }
  else if (p.flowMode != FlowMode::Fixed)
  {
    std::copy(steps.current.begin(), steps.current.end(), output);
  }
  return {};
}

} // namespace

int MeshStencilRings(const MeshSignal& signal, const AdvectionParameters& parameters)
{
  if (parameters.flowMode != FlowMode::Fixed && parameters.flowUpdates > 1)
  {
    return -1;
  }
  // Each step of ComputeFlow that reads a point's one-ring (MeshFlow.h) makes
  // a value exact one ring less deep: on a piece with R rings, a point whose
  // nearest triangle is of ring j has its whole one-ring when j < R, so after
  // such a step the points with j <= X - 1 are exact where those with j <= X
  // were before, and a triangle of ring k (its corners: j <= k) is exact when
  // its corners are. The steps: a cell signal's average to the points, the
  // signal's smoothing passes, the potential's average to the points, the
  // contrast's rings, the potential's smoothing passes.
  const int passes = std::max(0, parameters.smoothingPasses);
  const int contrast = signal.potentialContrast > 0.0 ? std::max(1, signal.contrastRings) : 0;
  const int cells = signal.location == MeshLocation::Triangles ? 1 : 0;
  return cells + passes + 1 + contrast + passes;
}

Status AdvectMeshSignal(const TriangleMesh& mesh, const MeshSignal& signal, double* output,
  const AdvectionParameters& parameters, AdvectionReport* report, MeshFlowFields* fields,
  const ProgressFunction& progress)
{
  const Status valid = CheckAdvectionParameters(parameters);
  if (!valid.Ok())
  {
    return valid;
  }
  if (signal.components < 1)
  {
    return { "the signal needs at least one component" };
  }
  const std::int64_t count =
    signal.location == MeshLocation::Triangles ? mesh.NumberOfTriangles() : mesh.NumberOfPoints();
  if ((count > 0 && (!signal.values || !output)) || (count > 0 && signal.values == output))
  {
    return { "input and output must be distinct, non-null buffers" };
  }
  if (!(signal.valueScale >= 0.0) || !std::isfinite(signal.valueScale) ||
    !(signal.lengthScale >= 0.0) || !std::isfinite(signal.lengthScale))
  {
    return { "the value and length scales must be finite and >= 0" };
  }
  if (!(signal.potentialContrast >= 0.0) || !std::isfinite(signal.potentialContrast) ||
    signal.contrastRings < 1)
  {
    return { "the potential's contrast must be finite and >= 0, over >= 1 rings" };
  }
  AdvectionReport localReport;
  AdvectionReport& r = report ? *report : localReport;
  r = AdvectionReport();
  return RunMesh(mesh, signal, output, parameters, r, fields, progress);
}

} // namespace shock
