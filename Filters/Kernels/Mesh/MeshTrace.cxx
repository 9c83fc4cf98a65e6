#include "MeshTrace.h"

namespace shock
{

std::int64_t TraceOnMesh(const TriangleMesh& mesh, const double* velocity, SurfacePoint& point,
  double time, const AdvectionParameters& parameters, bool* truncated, double length)
{
  bool cut = false;
  const SurfaceTracer tracer(
    mesh, velocity, parameters, length > 0.0 ? length : mesh.MeanEdgeLength());
  const std::int64_t steps = tracer.Trace(point, time, cut);
  if (truncated)
  {
    *truncated = cut;
  }
  return steps;
}

} // namespace shock
