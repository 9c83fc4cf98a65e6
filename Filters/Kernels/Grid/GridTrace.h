/**
 * @file GridTrace.h
 * @brief Appendix A Trace on a regular grid, in index coordinates: a point moved
 * back along the per-face constant flow, exactly from face to face
 * (Tracing::FaceCrossing) or in steps of at most delta (Tracing::Stepped).
 * The rule for any D and the step every face-crossing tracer shares are here;
 * the tracers written for images and volumes are in GridTraceScalar.h.
 * Loops use OpenMP: include only from translation units built with it.
 */
#ifndef GridTrace_h
#define GridTrace_h

#include "GridAvx2.h"
#include "GridLattice.h"
#include "GridTraceScalar.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace shock
{
namespace grid
{

/**
 * Appendix A Trace on the grid, in index coordinates. The flow is constant per
 * face; a trace stops when the time is used up, when the flow reverses
 * (<v, v0> <= 0, measured in the physical metric), at the grid boundary, or at
 * the step cap that guards against cycles of the discrete flow.
 */
template <int D>
class GridTracer
{
public:
  GridTracer(const Lattice<D>& lattice, const float* velocity, const AdvectionParameters& p)
    : L(lattice)
    , V(velocity)
    , Mode(p.tracing)
    , Delta(p.stepFraction)
  {
    // A discrete gradient flow has no cycles in the continuum limit; in case the
    // discretisation creates one, cap the work per trace at a few grid diameters.
    double diameter = 0.0;
    std::int64_t samples = 0;
    for (int d = 0; d < D; ++d)
    {
      diameter += L.wholeN[d] * L.h[d];
      samples += L.wholeN[d];
    }
    this->MaxSteps = (this->Mode == Tracing::FaceCrossing)
      ? 8 * samples
      : static_cast<std::int64_t>(std::ceil(4.0 * diameter / this->Delta)) + 1;
    // The fence: the faces the traces of the written samples start in (the
    // faces beside them), the whole grid by default.
    for (int d = 0; d < D; ++d)
    {
      const std::int64_t first = p.writtenSamples[2 * L.axis[d]];
      const std::int64_t last = p.writtenSamples[2 * L.axis[d] + 1];
      const bool whole = first > last;
      this->FenceLow[d] = whole ? 0 : std::max<std::int64_t>(first - 1, 0);
      this->FenceHigh[d] = whole ? L.m[d] - 1 : std::min(last, L.m[d] - 1);
    }
  }

  /**
   * Trace q (index coordinates), which lies in face f with coordinates c (as
   * FaceOf finds them), for time t; returns the number of steps taken. Wide:
   * the image tracer's AVX2 build (GridAvx2.h), for callers that checked UsesAvx2.
   */
  template <bool Wide = false>
  std::int64_t Trace(std::array<double, D>& q, const std::array<std::int64_t, D>& c,
    std::int64_t f, double t, TraceMarks<D>& marks) const
  {
    if (this->Mode != Tracing::FaceCrossing)
    {
      return this->TraceStepped(q, c, f, t, marks);
    }
#ifdef SHOCK_GRID_AVX2
    // The volume tracer has no AVX2 build: it was slower (its selects become
    // blends on the position's chain; docs/performance.md).
    if constexpr (Wide && D == 2)
    {
      return ScalarTracers<D>::TraceFaceCrossingPlanarAvx2(*this, q, c, f, t, marks);
    }
#endif
    if constexpr (D == 2)
    {
      return ScalarTracers<D>::TraceFaceCrossingPlanar(*this, q, c, f, t, marks);
    }
    else if constexpr (D == 3)
    {
      return ScalarTracers<D>::TraceFaceCrossingSpatial(*this, q, c, f, t, marks);
    }
    else
    {
      return this->TraceFaceCrossing(q, c, f, t, marks);
    }
  }

  /// Trace, for callers that want only the step cap's mark.
  template <bool Wide = false>
  std::int64_t Trace(std::array<double, D>& q, const std::array<std::int64_t, D>& c, std::int64_t f, double t,
    bool& truncated) const
  {
    TraceMarks<D> marks;
    const std::int64_t steps = this->template Trace<Wide>(q, c, f, t, marks);
    truncated = marks.truncated;
    return steps;
  }

  /// The most steps a trace takes (a guard against cycles of the discrete flow: a few whole-grid diameters).
  std::int64_t StepCap() const { return this->MaxSteps; }

  /// The fence along active axis d: the lowest and the highest face coordinate inside it.
  std::int64_t FenceLowest(int d) const { return this->FenceLow[d]; }
  std::int64_t FenceHighest(int d) const { return this->FenceHigh[d]; }

  /// The back-trace velocity of face f: D floats, index units.
  const float* Velocity(std::int64_t f) const { return this->V + f * D; }

  /// True when Trace takes the exact face-to-face path (its steps are face crossings).
  bool CrossesFaces() const { return this->Mode == Tracing::FaceCrossing; }

  /// The face holding q (clamped to the grid): its index, and its coordinates in c.
  std::int64_t FaceOf(const std::array<double, D>& q, std::array<std::int64_t, D>& c) const
  {
    std::int64_t f = 0;
    for (int d = 0; d < D; ++d)
    {
      c[d] = std::min<std::int64_t>(std::max<std::int64_t>(static_cast<std::int64_t>(q[d]), 0), L.m[d] - 1);
      f += c[d] * L.faceStride[d];
    }
    return f;
  }

  /// How a trace goes on after reaching a face boundary (Cross).
  enum class Entry
  {
    Go,    ///< on with the velocity w
    Stop,  ///< the grid boundary, the step cap, the flow reverses, or a sliding velocity vanishes
    Corner ///< pushed onto a grid edge or corner: the rest of the trace is stepped
  };

private:
  friend struct ScalarTracers<D>; // the image and volume tracers: Cross and its helpers

  /// Dot product of index-space velocities in the physical metric.
  template <typename A, typename B>
  double Dot(const A& a, const B& b) const
  {
    double dot = 0.0;
    for (int d = 0; d < D; ++d)
    {
      dot += L.h2[d] * a[d] * b[d];
    }
    return dot;
  }

  void Load(std::int64_t f, std::array<double, D>& v) const
  {
    for (int d = 0; d < D; ++d)
    {
      v[d] = this->V[f * D + d];
    }
  }

  /**
   * Filippov velocity on the boundary between face `lowerFace` and its upper
   * neighbour along `axis`, both pushing into it: the convex combination of their
   * velocities with no component across the boundary. False if it vanishes.
   */
  bool Sliding(std::int64_t lowerFace, int axis, std::array<double, D>& v) const
  {
    std::array<double, D> a, b;
    this->Load(lowerFace, a);
    this->Load(lowerFace + L.faceStride[axis], b);
    const double lambda = -b[axis] / (a[axis] - b[axis]);
    for (int d = 0; d < D; ++d)
    {
      v[d] = lambda * a[d] + (1.0 - lambda) * b[d];
    }
    v[axis] = 0.0;
    return this->Dot(v, v) > 0.0;
  }

public:
  /**
   * Exact tracing: straight to the next face boundary, then into the neighbour.
   * Where both faces of a boundary push towards it (a valley of the potential
   * crossed by the back-trace), the trace slides along the boundary with the
   * Filippov velocity, the convex combination of the two flows that is tangent
   * to it: this is the delta -> 0 limit of the zig-zag of the stepped trace.
   * Where the trace is pushed onto a grid edge or corner from several faces at
   * once, the exact rule is not unique; the rest of that trace uses the paper's
   * stepping, which zig-zags along the edge (or stops at a sink).
   * This is the rule for any D; Trace takes the image and volume tracers
   * written for D = 2 and 3 (GridTraceScalar.h: the same paths, to rounding).
   */
  std::int64_t TraceFaceCrossing(std::array<double, D>& q, std::array<std::int64_t, D> c,
    std::int64_t f, double t, TraceMarks<D>& marks) const
  {
    std::array<double, D> v;
    this->Load(f, v);
    if (!(this->Dot(v, v) > 0.0))
    {
      return 0;
    }
    int pinned = -1; // axis of the boundary the trace slides on; c is the lower face there
    std::int64_t steps = 0;
    while (t > 0.0)
    {
      double exitTime = 0.0;
      const int exitAxis = this->ExitAhead(q, c, v, pinned, exitTime);
      if (!(exitTime < std::numeric_limits<double>::infinity()))
      {
        break; // no motion left (a sliding velocity of zero)
      }
      exitTime = std::max(exitTime, 0.0);
      if (exitTime >= t)
      {
        for (int d = 0; d < D; ++d)
        {
          q[d] += v[d] * t;
        }
        break; // the time is used up in this face
      }
      for (int d = 0; d < D; ++d)
      {
        q[d] += v[d] * exitTime;
      }
      t -= exitTime;
      const int dir = v[exitAxis] > 0.0 ? 1 : -1;
      q[exitAxis] = static_cast<double>(dir > 0 ? c[exitAxis] + 1 : c[exitAxis]);
      ++steps;
      std::array<double, D> w;
      const Entry entry = this->Cross(c, f, exitAxis, dir, pinned, steps, marks, v, w);
      if (entry == Entry::Stop)
      {
        break;
      }
      if (entry == Entry::Corner)
      {
        return steps + this->TraceSteppedFrom(q, c, t, marks);
      }
      v = w;
    }
    this->ClampToGrid(q);
    return steps;
  }

private:
  /**
   * The first boundary of face c that a trace at q moving with v reaches, and
   * the time to it (infinite when it does not move), without branches (the exit
   * axis is not predictable): with r = 1 / v, (c + 1 - q) r is the time to the
   * upper boundary when v > 0 and <= 0 otherwise, (c - q) r the time to the
   * lower one when v < 0 and <= 0 otherwise; the larger is the boundary ahead.
   * An axis without motion (r infinite) or the one slid along is never left;
   * on a tie, the lower axis.
   */
  int ExitAhead(const std::array<double, D>& q, const std::array<std::int64_t, D>& c,
    const std::array<double, D>& v, int pinned, double& exitTime) const
  {
    constexpr double never = std::numeric_limits<double>::infinity();
    std::array<double, D> te;
    for (int d = 0; d < D; ++d)
    {
      const double r = 1.0 / v[d];
      const double lower = static_cast<double>(c[d]);
      const double ahead = std::max((lower + 1.0 - q[d]) * r, (lower - q[d]) * r);
      te[d] = (d != pinned && std::abs(r) < never) ? ahead : never;
    }
    int exitAxis = 0;
    exitTime = te[0];
    for (int d = 1; d < D; ++d)
    {
      const int earlier = te[d] < exitTime;
      exitAxis += earlier * (d - exitAxis);
      exitTime = std::min(exitTime, te[d]);
    }
    return exitAxis;
  }

  /**
   * The step every face-crossing tracer shares: the trace has reached the
   * boundary of face f along `axis`, moving in direction `dir` with velocity
   * v, after `steps` crossings. Into the neighbouring face (c and f follow)
   * with the velocity w to go on with (EnterFace), or Stop at the grid
   * boundary and at the step cap (`truncated`), or Stop / Corner as EnterFace
   * decides.
   */
  SHOCK_ALWAYS_INLINE Entry Cross(std::array<std::int64_t, D>& c, std::int64_t& f, int axis, int dir,
    int& pinned, std::int64_t steps, TraceMarks<D>& marks, const std::array<double, D>& v,
    std::array<double, D>& w) const
  {
    const std::int64_t next = c[axis] + dir;
    if (next < 0 || next >= L.m[axis])
    {
      return Entry::Stop; // grid boundary
    }
    if (steps >= this->MaxSteps)
    {
      marks.truncated = true;
      return Entry::Stop;
    }
    this->Fence(axis, next, marks);
    const std::int64_t left = f;
    c[axis] = next;
    if constexpr (D == 2)
    {
      f += axis ? dir * L.faceStride[1] : dir; // rows are contiguous: one load fewer on the image's hot path
    }
    else
    {
      f += dir * L.faceStride[axis];
    }
    return this->EnterFace(c, f, left, axis, dir, pinned, v, w);
  }

  /**
   * Into face f (coordinates c), crossed along `axis` in direction `dir` from
   * face `left` with velocity v: the velocity w to go on with. Off a boundary,
   * the trace stops where the flow reverses (a ridge of the potential), and
   * slides along the boundary just crossed where both faces push into it (the
   * Filippov velocity). On a boundary slid along, SlideOn decides, and a
   * velocity that pushes back across the crossing means a corner.
   */
  SHOCK_ALWAYS_INLINE Entry EnterFace(std::array<std::int64_t, D>& c, std::int64_t& f,
    std::int64_t left, int axis, int dir, int& pinned, const std::array<double, D>& v,
    std::array<double, D>& w) const
  {
    if (pinned >= 0)
    {
      if (!this->SlideOn(c, f, pinned, v, w))
      {
        return Entry::Stop;
      }
      return w[axis] * dir < 0.0 ? Entry::Corner : Entry::Go;
    }
    this->Load(f, w);
    if (!(this->Dot(w, v) > 0.0))
    {
      return Entry::Stop; // the flow reverses: a ridge of the potential
    }
    if (w[axis] * dir < 0.0)
    {
      // Both faces push towards the boundary just crossed: slide along it.
      pinned = axis;
      if (dir > 0)
      {
        c[pinned] -= 1;
        f = left;
      }
      if (!this->Sliding(f, pinned, w))
      {
        return Entry::Stop;
      }
    }
    return Entry::Go;
  }

  /// The stepped rest of a trace at q (clamped to the grid), c its face's coordinates.
  std::int64_t TraceSteppedFrom(
    std::array<double, D>& q, std::array<std::int64_t, D>& c, double t, TraceMarks<D>& marks) const
  {
    this->ClampToGrid(q);
    const std::int64_t face = this->FaceOf(q, c);
    for (int d = 0; d < D; ++d)
    {
      this->Fence(d, c[d], marks);
    }
    return this->TraceStepped(q, c, face, t, marks);
  }

  /**
   * On the boundary slid along (`pinned`, c the lower of its two faces), the
   * trace has moved into the next pair of faces: it slides on with their
   * Filippov velocity w where both still push into the boundary, else it
   * leaves the boundary into the face that does not push back into it (c, f
   * and `pinned` follow). False when the flow reverses.
   */
  bool SlideOn(std::array<std::int64_t, D>& c, std::int64_t& f, int& pinned, const std::array<double, D>& v,
    std::array<double, D>& w) const
  {
    // Sliding into the next pair of faces along the pinned boundary.
    std::array<double, D> lower, upper;
    this->Load(f, lower);
    this->Load(f + L.faceStride[pinned], upper);
    if (lower[pinned] > 0.0 && upper[pinned] < 0.0)
    {
      this->Sliding(f, pinned, w);
    }
    else
    {
      // Leave the boundary into a face that does not push back into it.
      const bool lowerOk = lower[pinned] <= 0.0;
      const bool upperOk = upper[pinned] >= 0.0;
      const bool takeUpper =
        upperOk && (!lowerOk || this->Dot(upper, v) > this->Dot(lower, v));
      if (takeUpper)
      {
        c[pinned] += 1;
        f += L.faceStride[pinned];
      }
      w = takeUpper ? upper : lower;
      pinned = -1;
    }
    if (!(this->Dot(w, v) > 0.0))
    {
      return false; // the flow reverses
    }
    return true;
  }

  std::int64_t TraceStepped(std::array<double, D>& q, std::array<std::int64_t, D> c,
    std::int64_t f, double t, TraceMarks<D>& marks) const
  {
    const float* v = this->V + f * D;
    const float* v0 = v;
    std::int64_t steps = 0;
    while (t > 0.0 && this->Dot(v, v0) > 0.0)
    {
      const double speed = std::sqrt(this->Dot(v, v));
      const double dt = std::min(t, this->Delta / speed);
      bool outside = false;
      for (int d = 0; d < D; ++d)
      {
        q[d] += v[d] * dt;
        outside = outside || q[d] < 0.0 || q[d] > static_cast<double>(L.m[d]);
      }
      t -= dt;
      ++steps;
      if (outside)
      {
        break; // grid boundary
      }
      if (steps >= this->MaxSteps)
      {
        marks.truncated = true;
        break;
      }
      v0 = v;
      v = this->V + this->FaceOf(q, c) * D;
      for (int d = 0; d < D; ++d)
      {
        this->Fence(d, c[d], marks);
      }
    }
    this->ClampToGrid(q);
    return steps;
  }

  /// Record in `marks` a face coordinate along axis d beyond the fence (every face a trace reads passes here).
  SHOCK_ALWAYS_INLINE void Fence(int d, std::int64_t coordinate, TraceMarks<D>& marks) const
  {
    if (coordinate < this->FenceLow[d] || coordinate > this->FenceHigh[d])
    {
      const bool below = coordinate < this->FenceLow[d];
      const std::int64_t depth = below ? this->FenceLow[d] - coordinate : coordinate - this->FenceHigh[d];
      if (marks.reach)
      {
        std::int64_t& deepest = (*marks.reach)[2 * d + (below ? 0 : 1)];
        deepest = std::max(deepest, depth);
      }
    }
  }

  void ClampToGrid(std::array<double, D>& q) const
  {
    for (int d = 0; d < D; ++d)
    {
      q[d] = std::min(std::max(q[d], 0.0), static_cast<double>(L.m[d]));
    }
  }

  const Lattice<D>& L;
  const float* V;
  Tracing Mode;
  double Delta;
  std::array<std::int64_t, D> FenceLow;
  std::array<std::int64_t, D> FenceHigh;
  std::int64_t MaxSteps = 0;
};

} // namespace grid
} // namespace shock

#endif
