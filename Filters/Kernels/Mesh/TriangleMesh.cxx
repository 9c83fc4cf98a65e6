#include "TriangleMesh.h"

#include <limits>
#include <utility>

namespace shock
{

TriangleMesh::TriangleMesh()
  : connectivity(std::make_shared<MeshConnectivity>())
{
}

Status TriangleMesh::Build(const TriangleMeshView& view, int threads)
{
  if (view.numberOfPoints < 0 || view.numberOfTriangles < 0 ||
    (view.numberOfPoints > 0 && !view.points) || (view.numberOfTriangles > 0 && !view.triangles))
  {
    return { "invalid mesh arrays" };
  }
  if (view.numberOfTriangles > std::numeric_limits<std::int64_t>::max() / 9)
  {
    return { "too many triangles" };
  }
  // Connectivity first (it depends on the ids only), then geometry.
  auto built = std::make_shared<MeshConnectivity>();
  const Status status = built->Build(view.numberOfPoints,
    IdVector(view.triangles, view.triangles + 3 * view.numberOfTriangles), threads);
  if (!status.Ok())
  {
    return status;
  }
  return this->Build(std::move(built), view.points, threads);
}

Status TriangleMesh::Build(
  std::int64_t numberOfPoints, const double* points, IdVector triangles, int threads)
{
  if (numberOfPoints < 0 || (numberOfPoints > 0 && !points) || triangles.size() % 3 != 0)
  {
    return { "invalid mesh arrays" };
  }
  auto built = std::make_shared<MeshConnectivity>();
  const Status status = built->Build(numberOfPoints, std::move(triangles), threads);
  if (!status.Ok())
  {
    return status;
  }
  return this->Build(std::move(built), points, threads);
}

Status TriangleMesh::BuildSplit(const TriangleMesh& source,
  const std::vector<std::int64_t>& original, IdVector triangles, int threads)
{
  auto built = std::make_shared<MeshConnectivity>();
  const Status status = built->BuildSplit(source.Connectivity(), original, std::move(triangles), threads);
  if (!status.Ok())
  {
    return status;
  }
  if (!built->DerivedFromSource())
  {
    // Not a split of the source: the general way, from the copied positions.
    std::vector<double> points(3 * original.size());
    for (size_t q = 0; q < original.size(); ++q)
    {
      const std::int64_t p = original[q];
      if (p < 0 || p >= source.NumberOfPoints())
      {
        return { "a point copies a point id outside [0, number of points)" };
      }
      std::copy(source.Point(p), source.Point(p) + 3, &points[3 * q]);
    }
    return this->Build(std::move(built), points.data(), threads);
  }
  this->geometry.ComputeFromCopies(source.Geometry(), original, threads);
  this->connectivity = std::move(built);
  const bool any = this->connectivity->NumberOfTriangles() > 0;
  this->corners = any ? this->connectivity->Corners(0) : nullptr;
  this->neighbours = any ? this->connectivity->Neighbours() : nullptr;
  return {};
}

Status TriangleMesh::Build(
  std::shared_ptr<const MeshConnectivity> shared, const double* points, int threads)
{
  if (!shared)
  {
    return { "invalid mesh arrays" };
  }
  const Status status = this->geometry.Compute(*shared, points, threads);
  if (!status.Ok())
  {
    return status;
  }
  this->connectivity = std::move(shared);
  const bool any = this->connectivity->NumberOfTriangles() > 0;
  this->corners = any ? this->connectivity->Corners(0) : nullptr;
  this->neighbours = any ? this->connectivity->Neighbours() : nullptr;
  return {};
}

} // namespace shock
