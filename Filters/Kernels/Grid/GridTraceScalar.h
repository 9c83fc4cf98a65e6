/**
 * @file GridTraceScalar.h
 * @brief The fast path of the face-crossing trace (docs/performance.md): the
 * tracers GridTracer::Trace takes on images (D = 2) and volumes (D = 3). They
 * follow the rule of GridTracer::TraceFaceCrossing (GridTrace.h) with the
 * position and velocity in scalars and the boundary ahead found from
 * reciprocal speeds, and cross every boundary with its shared step
 * (GridTracer::Cross). The same paths to rounding:
 * GridSteps.TheImageAndVolumeTracersFollowTheGeneralRule and
 * GridSteps.TheImageTracerFollowsTheVolumeTracerOnAFlatVolume.
 */
#ifndef GridTraceScalar_h
#define GridTraceScalar_h

#include "GridAvx2.h"
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
 * What a trace reports besides its steps: whether the step cap cut it, and,
 * where the tracer has a fence (GridTracer: the faces around the samples a
 * piece of a distributed image traces, AdvectionParameters::writtenSamples),
 * how far beyond it the trace went. `reach` is the caller's running maximum
 * (several traces may share it), per active axis d the deepest face layer
 * below the fence at 2d and above it at 2d + 1; null when not wanted.
 */
template <int D>
struct TraceMarks
{
  bool truncated = false;
  std::array<std::int64_t, 2 * D>* reach = nullptr;
};

template <int D>
class GridTracer;

/// The image and volume tracers of GridTracer<D> (a friend of it).
template <int D>
struct ScalarTracers
{
  using Tracer = GridTracer<D>;
  using Entry = typename Tracer::Entry;

  /**
   * TraceFaceCrossing on an image (D = 2), the same rules with the state in
   * scalars. The boundary ahead is found without dividing: with d the distance
   * to the boundary ahead along an axis and |v| the speed along it, the trace
   * leaves along y first when d_y |v_x| < d_x |v_y|, and it stays in its face
   * when d >= t |v| along that axis; the one division, d / |v|, is the time of
   * a crossing. An axis slid along has velocity 0 there and is never left.
   */
  static SHOCK_NOINLINE std::int64_t TraceFaceCrossingPlanar(const Tracer& tracer,
    std::array<double, D>& q, std::array<std::int64_t, D> c, std::int64_t f, double t, TraceMarks<D>& marks)
  {
    return PlanarTrace(tracer, q, c, f, t, marks);
  }
#ifdef SHOCK_GRID_AVX2
  /// TraceFaceCrossingPlanar built for AVX2.
  static SHOCK_NOINLINE SHOCK_TARGET_AVX2 std::int64_t TraceFaceCrossingPlanarAvx2(const Tracer& tracer,
    std::array<double, D>& q, std::array<std::int64_t, D> c, std::int64_t f, double t, TraceMarks<D>& marks)
  {
    return PlanarTrace(tracer, q, c, f, t, marks);
  }
#endif

  /**
   * TraceFaceCrossing in a volume (D = 3), the same rules with the position and
   * velocity in scalars: the time to the boundary ahead along each axis is the
   * distance to it times the reciprocal speed, computed from the velocity alone
   * (its division overlaps the position's chain of operations); an axis without
   * motion, or the one slid along, has an infinite time and is never left.
   */
  static std::int64_t TraceFaceCrossingSpatial(const Tracer& tracer, std::array<double, D>& q,
    std::array<std::int64_t, D> c, std::int64_t f, double t, TraceMarks<D>& marks)
  {
    static_assert(D == 3, "the spatial tracer is for volumes");
    constexpr double never = std::numeric_limits<double>::infinity();
    std::array<double, D> start;
    tracer.Load(f, start);
    if (!(tracer.Dot(start, start) > 0.0))
    {
      return 0;
    }
    double vx = start[0], vy = start[1], vz = start[2];
    double x = q[0], y = q[1], z = q[2];
    int pinned = -1; // axis of the boundary the trace slides on; c is the lower face there
    std::int64_t steps = 0;
    while (t > 0.0)
    {
      double exitTime = 0.0;
      const int axis = SpatialExit(x, y, z, vx, vy, vz, c, exitTime);
      if (!(exitTime < never))
      {
        break; // no motion left (a sliding velocity of zero)
      }
      if (exitTime >= t)
      {
        x += vx * t;
        y += vy * t;
        z += vz * t;
        break; // the time is used up in this face
      }
      x += vx * exitTime;
      y += vy * exitTime;
      z += vz * exitTime;
      t -= exitTime;
      ++steps;
      const double across = axis == 0 ? vx : (axis == 1 ? vy : vz);
      const int dir = across > 0.0 ? 1 : -1;
      const double boundary = static_cast<double>(dir > 0 ? c[axis] + 1 : c[axis]);
      x = axis == 0 ? boundary : x;
      y = axis == 1 ? boundary : y;
      z = axis == 2 ? boundary : z;
      const std::array<double, D> v{ vx, vy, vz };
      std::array<double, D> w;
      const Entry entry = tracer.Cross(c, f, axis, dir, pinned, steps, marks, v, w);
      if (entry == Entry::Stop)
      {
        break;
      }
      if (entry == Entry::Corner)
      {
        q = { x, y, z };
        return steps + tracer.TraceSteppedFrom(q, c, t, marks);
      }
      vx = w[0];
      vy = w[1];
      vz = w[2];
    }
    q = { x, y, z };
    tracer.ClampToGrid(q);
    return steps;
  }

private:
  /// The body of TraceFaceCrossingPlanar, built into each of its two versions.
  static SHOCK_ALWAYS_INLINE std::int64_t PlanarTrace(const Tracer& tracer, std::array<double, D>& q,
    std::array<std::int64_t, D> c, std::int64_t f, double t, TraceMarks<D>& marks)
  {
    static_assert(D == 2, "the planar tracer is for images");
    const double hx = tracer.L.h2[0];
    const double hy = tracer.L.h2[1];
    double vx = tracer.V[2 * f];
    double vy = tracer.V[2 * f + 1];
    if (!(hx * vx * vx + hy * vy * vy > 0.0))
    {
      return 0;
    }
    double x = q[0];
    double y = q[1];
    int pinned = -1; // axis of the boundary the trace slides on; c is the lower face there
    std::int64_t steps = 0;
    while (t > 0.0)
    {
      const double sx = std::abs(vx);
      const double sy = std::abs(vy);
      // The reciprocal speeds depend on the velocity alone: computed here, the
      // divisions run while the position's distances are found.
      const double rx = 1.0 / sx;
      const double ry = 1.0 / sy;
      const double cx = static_cast<double>(c[0]);
      const double cy = static_cast<double>(c[1]);
      const double dx = std::max((cx + static_cast<double>(vx > 0.0) - x) * std::copysign(1.0, vx), 0.0);
      const double dy = std::max((cy + static_cast<double>(vy > 0.0) - y) * std::copysign(1.0, vy), 0.0);
      const int axis = (vx == 0.0 || dy * sx < dx * sy) ? 1 : 0;
      const double distance = axis ? dy : dx;
      const double speed = axis ? sy : sx;
      if (distance >= t * speed)
      {
        x += vx * t;
        y += vy * t;
        break; // the time is used up in this face
      }
      const double exitTime = std::min(distance * (axis ? ry : rx), t);
      x += vx * exitTime;
      y += vy * exitTime;
      t -= exitTime;
      ++steps;
      const double across = axis ? vy : vx;
      const int dir = across > 0.0 ? 1 : -1;
      const double boundary = static_cast<double>(dir > 0 ? c[axis] + 1 : c[axis]);
      x = axis ? x : boundary;
      y = axis ? boundary : y;
      const std::array<double, D> v{ vx, vy };
      std::array<double, D> w;
      const Entry entry = tracer.Cross(c, f, axis, dir, pinned, steps, marks, v, w);
      if (entry == Entry::Stop)
      {
        break;
      }
      if (entry == Entry::Corner)
      {
        q = { x, y };
        return steps + tracer.TraceSteppedFrom(q, c, t, marks);
      }
      vx = w[0];
      vy = w[1];
    }
    q = { x, y };
    tracer.ClampToGrid(q);
    return steps;
  }

  /**
   * The exit rule of the volume tracer (GridTracer::ExitAhead's in scalars):
   * the time to the boundary ahead along each axis is the distance to it times
   * the reciprocal speed (its division overlaps the position's chain of
   * operations); an axis without motion has an infinite time. On a tie, the
   * lower axis (as ExitAhead).
   */
  static SHOCK_ALWAYS_INLINE int SpatialExit(double x, double y, double z, double vx, double vy, double vz,
    const std::array<std::int64_t, D>& c, double& exitTime)
  {
    constexpr double never = std::numeric_limits<double>::infinity();
    const double rx = 1.0 / std::abs(vx);
    const double ry = 1.0 / std::abs(vy);
    const double rz = 1.0 / std::abs(vz);
    const double dx = std::max((static_cast<double>(c[0]) + static_cast<double>(vx > 0.0) - x) * std::copysign(1.0, vx), 0.0);
    const double dy = std::max((static_cast<double>(c[1]) + static_cast<double>(vy > 0.0) - y) * std::copysign(1.0, vy), 0.0);
    const double dz = std::max((static_cast<double>(c[2]) + static_cast<double>(vz > 0.0) - z) * std::copysign(1.0, vz), 0.0);
    const double tx = vx == 0.0 ? never : dx * rx;
    const double ty = vy == 0.0 ? never : dy * ry;
    const double tz = vz == 0.0 ? never : dz * rz;
    int axis = ty < tx ? 1 : 0;
    exitTime = std::min(tx, ty);
    axis = tz < exitTime ? 2 : axis;
    exitTime = std::min(exitTime, tz);
    return axis;
  }
};

} // namespace grid
} // namespace shock

#endif
