/**
 * @file MeshTrace.h
 * @brief Appendix A Trace on a triangle mesh: surface points moved along a
 * per-triangle constant velocity, straight inside a triangle and unfolded
 * across edges (Shi and Yu 2004).
 *
 * Traces stop when the time is used up, when the flow reverses (the next
 * triangle's velocity, folded back into the current triangle's plane, makes an
 * angle of 90 degrees or more with the current one), at boundary and
 * non-manifold edges, at degenerate triangles, and at a step cap that guards
 * against cycles of the discrete flow.
 */
#ifndef MeshTrace_h
#define MeshTrace_h

#include "ShockTypes.h"
#include "TriangleMesh.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace shock
{

/// A point on the mesh: a triangle and barycentric coordinates (sum 1, each >= 0).
struct SurfacePoint
{
  std::int64_t triangle = -1;
  double barycentric[3] = { 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0 };
};

/**
 * How deep into a distributed piece's ghost rings one trace went: `ring` gives
 * each triangle's ring (0: the piece's own triangles, k: the k-th ring around
 * them); `deepest` is the largest ring of the triangles the trace started in or
 * entered (each one whose velocity or geometry it read). A trace that never
 * entered a triangle beyond ring E read only flow that a piece with E +
 * MeshStencilRings rings computes exactly as the whole mesh does.
 */
struct RingReach
{
  const unsigned char* ring = nullptr;
  int deepest = -1;

  void Visit(std::int64_t f)
  {
    this->deepest = std::max(this->deepest, static_cast<int>(this->ring[f]));
  }
};

/**
 * Move one surface point along a per-triangle velocity for time t with the Appendix A Trace
 * (Tracing::Stepped) or its exact delta -> 0 limit (Tracing::FaceCrossing).
 * `velocity` is 3 values per triangle in mesh axes (the kernel passes -u of
 * MeshFlowFields::flow, in length units per unit of time); `length` is the
 * length unit of the step delta = stepFraction x length (0: the mesh's mean
 * edge length).
 * @return the number of steps (delta-steps or face crossings).
 */
std::int64_t TraceOnMesh(const TriangleMesh& mesh, const double* velocity, SurfacePoint& point,
  double time, const AdvectionParameters& parameters, bool* truncated = nullptr,
  double length = 0.0);

// Crossings that make no progress (a trace turning around a vertex) before the
// trace is stopped there: more than any sane vertex valence.
constexpr int MaxStalledCrossings = 64;

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
};

/**
 * Traces surface points along a per-triangle constant velocity (world units per
 * unit of normalised time). Positions are (triangle, barycentric coordinates),
 * so traced points always lie on their triangle.
 */
class SurfaceTracer
{
public:
  /// `length`: the length unit (mean edge length), so delta = stepFraction x length;
  /// `capTriangles`: the triangles of the mesh whose diameter caps a trace (0: this mesh's).
  SurfaceTracer(const TriangleMesh& mesh, const double* velocity, const AdvectionParameters& p, double length,
    std::int64_t capTriangles = 0)
    : Mesh(mesh)
    , Velocity(velocity)
    , Mode(p.tracing)
    , Delta(p.stepFraction * length)
  {
    // A discrete gradient flow has no cycles in the continuum limit; should the
    // discretisation create one, cap the work per trace at a few mesh diameters
    // (a diameter is about sqrt(#triangles) edges).
    const std::int64_t triangles = capTriangles > 0 ? capTriangles : mesh.NumberOfTriangles();
    const double diameter = std::sqrt(2.0 * static_cast<double>(triangles)) + 1.0;
    this->MaxSteps = (this->Mode == Tracing::FaceCrossing)
      ? static_cast<std::int64_t>(16.0 * diameter) + 64
      : static_cast<std::int64_t>(std::ceil(4.0 * diameter / p.stepFraction)) + 64;
  }

  /// Trace q for time t; with `reach`, the rings of the triangles it reads are recorded there.
  std::int64_t Trace(SurfacePoint& q, double t, bool& truncated, RingReach* reach = nullptr) const
  {
    truncated = false;
    if (q.triangle < 0 || this->Mesh.Degenerate(q.triangle) || !(t > 0.0))
    {
      return 0;
    }
    if (reach)
    {
      reach->Visit(q.triangle);
    }
    return this->Mode == Tracing::FaceCrossing ? this->TraceFaceCrossing(q, t, truncated, reach)
                                               : this->TraceStepped(q, t, truncated, reach);
  }

  /**
   * Ask the memory system for what a trace through triangle f reads first (its
   * velocity, hat gradients and corners): advection loops call it some traces
   * ahead, so that the loads of several traces overlap. Changes nothing else.
   */
  void Prefetch(std::int64_t f) const
  {
    const double* g = this->Mesh.HatGradient(f, 0);
    __builtin_prefetch(g);
    __builtin_prefetch(g + 8);
    __builtin_prefetch(this->Velocity + 3 * f);
    __builtin_prefetch(this->Mesh.Corners(f));
  }

  /// Prefetch the triangles across the edges of f (see Prefetch).
  void PrefetchAcross(std::int64_t f) const
  {
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t g = this->Mesh.RawNeighbour(f, e);
      if (g >= 0)
      {
        this->Prefetch(g);
      }
    }
  }

private:
  Vec3 VelocityOf(std::int64_t f) const { return Load(this->Velocity + 3 * f); }

  /**
   * Time until q, moving with v, leaves its triangle, and the corner whose coordinate reaches 0.
   * `rates` receives the rates of change of the barycentric coordinates (for Advance).
   */
  double ExitTime(const SurfacePoint& q, const Vec3& v, int& corner, double rates[3]) const
  {
    double exit = std::numeric_limits<double>::infinity();
    corner = -1;
    for (int c = 0; c < 3; ++c)
    {
      const double rate = Dot(Load(this->Mesh.HatGradient(q.triangle, c)), v);
      rates[c] = rate;
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

  /**
   * Move q for dt inside its triangle with the barycentric rates of change `rates`
   * (ExitTime's); `exitCorner` >= 0 lands it exactly on that edge.
   */
  void Advance(SurfacePoint& q, const double rates[3], double dt, int exitCorner) const
  {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      double& l = q.barycentric[c];
      l = (c == exitCorner) ? 0.0 : std::max(0.0, l + rates[c] * dt);
      sum += l;
    }
    for (double& l : q.barycentric)
    {
      l = sum > 0.0 ? l / sum : 1.0 / 3.0;
    }
  }

  /**
   * Move q, on the edge opposite `corner` of its triangle, into the neighbouring
   * triangle g across that edge (same point, g's barycentric coordinates).
   * Returns g's corner opposite the edge. Every move into another triangle comes here.
   */
  int Enter(SurfacePoint& q, int corner, std::int64_t g, RingReach* reach) const
  {
    if (reach)
    {
      reach->Visit(g);
    }
    const std::int64_t* tf = this->Mesh.Corners(q.triangle);
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
    q.triangle = g;
    std::copy(lambda, lambda + 3, q.barycentric);
    return third;
  }

  /**
   * Move q across the edge opposite `corner` into the neighbouring triangle, with
   * the edge's hinge. Returns false (q unchanged) at boundary and non-manifold edges.
   */
  bool Cross(SurfacePoint& q, int corner, Hinge& hinge, RingReach* reach) const
  {
    const std::int64_t f = q.triangle;
    const std::int64_t g = this->Mesh.Neighbour(f, (corner + 1) % 3);
    if (g < 0)
    {
      return false;
    }
    const std::int64_t* tf = this->Mesh.Corners(f);
    const std::int64_t a = tf[(corner + 1) % 3];
    const std::int64_t b = tf[(corner + 2) % 3];
    const std::int64_t opposite = tf[corner];
    const int third = this->Enter(q, corner, g, reach);
    const Vec3 xa = Load(this->Mesh.Point(a));
    const Vec3 edge = Unit(Combine(1.0, Load(this->Mesh.Point(b)), -1.0, xa));
    auto perpendicular = [&](std::int64_t p) {
      const Vec3 w = Combine(1.0, Load(this->Mesh.Point(p)), -1.0, xa);
      return Unit(Combine(1.0, w, -Dot(w, edge), edge));
    };
    const Vec3 intoFirst = perpendicular(opposite);
    hinge = { edge, { -intoFirst[0], -intoFirst[1], -intoFirst[2] },
      perpendicular(this->Mesh.Corners(g)[third]) };
    return true;
  }

  /**
   * One Appendix A step: walk straight (a geodesic) along `direction` for time dt,
   * unfolding across edges; `direction` comes back expressed in the final triangle.
   * Returns false when the walk stops at a boundary, non-manifold edge or stall.
   */
  bool Walk(SurfacePoint& q, Vec3& direction, double dt, RingReach* reach) const
  {
    int stalled = 0;
    while (true)
    {
      int corner = -1;
      double rates[3];
      const double exit = this->ExitTime(q, direction, corner, rates);
      if (exit >= dt)
      {
        this->Advance(q, rates, dt, -1);
        return true;
      }
      this->Advance(q, rates, exit, corner);
      dt -= exit;
      stalled = exit > 0.0 ? 0 : stalled + 1;
      Hinge hinge;
      if (stalled > MaxStalledCrossings || !this->Cross(q, corner, hinge, reach))
      {
        return false;
      }
      direction = hinge.Unfold(direction);
    }
  }

  /// The paper's Appendix A Trace with steps of at most delta.
  std::int64_t TraceStepped(SurfacePoint& q, double t, bool& truncated, RingReach* reach) const
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
      if (!this->Walk(q, previous, dt, reach))
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
  std::int64_t TraceFaceCrossing(SurfacePoint& q, double t, bool& truncated, RingReach* reach) const
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
      double rates[3];
      const double exit = this->ExitTime(q, v, corner, rates);
      if (exit >= t)
      {
        this->Advance(q, rates, t, -1);
        break;
      }
      this->Advance(q, rates, exit, corner);
      t -= exit;
      ++steps;
      stalled = exit > 0.0 ? 0 : stalled + 1;
      // The hinge's frame without building it: along the edge E = b - a (length L),
      // with heights h = 2 area / L, its unit vectors are E / L, outOfFirst =
      // -h_f grad(lambda_corner) of f and intoSecond = h_g grad(lambda_third) of g,
      // so every test below is the hinge's own times a positive factor.
      const std::int64_t f = q.triangle;
      const std::int64_t g = this->Mesh.Neighbour(f, (corner + 1) % 3);
      if (g < 0)
      {
        break; // boundary or non-manifold edge
      }
      const std::int64_t* tf = this->Mesh.Corners(f);
      const Vec3 xa = Load(this->Mesh.Point(tf[(corner + 1) % 3]));
      const Vec3 edge = Combine(1.0, Load(this->Mesh.Point(tf[(corner + 2) % 3])), -1.0, xa);
      SurfacePoint across = q;
      const int third = this->Enter(across, corner, g, reach);
      const Vec3 next = this->VelocityOf(g);
      // The speeds out of f and into g across the edge, times |E| / 2: both > 0
      // when the trace leaves f and the next flow leaves the edge.
      const double outOfFirst = this->Mesh.Area(f) * -rates[corner];
      const double intoSecond = this->Mesh.Area(g) * Dot(Load(this->Mesh.HatGradient(g, third)), next);
      // |E|^2 <next folded back into f's plane, v>: the paper's direction test, in the unfolded frame.
      if (Dot(next, edge) * Dot(v, edge) + 4.0 * outOfFirst * intoSecond <= 0.0)
      {
        break; // the flow reverses
      }
      if (intoSecond > 0.0)
      {
        q = across;
        v = next;
        continue;
      }
      // Both triangles push into the edge: slide along it, with the convex
      // combination of the two velocities that has no component across it.
      const double w = outOfFirst / (outOfFirst - intoSecond);
      const double rate = ((1.0 - w) * Dot(v, edge) + w * Dot(next, edge)) / Dot(edge, edge);
      if (!(outOfFirst - intoSecond > 0.0) || rate == 0.0)
      {
        break; // a sink on the edge
      }
      steps += this->Slide(q, corner, rate, t);
      if (t > 0.0)
      {
        return steps + this->TraceStepped(q, t, truncated, reach);
      }
    }
    return steps;
  }

  /**
   * Slide q along the edge opposite `corner` until t or a vertex; `rate` is the
   * rate of change of the barycentric coordinate of corner + 2 (> 0: towards it).
   */
  std::int64_t Slide(SurfacePoint& q, int corner, double rate, double& t) const
  {
    const int ia = (corner + 1) % 3;
    const int ib = (corner + 2) % 3;
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

} // namespace shock

#endif
