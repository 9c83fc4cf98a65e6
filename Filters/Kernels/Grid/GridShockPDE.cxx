#include "GridShockPDE.h"
#include "GridFlow.h"
#include "Timer.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

namespace shock
{

namespace
{
using namespace grid;

// A step that changes no value by more than this (range-normalised) is a steady state.
constexpr double SteadyChange = 1e-12;

double MinMod(double a, double b)
{
  if (a > 0.0 && b > 0.0)
  {
    return std::min(a, b);
  }
  if (a < 0.0 && b < 0.0)
  {
    return std::max(a, b);
  }
  return 0.0;
}

/**
 * One explicit Osher-Rudin step on a range-normalised signal: state -> next.
 * Returns the largest change of a value.
 */
template <int D>
class PDEStep
{
public:
  PDEStep(const Lattice<D>& lattice, int components, const unsigned char* validSample,
    const unsigned char* validFace, int threads)
    : L(lattice)
    , C(components)
    , ValidSample(validSample)
    , ValidFace(validFace)
    , Threads(threads)
  {
  }

  /**
   * The CFL speed bound max_faces |u| x sum_d 1/h_d, in samples per unit time;
   * `velocity` is the back-trace velocity -u/h per face (index units).
   */
  double SpeedBound(const float* velocity) const
  {
    double largest = 0.0;
#pragma omp parallel for schedule(static) num_threads(this->Threads) reduction(max : largest)
    for (std::int64_t f = 0; f < L.numFaces; ++f)
    {
      double norm2 = 0.0;
      for (int d = 0; d < D; ++d)
      {
        const double u = static_cast<double>(velocity[f * D + d]) * L.h[d];
        norm2 += u * u;
      }
      largest = std::max(largest, norm2);
    }
    double inverseSpacings = 0.0;
    for (int d = 0; d < D; ++d)
    {
      inverseSpacings += 1.0 / L.h[d];
    }
    return std::sqrt(largest) * inverseSpacings;
  }

  double Apply(const float* velocity, double dt, const double* state, double* next) const
  {
    double largestChange = 0.0;
    const RowBlocks<D> blocks(L.n);
#pragma omp parallel for schedule(static) num_threads(this->Threads) reduction(max : largestChange)
    for (std::int64_t k = 0; k < blocks.Count(); ++k)
    {
      std::array<std::int64_t, D> i;
      const std::int64_t length = blocks.Get(k, i);
      const std::int64_t s0 = L.SampleIndex(i);
      const AdjacentFaces<D> faces(L, i);
      for (std::int64_t j = 0; j < length; ++j)
      {
        std::array<std::int64_t, D> at = i;
        at[0] += j;
        largestChange =
          std::max(largestChange, this->UpdateSample(at, s0 + j, faces, velocity, dt, state, next));
      }
    }
    return largestChange;
  }

private:
  bool Valid(std::int64_t s) const { return !this->ValidSample || this->ValidSample[s]; }

  double UpdateSample(const std::array<std::int64_t, D>& i, std::int64_t s,
    const AdjacentFaces<D>& faces, const float* velocity, double dt, const double* state,
    double* next) const
  {
    const double* value = state + s * C;
    double* out = next + s * C;
    if (!this->Valid(s))
    {
      std::copy(value, value + C, out);
      return 0.0;
    }
    // u at the sample: the mean over its valid adjacent faces (equal areas), in
    // the index units of `velocity` (the sign is folded into the dot product below).
    std::array<double, D> v{};
    int count = 0;
    for (int b = 0; b < Lattice<D>::Corners; ++b)
    {
      const std::int64_t f = faces.Face(i[0], b);
      if (f >= 0 && (!this->ValidFace || this->ValidFace[f]))
      {
        for (int d = 0; d < D; ++d)
        {
          v[d] += velocity[f * D + d];
        }
        ++count;
      }
    }
    if (count > 0)
    {
      for (int d = 0; d < D; ++d)
      {
        v[d] /= count;
      }
    }
    // Neighbour offsets per axis; 0 where the grid ends or the neighbour is not finite,
    // which makes the one-sided difference across it zero (a reflecting boundary).
    std::array<std::int64_t, D> below{}, above{};
    for (int d = 0; d < D; ++d)
    {
      const std::int64_t stride = L.sampleStride[d];
      below[d] = i[d] > 0 && this->Valid(s - stride) ? stride : 0;
      above[d] = i[d] + 1 < L.n[d] && this->Valid(s + stride) ? stride : 0;
    }
    double largestChange = 0.0;
    for (int c = 0; c < C; ++c)
    {
      double upwind2 = 0.0;  // |grad I|^2 from minmod differences
      double central2 = 0.0; // |grad I|^2 from central differences
      double flowDot = 0.0;  // <u, grad I> from central differences
      for (int d = 0; d < D; ++d)
      {
        const double forward = value[above[d] * C + c] - value[c];
        const double backward = value[c] - value[-below[d] * C + c];
        const double central = 0.5 * (forward + backward);
        const double m = MinMod(forward, backward) / L.h[d];
        upwind2 += m * m;
        central2 += central * central / L.h2[d];
        // u_d (grad I)_d = (-v_d h_d) (central / h_d)
        flowDot -= v[d] * central;
      }
      double change = 0.0;
      if (central2 > 0.0 && upwind2 > 0.0)
      {
        // F = <u, grad I> / |grad I|: the paper's edge detector with F = identity
        // (one square root for both norms: this loop is most of a step's cost).
        change = -dt * flowDot * std::sqrt(upwind2 / central2);
      }
      out[c] = value[c] + change;
      largestChange = std::max(largestChange, std::abs(change));
    }
    return largestChange;
  }

  const Lattice<D>& L;
  const int C;
  const unsigned char* ValidSample;
  const unsigned char* ValidFace;
  const int Threads;
};

/// A signal that cannot move (no flow): every checkpoint sees the input.
void PassWithoutFlow(const PDEParameters& p, const double* input, PDEReport& report,
  const PDECheckpointFunction& checkpoint)
{
  report.reachedTime = p.time;
  for (double t : p.checkpointTimes)
  {
    if (checkpoint)
    {
      checkpoint(t, 0.0, input);
    }
  }
}

/**
 * The time integration of one run: range-normalised values in two buffers that
 * swap roles every step, the flow recomputed before each step, checkpoints
 * written as they are passed.
 */
template <int D>
class PDEIntegration
{
public:
  /// `validSample` and `validFace` are null when every sample is finite.
  PDEIntegration(const Lattice<D>& lattice, int components, const double* input, double range,
    const PDEParameters& parameters, const unsigned char* validSample,
    const unsigned char* validFace, int threads, PDEReport& report,
    const PDECheckpointFunction& checkpoint)
    : L(lattice)
    , C(components)
    , Count(lattice.numSamples * components)
    , Input(input)
    , Range(range)
    , P(parameters)
    , ValidSample(validSample)
    , Threads(threads)
    , Report(report)
    , Checkpoint(checkpoint)
    , State(AllocateLargeArray<double>(this->Count))
    , Next(AllocateLargeArray<double>(this->Count))
    , Flow(lattice, components, parameters.smoothingPasses, validSample, validFace, threads)
    , Stepper(lattice, components, validSample, validFace, threads)
  {
    const double inverseRange = 1.0 / range;
    double* state = this->State.get();
    const std::int64_t count = this->Count;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t v = 0; v < count; ++v)
    {
      state[v] = input[v] * inverseRange;
    }
    if (checkpoint && !parameters.checkpointTimes.empty())
    {
      this->Snapshot = AllocateLargeArray<double>(this->Count);
    }
  }

  /// Step until the time, a steady state, the iteration limit or an abort.
  void Run(const ProgressFunction& progress)
  {
    PDEReport& report = this->Report;
    const PDEParameters& p = this->P;
    double t = 0.0;
    while (t < p.time)
    {
      if (report.iterations >= p.maximumIterations)
      {
        report.iterationLimit = true;
        break;
      }
      const auto flowStart = Clock::now();
      this->Flow.Compute(this->State.get(), 1.0);
      this->FlowComputed = true;
      report.flowSeconds += SecondsSince(flowStart);

      const auto updateStart = Clock::now();
      const double speed = this->Stepper.SpeedBound(this->Flow.Velocity());
      if (!(speed > 0.0))
      {
        report.updateSeconds += SecondsSince(updateStart);
        report.steadyState = true; // no flow anywhere: nothing can change any more
        break;
      }
      const double cflStep = p.courantNumber / speed;
      double target = std::min(p.time, t + cflStep);
      if (this->NextCheckpoint < p.checkpointTimes.size())
      {
        target = std::min(target, p.checkpointTimes[this->NextCheckpoint]);
      }
      const double dt = target - t;
      report.largestStep = std::max(report.largestStep, cflStep);
      report.smallestStep = report.iterations == 0 ? cflStep : std::min(report.smallestStep, cflStep);
      const double change =
        this->Stepper.Apply(this->Flow.Velocity(), dt, this->State.get(), this->Next.get());
      std::swap(this->State, this->Next);
      report.updateSeconds += SecondsSince(updateStart);
      ++report.iterations;
      t = target;
      this->PassCheckpoints(t, false);
      if (progress && !progress(t / p.time))
      {
        report.aborted = true;
        break;
      }
      // Only a full CFL step can tell: one shortened to land on a checkpoint may
      // be too short to change anything.
      if (change <= SteadyChange && dt >= cflStep)
      {
        report.steadyState = t < p.time;
        break;
      }
    }
    report.reachedTime = report.steadyState ? p.time : t;
  }

  /// Keep the whole potential of each flow, for the flow fields of Finish.
  void KeepPotential() { this->Flow.KeepPotential(); }

  /// After Run: the remaining checkpoints, the flow fields and the output.
  void Finish(double* output, GridFlowFields* fields)
  {
    if (this->Report.aborted)
    {
      std::copy(this->Input, this->Input + this->Count, output);
      return;
    }
    // A steady state holds for every later checkpoint; a run cut short gives none.
    if (this->Report.steadyState)
    {
      this->PassCheckpoints(this->P.time, true);
    }
    if (fields)
    {
      if (!this->FlowComputed)
      {
        this->Flow.Compute(this->State.get(), 1.0);
      }
      ExportFlowFields<D>(L, this->Flow, *fields);
    }
    if (this->P.time == 0.0)
    {
      std::copy(this->Input, this->Input + this->Count, output); // t = 0 gives the input exactly
      return;
    }
    this->WriteOutput(this->State.get(), output);
  }

private:
  void WriteOutput(const double* normalised, double* target) const
  {
    const double* input = this->Input;
    const unsigned char* validSample = this->ValidSample;
    const double range = this->Range;
    const int C = this->C;
    const std::int64_t count = this->Count;
#pragma omp parallel for schedule(static) num_threads(this->Threads)
    for (std::int64_t v = 0; v < count; ++v)
    {
      // Samples with a non-finite component never change: copied bit for bit.
      target[v] = validSample && !validSample[v / C] ? input[v] : normalised[v] * range;
    }
  }

  void PassCheckpoints(double reached, bool all)
  {
    const std::vector<double>& times = this->P.checkpointTimes;
    while (this->NextCheckpoint < times.size() && (all || times[this->NextCheckpoint] <= reached))
    {
      if (this->Checkpoint)
      {
        this->WriteOutput(this->State.get(), this->Snapshot.get());
        this->Checkpoint(times[this->NextCheckpoint],
          this->Report.flowSeconds + this->Report.updateSeconds, this->Snapshot.get());
      }
      ++this->NextCheckpoint;
    }
  }

  const Lattice<D>& L;
  const int C;
  const std::int64_t Count;
  const double* Input;
  const double Range;
  const PDEParameters& P;
  const unsigned char* ValidSample;
  const int Threads;
  PDEReport& Report;
  const PDECheckpointFunction& Checkpoint;
  LargeArray<double> State;
  LargeArray<double> Next;
  LargeArray<double> Snapshot;
  FlowComputation<D> Flow;
  const PDEStep<D> Stepper;
  size_t NextCheckpoint = 0;
  bool FlowComputed = false;
};

template <int D>
Status RunPDE(const GridShape& shape, int C, const double* input, double* output,
  const PDEParameters& p, PDEReport& report, GridFlowFields* fields,
  const ProgressFunction& progress, const PDECheckpointFunction& checkpoint)
{
  const Lattice<D> L(shape);
  const int threads = ThreadsForWork(p.numberOfThreads, L.numSamples);
  const std::int64_t count = L.numSamples * C;

  const SignalRange scan = ScanSignal(L.numSamples, C, input, threads);
  const double range = p.valueScale > 0.0 ? p.valueScale : scan.high - scan.low;
  if (range == std::numeric_limits<double>::infinity())
  {
    return { ValueSpanError(scan.low, scan.high) };
  }
  if (!(range > 0.0) || !std::isfinite(range))
  {
    // Constant (or entirely non-finite) signal: no flow, nothing moves.
    std::copy(input, input + count, output);
    if (fields)
    {
      ZeroFlowFields(L.numSamples, L.numFaces, *fields);
    }
    report.steadyState = p.time > 0.0;
    PassWithoutFlow(p, input, report, checkpoint);
    return {};
  }

  const ValidityMasks<D> masks(L, C, input, scan.allFinite, threads);
  PDEIntegration<D> integration(
    L, C, input, range, p, masks.Samples(), masks.Faces(), threads, report, checkpoint);
  if (fields)
  {
    integration.KeepPotential();
  }
  integration.Run(progress);
  integration.Finish(output, fields);
  return {};
}

} // namespace

Status CheckPDEParameters(const PDEParameters& p)
{
  if (!(p.time >= 0.0) || !std::isfinite(p.time))
  {
    return { "the flow time must be finite and >= 0" };
  }
  if (p.smoothingPasses < 0)
  {
    return { "the number of smoothing passes must be >= 0" };
  }
  if (!(p.courantNumber > 0.0 && p.courantNumber <= 1.0))
  {
    return { "the Courant number must be in (0, 1]" };
  }
  if (p.maximumIterations < 1)
  {
    return { "the iteration limit must be >= 1" };
  }
  if (!(p.valueScale >= 0.0) || !std::isfinite(p.valueScale))
  {
    return { "the value scale must be finite and >= 0" };
  }
  double previous = 0.0;
  for (double t : p.checkpointTimes)
  {
    if (!(t > previous) || t > p.time)
    {
      return { "checkpoint times must increase within (0, time]" };
    }
    previous = t;
  }
  return {};
}

Status SolveGridShockPDE(const GridShape& shape, int components, const double* input,
  double* output, const PDEParameters& parameters, PDEReport* report, GridFlowFields* fields,
  const ProgressFunction& progress, const PDECheckpointFunction& checkpoint)
{
  const Status arguments = CheckGridArguments(shape, components, input, output);
  if (!arguments.Ok())
  {
    return arguments;
  }
  const Status valid = CheckPDEParameters(parameters);
  if (!valid.Ok())
  {
    return valid;
  }

  PDEReport localReport;
  PDEReport& r = report ? *report : localReport;
  r = PDEReport();
  switch (shape.ActiveAxes())
  {
    case 1:
      return RunPDE<1>(shape, components, input, output, parameters, r, fields, progress, checkpoint);
    case 2:
      return RunPDE<2>(shape, components, input, output, parameters, r, fields, progress, checkpoint);
    case 3:
      return RunPDE<3>(shape, components, input, output, parameters, r, fields, progress, checkpoint);
    default:
      // A single sample has no faces, hence no flow.
      std::copy(input, input + shape.NumberOfSamples() * components, output);
      if (fields)
      {
        ZeroFlowFields(shape.NumberOfSamples(), shape.NumberOfFaces(), *fields);
      }
      PassWithoutFlow(parameters, input, r, checkpoint);
      return {};
  }
}

} // namespace shock
