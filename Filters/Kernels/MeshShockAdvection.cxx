#include "MeshShockAdvection.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

namespace shock
{

namespace
{
using Clock = std::chrono::steady_clock;
using Vec3 = std::array<double, 3>;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Offset of a vertex-advection start towards the adjacent face centre (the paper's epsilon).
constexpr double VertexOffset = 0.001;

// Crossings that make no progress (a trace turning around a vertex) before the
// trace is stopped there: more than any sane vertex valence.
constexpr int MaxStalledCrossings = 64;

inline double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline Vec3 Load(const double* v)
{
  return { v[0], v[1], v[2] };
}

inline Vec3 Combine(double a, const Vec3& x, double b, const Vec3& y)
{
  return { a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2] };
}

inline Vec3 Unit(const Vec3& v)
{
  const double n = std::sqrt(Dot(v, v));
  return n > 0.0 ? Vec3{ v[0] / n, v[1] / n, v[2] / n } : Vec3{ 0.0, 0.0, 0.0 };
}

/**
 * The shared edge of two triangles as a hinge: `edge` along it, `outOfFirst` in
 * the first triangle's plane pointing across the edge, `intoSecond` in the second
 * triangle's plane pointing away from the edge. Unfolding maps the in-plane
 * frame (edge, outOfFirst) onto (edge, intoSecond), an isometry, so directions
 * keep their angle to the edge (Shi and Yu 2004). Built from the opposite
 * corners, it does not depend on the triangles' orientations.
 */
struct Hinge
{
  Vec3 edge;
  Vec3 outOfFirst;
  Vec3 intoSecond;

  Vec3 Unfold(const Vec3& v) const
  {
    return Combine(Dot(v, this->edge), this->edge, Dot(v, this->outOfFirst), this->intoSecond);
  }
  Vec3 FoldBack(const Vec3& v) const
  {
    return Combine(Dot(v, this->edge), this->edge, Dot(v, this->intoSecond), this->outOfFirst);
  }
};

/**
 * Traces surface points along a per-triangle constant velocity (world units per
 * unit of normalised time). Positions are (triangle, barycentric coordinates),
 * so traced points always lie on their triangle.
 */
class SurfaceTracer
{
public:
  /// `length`: the length unit (mean edge length), so delta = stepFraction x length.
  SurfaceTracer(
    const TriangleMesh& mesh, const double* velocity, const AdvectionParameters& p, double length)
    : Mesh(mesh)
    , Velocity(velocity)
    , Mode(p.tracing)
    , Delta(p.stepFraction * length)
  {
    // A discrete gradient flow has no cycles in the continuum limit; should the
    // discretisation create one, cap the work per trace at a few mesh diameters
    // (a diameter is about sqrt(#triangles) edges).
    const double diameter = std::sqrt(2.0 * static_cast<double>(mesh.NumberOfTriangles())) + 1.0;
    this->MaxSteps = (this->Mode == Tracing::FaceCrossing)
      ? static_cast<std::int64_t>(16.0 * diameter) + 64
      : static_cast<std::int64_t>(std::ceil(4.0 * diameter / p.stepFraction)) + 64;
  }

  std::int64_t Trace(SurfacePoint& q, double t, bool& truncated) const
  {
    truncated = false;
    if (q.triangle < 0 || this->Mesh.Degenerate(q.triangle) || !(t > 0.0))
    {
      return 0;
    }
    return this->Mode == Tracing::FaceCrossing ? this->TraceFaceCrossing(q, t, truncated)
                                               : this->TraceStepped(q, t, truncated);
  }

private:
  Vec3 VelocityOf(std::int64_t f) const { return Load(this->Velocity + 3 * f); }

  /// Time until q, moving with v, leaves its triangle, and the corner whose coordinate reaches 0.
  double ExitTime(const SurfacePoint& q, const Vec3& v, int& corner) const
  {
    double exit = std::numeric_limits<double>::infinity();
    corner = -1;
    for (int c = 0; c < 3; ++c)
    {
      const double rate = Dot(Load(this->Mesh.HatGradient(q.triangle, c)), v);
      if (rate < 0.0)
      {
        const double time = std::max(0.0, q.barycentric[c]) / -rate;
        if (time < exit)
        {
          exit = time;
          corner = c;
        }
      }
    }
    return exit;
  }

  /// Move q with v for dt inside its triangle; `exitCorner` >= 0 lands it exactly on that edge.
  void Advance(SurfacePoint& q, const Vec3& v, double dt, int exitCorner) const
  {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      double& l = q.barycentric[c];
      l = (c == exitCorner) ? 0.0 : std::max(0.0, l + Dot(Load(this->Mesh.HatGradient(q.triangle, c)), v) * dt);
      sum += l;
    }
    for (double& l : q.barycentric)
    {
      l = sum > 0.0 ? l / sum : 1.0 / 3.0;
    }
  }

  /**
   * Move q across the edge opposite `corner` into the neighbouring triangle.
   * Returns false (q unchanged) at boundary and non-manifold edges.
   */
  bool Cross(SurfacePoint& q, int corner, Hinge& hinge) const
  {
    const std::int64_t f = q.triangle;
    const std::int64_t g = this->Mesh.Neighbour(f, (corner + 1) % 3);
    if (g < 0)
    {
      return false;
    }
    const std::int64_t* tf = this->Mesh.Corners(f);
    const std::int64_t* tg = this->Mesh.Corners(g);
    const std::int64_t a = tf[(corner + 1) % 3];
    const std::int64_t b = tf[(corner + 2) % 3];
    int third = 0;
    double lambda[3] = { 0.0, 0.0, 0.0 };
    for (int c = 0; c < 3; ++c)
    {
      if (tg[c] == a)
      {
        lambda[c] = q.barycentric[(corner + 1) % 3];
      }
      else if (tg[c] == b)
      {
        lambda[c] = q.barycentric[(corner + 2) % 3];
      }
      else
      {
        third = c;
      }
    }
    const Vec3 xa = Load(this->Mesh.Point(a));
    const Vec3 edge = Unit(Combine(1.0, Load(this->Mesh.Point(b)), -1.0, xa));
    auto perpendicular = [&](std::int64_t p) {
      const Vec3 w = Combine(1.0, Load(this->Mesh.Point(p)), -1.0, xa);
      return Unit(Combine(1.0, w, -Dot(w, edge), edge));
    };
    const Vec3 intoFirst = perpendicular(tf[corner]);
    hinge = { edge, { -intoFirst[0], -intoFirst[1], -intoFirst[2] }, perpendicular(tg[third]) };
    q.triangle = g;
    std::copy(lambda, lambda + 3, q.barycentric);
    return true;
  }

  /**
   * One Appendix A step: walk straight (a geodesic) along `direction` for time dt,
   * unfolding across edges; `direction` comes back expressed in the final triangle.
   * Returns false when the walk stops at a boundary, non-manifold edge or stall.
   */
  bool Walk(SurfacePoint& q, Vec3& direction, double dt) const
  {
    int stalled = 0;
    while (true)
    {
      int corner = -1;
      const double exit = this->ExitTime(q, direction, corner);
      if (exit >= dt)
      {
        this->Advance(q, direction, dt, -1);
        return true;
      }
      this->Advance(q, direction, exit, corner);
      dt -= exit;
      stalled = exit > 0.0 ? 0 : stalled + 1;
      Hinge hinge;
      if (stalled > MaxStalledCrossings || !this->Cross(q, corner, hinge))
      {
        return false;
      }
      direction = hinge.Unfold(direction);
    }
  }

  /// The paper's Appendix A Trace with steps of at most delta.
  std::int64_t TraceStepped(SurfacePoint& q, double t, bool& truncated) const
  {
    Vec3 v = this->VelocityOf(q.triangle);
    Vec3 previous = v;
    std::int64_t steps = 0;
    while (t > 0.0 && Dot(v, previous) > 0.0)
    {
      if (steps >= this->MaxSteps)
      {
        truncated = true;
        break;
      }
      const double dt = std::min(t, this->Delta / std::sqrt(Dot(v, v)));
      previous = v;
      ++steps;
      if (!this->Walk(q, previous, dt))
      {
        break;
      }
      t -= dt;
      v = this->VelocityOf(q.triangle); // `previous` is now in this triangle's frame
    }
    return steps;
  }

  /**
   * The exact limit of TraceStepped as delta -> 0: straight to the triangle's edge,
   * then on with the next triangle's velocity. Where both triangles push into
   * their shared edge, the stepped trace zig-zags along it; its limit is the
   * sliding (Filippov) velocity along the edge. At the end of such an edge (a
   * vertex) the rest of the trace is stepped.
   */
  std::int64_t TraceFaceCrossing(SurfacePoint& q, double t, bool& truncated) const
  {
    Vec3 v = this->VelocityOf(q.triangle);
    std::int64_t steps = 0;
    int stalled = 0;
    while (t > 0.0 && Dot(v, v) > 0.0)
    {
      if (steps >= this->MaxSteps || stalled > MaxStalledCrossings)
      {
        truncated = true;
        break;
      }
      int corner = -1;
      const double exit = this->ExitTime(q, v, corner);
      if (exit >= t)
      {
        this->Advance(q, v, t, -1);
        break;
      }
      this->Advance(q, v, exit, corner);
      t -= exit;
      ++steps;
      stalled = exit > 0.0 ? 0 : stalled + 1;
      SurfacePoint across = q;
      Hinge hinge;
      if (!this->Cross(across, corner, hinge))
      {
        break; // boundary or non-manifold edge
      }
      const Vec3 next = this->VelocityOf(across.triangle);
      const Vec3 nextHere = hinge.FoldBack(next);
      if (Dot(nextHere, v) <= 0.0)
      {
        break; // the flow reverses (the paper's direction test, in the unfolded frame)
      }
      const double awayFromEdge = Dot(next, hinge.intoSecond);
      if (awayFromEdge > 0.0)
      {
        q = across;
        v = next;
        continue;
      }
      // Both triangles push into the edge: slide along it.
      const double outward = std::max(Dot(v, hinge.outOfFirst), 0.0);
      const double w = outward / (outward - awayFromEdge);
      const double speed = (1.0 - w) * Dot(v, hinge.edge) + w * Dot(next, hinge.edge);
      if (!(outward - awayFromEdge > 0.0) || speed == 0.0)
      {
        break; // a sink on the edge
      }
      steps += this->Slide(q, corner, speed, t);
      if (t > 0.0)
      {
        return steps + this->TraceStepped(q, t, truncated);
      }
    }
    return steps;
  }

  /// Slide q along the edge opposite `corner` (speed > 0 towards corner + 2) until t or a vertex.
  std::int64_t Slide(SurfacePoint& q, int corner, double speed, double& t) const
  {
    const int ia = (corner + 1) % 3;
    const int ib = (corner + 2) % 3;
    const std::int64_t* tf = this->Mesh.Corners(q.triangle);
    const Vec3 xa = Load(this->Mesh.Point(tf[ia]));
    const Vec3 xb = Load(this->Mesh.Point(tf[ib]));
    const Vec3 ab = Combine(1.0, xb, -1.0, xa);
    const double length = std::sqrt(Dot(ab, ab));
    const double rate = speed / length; // d(lambda_b)/dt
    const double toVertex = rate > 0.0 ? q.barycentric[ia] / rate : q.barycentric[ib] / -rate;
    const double dt = std::min(t, toVertex);
    double lb = std::clamp(q.barycentric[ib] + rate * dt, 0.0, 1.0);
    if (dt == toVertex)
    {
      lb = rate > 0.0 ? 1.0 : 0.0;
    }
    q.barycentric[corner] = 0.0;
    q.barycentric[ib] = lb;
    q.barycentric[ia] = 1.0 - lb;
    t -= dt;
    return 1;
  }

  const TriangleMesh& Mesh;
  const double* Velocity;
  Tracing Mode;
  double Delta;
  std::int64_t MaxSteps = 0;
};

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
  std::vector<unsigned char> validPoint;    // point has a finite value (or, for cells, a finite neighbour)
  std::vector<unsigned char> validTriangle; // non-degenerate, finite corners (and value): carries flow
  std::vector<double> umbrellaWeight;       // per one-ring entry, exp(-|(v-w)/l|^2)

  std::int64_t Points() const { return this->mesh.NumberOfPoints(); }
  std::int64_t Triangles() const { return this->mesh.NumberOfTriangles(); }
  bool CellSignal() const { return this->signal.location == MeshLocation::Triangles; }
};

bool Finite(const double* v, int C)
{
  for (int c = 0; c < C; ++c)
  {
    if (!std::isfinite(v[c]))
    {
      return false;
    }
  }
  return true;
}

/**
 * Average a per-triangle signal to the points, weighted by area, over valid
 * triangles; points without any keep zeros (they are marked invalid).
 */
void TrianglesToPoints(const MeshRun& run, int C, const double* cells,
  const std::vector<unsigned char>& cellValid, std::vector<double>& points)
{
  const CompressedLists& around = run.mesh.PointTriangles();
  points.assign(static_cast<size_t>(run.Points() * C), 0.0);
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t p = 0; p < run.Points(); ++p)
  {
    double total = 0.0;
    double* out = &points[static_cast<size_t>(p * C)];
    for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
    {
      const std::int64_t f = around.items[static_cast<size_t>(k)];
      const double a = run.mesh.Area(f);
      if (a > 0.0 && cellValid[static_cast<size_t>(f)])
      {
        total += a;
        for (int c = 0; c < C; ++c)
        {
          out[c] += a * cells[f * C + c];
        }
      }
    }
    for (int c = 0; c < C; ++c)
    {
      out[c] = total > 0.0 ? out[c] / total : 0.0;
    }
  }
}

/// Appendix A umbrella smoothing over the one-ring; invalid points neither change nor contribute.
void UmbrellaSmooth(const MeshRun& run, int C, std::vector<double>& values, int passes)
{
  const CompressedLists& ring = run.mesh.OneRing();
  std::vector<double> smoothed(values.size());
  for (int pass = 0; pass < passes; ++pass)
  {
#pragma omp parallel for num_threads(run.threads) schedule(static)
    for (std::int64_t p = 0; p < run.Points(); ++p)
    {
      double* out = &smoothed[static_cast<size_t>(p * C)];
      const double* self = &values[static_cast<size_t>(p * C)];
      std::copy(self, self + C, out);
      if (!run.validPoint[static_cast<size_t>(p)])
      {
        continue;
      }
      double weight = 1.0;
      for (std::int64_t k = ring.Begin(p); k < ring.End(p); ++k)
      {
        const std::int64_t w = ring.items[static_cast<size_t>(k)];
        if (!run.validPoint[static_cast<size_t>(w)])
        {
          continue;
        }
        const double a = run.umbrellaWeight[static_cast<size_t>(k)];
        weight += a;
        for (int c = 0; c < C; ++c)
        {
          out[c] += a * values[static_cast<size_t>(w * C + c)];
        }
      }
      for (int c = 0; c < C; ++c)
      {
        out[c] /= weight;
      }
    }
    values.swap(smoothed);
  }
}

/// Gradient (normalised lengths) of channel c of a point signal on triangle f.
inline Vec3 TriangleGradient(const MeshRun& run, const double* values, int C, int c, std::int64_t f)
{
  const std::int64_t* t = run.mesh.Corners(f);
  Vec3 g{ 0.0, 0.0, 0.0 };
  for (int k = 0; k < 3; ++k)
  {
    g = Combine(1.0, g, values[t[k] * C + c], Load(run.mesh.HatGradient(f, k)));
  }
  const double l = run.length;
  return { g[0] * l, g[1] * l, g[2] * l };
}

/**
 * Flow of a point signal (range-normalised): smoothing, potential (|grad I|^2
 * summed over channels, area-averaged to points, smoothed), u = 1/2 grad P.
 * Returns the potential; `flow` receives u per triangle (normalised units).
 */
std::vector<double> ComputeFlow(const MeshRun& run, std::vector<double> signal, std::vector<double>& flow)
{
  const int C = run.C;
  UmbrellaSmooth(run, C, signal, run.p.smoothingPasses);
  std::vector<double> energy(static_cast<size_t>(run.Triangles()), 0.0);
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t f = 0; f < run.Triangles(); ++f)
  {
    if (!run.validTriangle[static_cast<size_t>(f)])
    {
      continue;
    }
    double e = 0.0;
    for (int c = 0; c < C; ++c)
    {
      const Vec3 g = TriangleGradient(run, signal.data(), C, c, f);
      e += Dot(g, g);
    }
    energy[static_cast<size_t>(f)] = e;
  }
  std::vector<double> potential;
  TrianglesToPoints(run, 1, energy.data(), run.validTriangle, potential);
  UmbrellaSmooth(run, 1, potential, run.p.smoothingPasses);

  flow.assign(static_cast<size_t>(3 * run.Triangles()), 0.0);
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t f = 0; f < run.Triangles(); ++f)
  {
    if (run.validTriangle[static_cast<size_t>(f)])
    {
      const Vec3 g = TriangleGradient(run, potential.data(), 1, 0, f);
      for (int k = 0; k < 3; ++k)
      {
        flow[static_cast<size_t>(3 * f + k)] = 0.5 * g[k];
      }
    }
  }
  return potential;
}

/// Read a signal at a traced point. Returns false when nothing valid is there.
bool SampleAt(const MeshRun& run, const SurfacePoint& q, const double* cells, const double* points,
  double* acc)
{
  const int C = run.C;
  const std::int64_t* t = run.mesh.Corners(q.triangle);
  if (run.p.sampling == Sampling::Nearest)
  {
    if (run.CellSignal())
    {
      if (!Finite(cells + q.triangle * C, C))
      {
        return false;
      }
      for (int c = 0; c < C; ++c)
      {
        acc[c] += cells[q.triangle * C + c];
      }
      return true;
    }
    Vec3 x{ 0.0, 0.0, 0.0 };
    for (int k = 0; k < 3; ++k)
    {
      x = Combine(1.0, x, q.barycentric[k], Load(run.mesh.Point(t[k])));
    }
    int nearest = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k)
    {
      const Vec3 d = Combine(1.0, x, -1.0, Load(run.mesh.Point(t[k])));
      if (run.validPoint[static_cast<size_t>(t[k])] && Dot(d, d) < best)
      {
        best = Dot(d, d);
        nearest = k;
      }
    }
    if (nearest < 0)
    {
      return false;
    }
    for (int c = 0; c < C; ++c)
    {
      acc[c] += points[t[nearest] * C + c];
    }
    return true;
  }
  double total = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    total += run.validPoint[static_cast<size_t>(t[k])] ? q.barycentric[k] : 0.0;
  }
  if (!(total > 0.0))
  {
    return false;
  }
  for (int c = 0; c < C; ++c)
  {
    // A convex combination: clamp away rounding so outputs never leave the corners' range.
    double value = 0.0;
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (int k = 0; k < 3; ++k)
    {
      if (run.validPoint[static_cast<size_t>(t[k])])
      {
        const double v = points[t[k] * C + c];
        value += (q.barycentric[k] / total) * v;
        low = std::min(low, v);
        high = std::max(high, v);
      }
    }
    acc[c] += std::clamp(value, low, high);
  }
  return true;
}

/// Counters and progress reporting shared by the advection passes.
struct AdvectionPass
{
  const MeshRun& run;
  const SurfaceTracer& tracer;
  double time;
  const ProgressFunction& progress;
  double progressStart;
  double progressSpan;
  AdvectionReport& report;

  /// Run body(i) for i in [0, n) in parallel chunks, reporting progress between chunks.
  template <typename Body>
  bool ForEach(std::int64_t n, Body&& body)
  {
    const std::int64_t chunkCount = std::max<std::int64_t>(1, std::min<std::int64_t>(64, n / 8192));
    const std::int64_t chunkSize = (n + chunkCount - 1) / chunkCount;
    std::uint64_t steps = 0;
    std::uint64_t truncated = 0;
    bool completed = true;
    for (std::int64_t chunk = 0; chunk < chunkCount && completed; ++chunk)
    {
      const std::int64_t begin = chunk * chunkSize;
      const std::int64_t end = std::min(n, begin + chunkSize);
#pragma omp parallel for schedule(dynamic, 256) num_threads(this->run.threads) reduction(+ : steps, truncated)
      for (std::int64_t i = begin; i < end; ++i)
      {
        body(i, steps, truncated);
      }
      completed = !this->progress ||
        this->progress(this->progressStart + this->progressSpan * static_cast<double>(end) / n);
    }
    this->report.traceSteps += steps;
    this->report.truncatedTraces += truncated;
    return completed;
  }

  std::uint64_t Trace(SurfacePoint& q, std::uint64_t& truncated) const
  {
    bool cut = false;
    const std::int64_t steps = this->tracer.Trace(q, this->time, cut);
    truncated += cut ? 1 : 0;
    return static_cast<std::uint64_t>(steps);
  }
};

/// Start of the vertex-advection trace of point p into triangle f (the Appendix's offset).
SurfacePoint VertexStart(const TriangleMesh& mesh, std::int64_t p, std::int64_t f)
{
  SurfacePoint q;
  q.triangle = f;
  const std::int64_t* t = mesh.Corners(f);
  for (int k = 0; k < 3; ++k)
  {
    q.barycentric[k] = VertexOffset / 3.0 + (t[k] == p ? 1.0 - VertexOffset : 0.0);
  }
  return q;
}

SurfacePoint FaceStart(std::int64_t f)
{
  SurfacePoint q;
  q.triangle = f;
  return q;
}

/**
 * Appendix A AdvectVertices (point signals) or AdvectFaces (cell signals):
 * trace, sample `source` (with `sourcePoints` its per-point values for Linear
 * sampling of cells) and average. With `positions` (Composed flow), traces resume
 * from and update stored positions. Returns false when aborted.
 */
bool Advect(AdvectionPass& pass, const double* source, const double* sourcePoints, double* out,
  std::vector<SurfacePoint>* positions)
{
  const MeshRun& run = pass.run;
  const int C = run.C;
  const TriangleMesh& mesh = run.mesh;
  if (run.CellSignal())
  {
    return pass.ForEach(run.Triangles(), [&](std::int64_t f, std::uint64_t& steps, std::uint64_t& cut) {
      double* acc = out + f * C;
      const double* own = source + f * C;
      if (mesh.Degenerate(f) || !Finite(own, C))
      {
        std::copy(own, own + C, acc);
        return;
      }
      SurfacePoint local = FaceStart(f);
      SurfacePoint& q = positions ? (*positions)[static_cast<size_t>(f)] : local;
      steps += pass.Trace(q, cut);
      std::fill(acc, acc + C, 0.0);
      if (!SampleAt(run, q, source, sourcePoints, acc))
      {
        std::copy(own, own + C, acc);
      }
    });
  }
  const CompressedLists& around = mesh.PointTriangles();
  return pass.ForEach(run.Points(), [&](std::int64_t p, std::uint64_t& steps, std::uint64_t& cut) {
    double* acc = out + p * C;
    const double* own = source + p * C;
    std::fill(acc, acc + C, 0.0);
    int samples = 0;
    if (run.validPoint[static_cast<size_t>(p)])
    {
      for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
      {
        const std::int64_t f = around.items[static_cast<size_t>(k)];
        if (mesh.Degenerate(f))
        {
          continue;
        }
        SurfacePoint local = VertexStart(mesh, p, f);
        SurfacePoint& q = positions ? (*positions)[static_cast<size_t>(k)] : local;
        steps += pass.Trace(q, cut);
        if (!SampleAt(run, q, nullptr, source, acc))
        {
          for (int c = 0; c < C; ++c)
          {
            acc[c] += own[c]; // only non-finite values around q: keep the point's own value
          }
        }
        ++samples;
      }
    }
    if (samples == 0)
    {
      std::copy(own, own + C, acc); // invalid, isolated or only on degenerate triangles
      return;
    }
    for (int c = 0; c < C; ++c)
    {
      acc[c] /= samples;
    }
  });
}

/// Composed-flow start positions: one per trace, as Advect would start them.
std::vector<SurfacePoint> InitialPositions(const MeshRun& run)
{
  if (run.CellSignal())
  {
    std::vector<SurfacePoint> positions(static_cast<size_t>(run.Triangles()));
    for (std::int64_t f = 0; f < run.Triangles(); ++f)
    {
      positions[static_cast<size_t>(f)] = FaceStart(f);
    }
    return positions;
  }
  const CompressedLists& around = run.mesh.PointTriangles();
  std::vector<SurfacePoint> positions(around.items.size());
  for (std::int64_t p = 0; p < run.Points(); ++p)
  {
    for (std::int64_t k = around.Begin(p); k < around.End(p); ++k)
    {
      positions[static_cast<size_t>(k)] = VertexStart(run.mesh, p, around.items[static_cast<size_t>(k)]);
    }
  }
  return positions;
}

/// Validity masks, range and umbrella weights; returns false when there is nothing to filter.
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
    finite[static_cast<size_t>(i)] = Finite(values + i * C, C) ? 1 : 0;
    if (finite[static_cast<size_t>(i)])
    {
      for (int c = 0; c < C; ++c)
      {
        low = std::min(low, values[i * C + c]);
        high = std::max(high, values[i * C + c]);
      }
    }
  }
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

  const CompressedLists& ring = mesh.OneRing();
  const double l = run.length;
  run.umbrellaWeight.resize(ring.items.size());
#pragma omp parallel for num_threads(run.threads) schedule(static)
  for (std::int64_t p = 0; p < run.Points(); ++p)
  {
    const Vec3 x = Load(mesh.Point(p));
    for (std::int64_t k = ring.Begin(p); k < ring.End(p); ++k)
    {
      const Vec3 d = Combine(1.0, x, -1.0, Load(mesh.Point(ring.items[static_cast<size_t>(k)])));
      run.umbrellaWeight[static_cast<size_t>(k)] = std::exp(-Dot(d, d) / (l * l));
    }
  }
  return true;
}

Status RunMesh(const TriangleMesh& mesh, const MeshSignal& signal, double* output,
  const AdvectionParameters& p, AdvectionReport& report, MeshFlowFields* fields,
  const ProgressFunction& progress)
{
  MeshRun run{ mesh, signal, p, signal.components, ResolveThreadCount(p.numberOfThreads) };
  const int C = run.C;
  const std::int64_t count = (run.CellSignal() ? run.Triangles() : run.Points()) * C;
  const double* input = signal.values;
  std::copy(input, input + count, output);
  if (fields)
  {
    fields->potential.assign(static_cast<size_t>(run.Points()), 0.0);
    fields->flow.assign(static_cast<size_t>(3 * run.Triangles()), 0.0);
  }
  const auto setupStart = Clock::now();
  if (!Prepare(run))
  {
    return {};
  }
  report.flowSeconds += SecondsSince(setupStart);

  const int updates = p.flowMode == FlowMode::Fixed ? 1 : std::max(1, p.flowUpdates);
  const double stepTime = p.time / updates;
  std::vector<double> current(input, input + count); // the signal the flow is computed from
  std::vector<double> next(p.flowMode == FlowMode::Naive ? count : 0);
  std::vector<SurfacePoint> positions;
  if (p.flowMode == FlowMode::Composed && (p.time > 0.0 || signal.sampleAtTimeZero))
  {
    positions = InitialPositions(run);
  }
  std::vector<unsigned char> cellValid;
  if (run.CellSignal())
  {
    cellValid.resize(static_cast<size_t>(run.Triangles()));
    for (std::int64_t f = 0; f < run.Triangles(); ++f)
    {
      cellValid[static_cast<size_t>(f)] = Finite(input + f * C, C) ? 1 : 0;
    }
  }
  // Per-point values of a cell signal: what the potential and Linear sampling use.
  std::vector<double> inputPoints;
  if (run.CellSignal())
  {
    TrianglesToPoints(run, C, input, cellValid, inputPoints);
  }

  std::vector<double> flow;
  std::vector<double> velocity;
  for (int k = 0; k < updates; ++k)
  {
    const auto flowStart = Clock::now();
    std::vector<double> normalised;
    if (run.CellSignal())
    {
      TrianglesToPoints(run, C, current.data(), cellValid, normalised);
    }
    else
    {
      normalised = current;
    }
    for (double& v : normalised)
    {
      v /= run.range;
    }
    std::vector<double> potential = ComputeFlow(run, std::move(normalised), flow);
    // Back-trace velocity in world units per unit normalised time: -u scaled by l-bar.
    velocity.resize(flow.size());
    const double l = run.length;
    for (size_t i = 0; i < flow.size(); ++i)
    {
      velocity[i] = -l * flow[i];
    }
    report.flowSeconds += SecondsSince(flowStart);
    if (fields && k == updates - 1)
    {
      fields->potential = std::move(potential);
      fields->flow = flow;
    }
    const double progressStart = (k + 0.1) / updates;
    if (progress && !progress(progressStart))
    {
      report.aborted = true;
      break;
    }
    if (!(p.time > 0.0) && !signal.sampleAtTimeZero)
    {
      continue; // t = 0: the input, exactly
    }

    const auto advectStart = Clock::now();
    const SurfaceTracer tracer(mesh, velocity.data(), p, run.length);
    AdvectionPass pass{ run, tracer, stepTime, progress, progressStart, 0.9 / updates, report };
    bool completed = true;
    switch (p.flowMode)
    {
      case FlowMode::Fixed:
        completed = Advect(pass, input, run.CellSignal() ? inputPoints.data() : input, output, nullptr);
        break;
      case FlowMode::Composed:
        completed = Advect(pass, input, run.CellSignal() ? inputPoints.data() : input, current.data(), &positions);
        break;
      case FlowMode::Naive:
      {
        std::vector<double> currentPoints;
        if (run.CellSignal())
        {
          TrianglesToPoints(run, C, current.data(), cellValid, currentPoints);
        }
        completed = Advect(pass, current.data(), run.CellSignal() ? currentPoints.data() : current.data(),
          next.data(), nullptr);
        current.swap(next);
        break;
      }
    }
    report.advectionSeconds += SecondsSince(advectStart);
    if (!completed)
    {
      report.aborted = true;
      break;
    }
  }

  if (report.aborted)
  {
    std::copy(input, input + count, output);
  }
  else if (p.flowMode != FlowMode::Fixed && (p.time > 0.0 || signal.sampleAtTimeZero))
  {
    std::copy(current.begin(), current.end(), output);
  }
  return {};
}

} // namespace

std::int64_t TraceOnMesh(const TriangleMesh& mesh, const double* velocity, SurfacePoint& point,
  double time, const AdvectionParameters& parameters, bool* truncated)
{
  bool cut = false;
  const SurfaceTracer tracer(mesh, velocity, parameters, mesh.MeanEdgeLength());
  const std::int64_t steps = tracer.Trace(point, time, cut);
  if (truncated)
  {
    *truncated = cut;
  }
  return steps;
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
  AdvectionReport localReport;
  AdvectionReport& r = report ? *report : localReport;
  r = AdvectionReport();
  return RunMesh(mesh, signal, output, parameters, r, fields, progress);
}

} // namespace shock
