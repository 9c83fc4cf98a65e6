// Tests of the synthetic test meshes (TestMeshes.h) themselves: the topology and
// geometry the mesh-filter tests rely on (closedness, orientation, Euler
// characteristic, boundaries, positions, determinism).
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

namespace
{
using namespace shocktest;
using Edge = std::pair<std::int64_t, std::int64_t>;

/// The combinatorial facts a test asserts about a mesh.
struct Topology
{
  std::int64_t usedPoints = 0;
  std::int64_t edges = 0;            ///< distinct undirected edges
  std::int64_t boundaryEdges = 0;    ///< edges of one triangle
  std::int64_t nonManifoldEdges = 0; ///< edges of three or more triangles
  bool oriented = true;              ///< no directed edge twice, and interior edges once each way
  int boundaryLoops = 0;             ///< -1 when a point starts two boundary edges
  int components = 0;                ///< edge-connected groups of used points

  std::int64_t Euler(const MeshData& mesh) const
  {
    return usedPoints - edges + mesh.NumberOfTriangles();
  }
  bool Closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
};

Topology Analyse(const MeshData& mesh)
{
  Topology topology;
  std::map<Edge, int> directed, undirected;
  std::set<std::int64_t> used(mesh.triangles.begin(), mesh.triangles.end());
  topology.usedPoints = static_cast<std::int64_t>(used.size());
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = mesh.triangles[3 * t + k], b = mesh.triangles[3 * t + (k + 1) % 3];
      ++directed[{ a, b }];
      ++undirected[{ std::min(a, b), std::max(a, b) }];
    }
  }
  topology.edges = static_cast<std::int64_t>(undirected.size());
  std::map<std::int64_t, std::int64_t> nextOnBoundary;
  for (const auto& [edge, count] : directed)
  {
    const int uses =
      undirected[{ std::min(edge.first, edge.second), std::max(edge.first, edge.second) }];
    const auto reverse = directed.find({ edge.second, edge.first });
    topology.oriented = topology.oriented && count == 1 && (uses != 2 || reverse != directed.end());
    if (uses == 1 && !nextOnBoundary.emplace(edge.first, edge.second).second)
    {
      topology.boundaryLoops = -1;
    }
  }
  for (const auto& [edge, uses] : undirected)
  {
    topology.boundaryEdges += uses == 1;
    topology.nonManifoldEdges += uses > 2;
  }
  if (topology.boundaryLoops == 0)
  {
    std::set<std::int64_t> visited;
    for (const auto& [start, next] : nextOnBoundary)
    {
      if (visited.insert(start).second)
      {
        ++topology.boundaryLoops;
        for (auto at = nextOnBoundary.find(next);
             at != nextOnBoundary.end() && visited.insert(at->first).second;
             at = nextOnBoundary.find(at->second))
        {
        }
      }
    }
  }
  // Union-find over the triangles' points.
  std::vector<std::int64_t> parent(static_cast<size_t>(mesh.NumberOfPoints()));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&parent](std::int64_t p) {
    while (parent[static_cast<size_t>(p)] != p)
    {
      p = parent[static_cast<size_t>(p)] =
        parent[static_cast<size_t>(parent[static_cast<size_t>(p)])];
    }
    return p;
  };
  for (const auto& [edge, uses] : undirected)
  {
    parent[static_cast<size_t>(root(edge.first))] = root(edge.second);
  }
  for (std::int64_t p : used)
  {
    topology.components += root(p) == p;
  }
  return topology;
}

/// Checks a closed, consistently outward-oriented surface of genus 0 (one per component).
void ExpectClosedOutwardSpheres(const MeshData& mesh, int components = 1)
{
  const Topology topology = Analyse(mesh);
  EXPECT_TRUE(topology.Closed());
  EXPECT_TRUE(topology.oriented);
  EXPECT_EQ(topology.components, components);
  EXPECT_EQ(topology.Euler(mesh), 2 * components);
  EXPECT_EQ(topology.usedPoints, mesh.NumberOfPoints());
  EXPECT_EQ(2 * topology.edges, 3 * mesh.NumberOfTriangles());
  EXPECT_GT(SignedVolume(mesh), 0.0);
}

TEST(TestMeshes, IcosphereIsAClosedOutwardSphere)
{
  for (int s = 0; s <= 7; ++s)
  {
    SCOPED_TRACE(s);
    const double radius = 2.5;
    const MeshData mesh = Icosphere(s, radius);
    const std::int64_t faces = 20 * (std::int64_t(1) << (2 * s));
    EXPECT_EQ(mesh.NumberOfTriangles(), faces);
    EXPECT_EQ(mesh.NumberOfPoints(), faces / 2 + 2);
    for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
    {
      ASSERT_NEAR(Norm(Point(mesh, p)), radius, 1e-12);
    }
    if (s <=
      5) // the map-based analysis of the finest levels only repeats what the coarse ones show
    {
      ExpectClosedOutwardSpheres(mesh);
    }
    for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
    {
      ASSERT_GT(Dot(TriangleNormal(mesh, t), TriangleCentroid(mesh, t)), 0.0);
    }
    const double sphereVolume = 4.0 / 3.0 * std::acos(-1.0) * radius * radius * radius;
    // An inscribed polyhedron whose volume deficit shrinks like the squared edge length.
    EXPECT_LT(SignedVolume(mesh), sphereVolume);
    EXPECT_GT(SignedVolume(mesh), (1.0 - 0.6 / static_cast<double>(faces / 20)) * sphereVolume);
  }
}

TEST(TestMeshes, IcosphereTrianglesAreNearlyEquilateral)
{
  const MeshData mesh = Icosphere(4);
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const auto c = TriangleCorners(mesh, t);
    const double e[3] = { Norm(c[1] - c[0]), Norm(c[2] - c[1]), Norm(c[0] - c[2]) };
    ASSERT_LT(*std::max_element(e, e + 3) / *std::min_element(e, e + 3), 1.3);
  }
  EXPECT_THROW(Icosphere(-1), std::invalid_argument);
  EXPECT_THROW(Icosphere(8), std::invalid_argument);
}

TEST(TestMeshes, PlaneGridMatchesImageSamples)
{
  const int nx = 7, ny = 5;
  const double spacing = 0.5;
  const MeshData mesh = PlaneGrid(nx, ny, spacing);
  ASSERT_EQ(mesh.NumberOfPoints(), nx * ny);
  EXPECT_EQ(mesh.NumberOfTriangles(), 2 * (nx - 1) * (ny - 1));
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const Vec3 expected{ i * spacing, j * spacing, 0.0 };
      EXPECT_EQ(Point(mesh, j * nx + i), expected);
    }
  }
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    EXPECT_EQ(TriangleNormal(mesh, t), (Vec3{ 0.0, 0.0, 1.0 }));
    EXPECT_DOUBLE_EQ(TriangleArea(mesh, t), 0.5 * spacing * spacing);
  }
  const Topology topology = Analyse(mesh);
  EXPECT_TRUE(topology.oriented);
  EXPECT_EQ(topology.nonManifoldEdges, 0);
  EXPECT_EQ(topology.boundaryLoops, 1);
  EXPECT_EQ(topology.boundaryEdges, 2 * (nx - 1) + 2 * (ny - 1));
  EXPECT_EQ(topology.Euler(mesh), 1); // a disk
  EXPECT_DOUBLE_EQ(SurfaceArea(mesh), (nx - 1) * (ny - 1) * spacing * spacing);
  EXPECT_THROW(PlaneGrid(1, 5), std::invalid_argument);
}

TEST(TestMeshes, CylinderIsAnOpenOutwardTube)
{
  const int around = 12, along = 4;
  const double radius = 1.5, height = 3.0;
  const MeshData mesh = Cylinder(around, along, radius, height);
  EXPECT_EQ(mesh.NumberOfPoints(), around * (along + 1));
  EXPECT_EQ(mesh.NumberOfTriangles(), 2 * around * along);
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const Vec3 x = Point(mesh, p);
    EXPECT_NEAR(std::hypot(x[0], x[1]), radius, 1e-12);
    EXPECT_DOUBLE_EQ(x[2], height * static_cast<double>(p / around) / along);
  }
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const Vec3 c = TriangleCentroid(mesh, t);
    EXPECT_GT(Dot(TriangleNormal(mesh, t), { c[0], c[1], 0.0 }), 0.0);
  }
  const Topology topology = Analyse(mesh);
  EXPECT_TRUE(topology.oriented);
  EXPECT_EQ(topology.boundaryLoops, 2);
  EXPECT_EQ(topology.boundaryEdges, 2 * around);
  EXPECT_EQ(topology.Euler(mesh), 0); // an annulus
  EXPECT_EQ(topology.components, 1);
}

TEST(TestMeshes, BoxSurfaceIsAClosedOutwardBox)
{
  for (int n : { 1, 2, 5 })
  {
    SCOPED_TRACE(n);
    const double sx = 2.0, sy = 3.0, sz = 0.5;
    const MeshData mesh = BoxSurface(n, sx, sy, sz);
    EXPECT_EQ(mesh.NumberOfPoints(), 6 * n * n + 2);
    EXPECT_EQ(mesh.NumberOfTriangles(), 12 * n * n);
    ExpectClosedOutwardSpheres(mesh);
    EXPECT_NEAR(SignedVolume(mesh), sx * sy * sz, 1e-12);
    EXPECT_NEAR(SurfaceArea(mesh), 2.0 * (sx * sy + sy * sz + sz * sx), 1e-12);
    const Vec3 half{ sx / 2, sy / 2, sz / 2 };
    for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
    {
      // Every normal is an outward axis: +-e_c on the face where |x_c| = half_c.
      const Vec3 normal = TriangleNormal(mesh, t), c = TriangleCentroid(mesh, t);
      int axis = 0;
      while (axis < 3 && std::abs(std::abs(normal[axis]) - 1.0) > 1e-12)
      {
        ++axis;
      }
      ASSERT_LT(axis, 3);
      EXPECT_NEAR(c[axis], std::copysign(half[axis], normal[axis]), 1e-12);
    }
  }
}

TEST(TestMeshes, RoundedBoxLiesOnTheRoundedSurface)
{
  const int n = 16;
  const double size = 2.0, r = 0.4, h = 0.5 * size - r;
  const MeshData mesh = RoundedBox(n, size, r);
  ExpectClosedOutwardSpheres(mesh);
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const Vec3 x = Point(mesh, p);
    const Vec3 nearest{ std::clamp(x[0], -h, h), std::clamp(x[1], -h, h), std::clamp(x[2], -h, h) };
    ASSERT_NEAR(Norm(x - nearest), r, 1e-12);
  }
  // Volume of the Minkowski sum of a cube of side a and a ball of radius r.
  const double pi = std::acos(-1.0), a = 2.0 * h;
  const double volume =
    a * a * a + 6.0 * a * a * r + 3.0 * pi * a * r * r + 4.0 / 3.0 * pi * r * r * r;
  EXPECT_LT(SignedVolume(mesh), volume);
  EXPECT_GT(SignedVolume(mesh), 0.99 * volume);

  // The extremes: no rounding is the box, full rounding a sphere.
  EXPECT_EQ(RoundedBox(3, size, 0.0).points, BoxSurface(3, size, size, size).points);
  const MeshData sphere = RoundedBox(4, size, 0.5 * size);
  for (std::int64_t p = 0; p < sphere.NumberOfPoints(); ++p)
  {
    EXPECT_NEAR(Norm(Point(sphere, p)), 0.5 * size, 1e-12);
  }
  EXPECT_THROW(RoundedBox(3, size, 0.6 * size), std::invalid_argument);
}

TEST(TestMeshes, WithHolesCutsBoundaryLoops)
{
  const MeshData sphere = Icosphere(3);
  const MeshData mesh =
    WithHoles(sphere, { { { 0.0, 0.0, 1.0 }, 0.5 }, { { 0.0, 0.0, -1.0 }, 0.3 } });
  EXPECT_LT(mesh.NumberOfTriangles(), sphere.NumberOfTriangles());
  const Topology topology = Analyse(mesh);
  EXPECT_TRUE(topology.oriented);
  EXPECT_EQ(topology.nonManifoldEdges, 0);
  EXPECT_EQ(topology.boundaryLoops, 2);
  EXPECT_EQ(topology.Euler(mesh), 0);                    // a sphere less two disks
  EXPECT_EQ(topology.usedPoints, mesh.NumberOfPoints()); // the unused points are gone
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const Vec3 c = TriangleCentroid(mesh, t);
    EXPECT_GE(Norm(c - Vec3{ 0.0, 0.0, 1.0 }), 0.5);
    EXPECT_GE(Norm(c - Vec3{ 0.0, 0.0, -1.0 }), 0.3);
  }
  EXPECT_EQ(WithHoles(sphere, {}).triangles, sphere.triangles);
}

TEST(TestMeshes, NonManifoldFanHasAFinEdgeAndABowtie)
{
  const MeshData mesh = NonManifoldFan();
  EXPECT_EQ(mesh.NumberOfPoints(), 12);
  const Topology topology = Analyse(mesh);
  EXPECT_EQ(topology.nonManifoldEdges, 1);
  EXPECT_EQ(topology.boundaryLoops, -1); // the bowtie point starts two boundary edges
  int finTriangles = 0;
  std::vector<std::int64_t> aroundBowtie;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const std::set<std::int64_t> ids(
      mesh.triangles.begin() + 3 * t, mesh.triangles.begin() + 3 * t + 3);
    finTriangles += ids.count(0) && ids.count(1);
    if (ids.count(5))
    {
      aroundBowtie.push_back(t);
    }
    EXPECT_GT(TriangleArea(mesh, t), 0.0);
  }
  EXPECT_EQ(finTriangles, 3);
  // Without point 5, the triangles around it fall into two groups sharing no point:
  // their opposite edges, as degenerate triangles, form two components.
  ASSERT_EQ(aroundBowtie.size(), 4u);
  MeshData link;
  link.points = mesh.points;
  for (std::int64_t t : aroundBowtie)
  {
    std::vector<std::int64_t> others;
    std::copy_if(mesh.triangles.begin() + 3 * t, mesh.triangles.begin() + 3 * t + 3,
      std::back_inserter(others), [](std::int64_t id) { return id != 5; });
    AddTriangle(link, others[0], others[1], others[1]);
  }
  EXPECT_EQ(Analyse(link).components, 2);
}

TEST(TestMeshes, WithDuplicatePointsSplitsAlongASeam)
{
  const MeshData sphere = Icosphere(3);
  const MeshData mesh = WithDuplicatePoints(sphere);
  const std::int64_t added = mesh.NumberOfPoints() - sphere.NumberOfPoints();
  EXPECT_GT(added, 0);
  ASSERT_EQ(mesh.NumberOfTriangles(), sphere.NumberOfTriangles());
  // Mapping every copy back to the original point by its coordinates restores the sphere.
  std::map<Vec3, std::int64_t> original;
  for (std::int64_t p = 0; p < sphere.NumberOfPoints(); ++p)
  {
    ASSERT_TRUE(original.emplace(Point(sphere, p), p).second);
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
  {
    EXPECT_EQ(original.at(Point(mesh, mesh.triangles[i])), sphere.triangles[i]);
  }
  EXPECT_EQ(std::vector<double>(mesh.points.begin(), mesh.points.begin() + sphere.points.size()),
    sphere.points);
  // By ids the sphere is now two disks whose boundaries are the seam, twice.
  const Topology topology = Analyse(mesh);
  EXPECT_EQ(topology.components, 2);
  EXPECT_EQ(topology.boundaryLoops, 2);
  EXPECT_EQ(topology.boundaryEdges, 2 * added);
  EXPECT_EQ(topology.Euler(mesh), 2);
  EXPECT_TRUE(topology.oriented);
}

TEST(TestMeshes, WithDegenerateTrianglesAddsZeroAreaTriangles)
{
  const MeshData grid = PlaneGrid(4, 4);
  const MeshData mesh = WithDegenerateTriangles(grid);
  ASSERT_EQ(mesh.NumberOfTriangles(), grid.NumberOfTriangles() + 4);
  EXPECT_EQ(mesh.NumberOfPoints(), grid.NumberOfPoints() + 3);
  const std::int64_t first = grid.NumberOfTriangles();
  EXPECT_EQ(mesh.triangles[3 * first], mesh.triangles[3 * first + 1]); // repeated id
  EXPECT_EQ(TriangleArea(mesh, first), 0.0);
  const double edge = MeanEdgeLength(grid);
  for (std::int64_t t = first + 1; t < mesh.NumberOfTriangles(); ++t)
  {
    EXPECT_LT(TriangleArea(mesh, t), 1e-8 * edge * edge); // collinear, cap, needle
    const std::set<std::int64_t> ids(
      mesh.triangles.begin() + 3 * t, mesh.triangles.begin() + 3 * t + 3);
    EXPECT_EQ(ids.size(), 3u); // distinct ids: degenerate by geometry only
  }
  EXPECT_EQ(TriangleArea(mesh, first + 1), 0.0); // an exact midpoint on an axis-aligned edge
  EXPECT_THROW(WithDegenerateTriangles(MeshData()), std::invalid_argument);
}

TEST(TestMeshes, WithIsolatedPointsAddsUnusedPointsInsideTheBounds)
{
  const MeshData sphere = Icosphere(2);
  const MeshData mesh = WithIsolatedPoints(sphere, 5);
  EXPECT_EQ(mesh.NumberOfPoints(), sphere.NumberOfPoints() + 5);
  EXPECT_EQ(mesh.triangles, sphere.triangles);
  EXPECT_EQ(Analyse(mesh).usedPoints, sphere.NumberOfPoints());
  const auto [low, high] = Bounds(sphere);
  for (std::int64_t p = sphere.NumberOfPoints(); p < mesh.NumberOfPoints(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_GT(Point(mesh, p)[c], low[c]);
      EXPECT_LT(Point(mesh, p)[c], high[c]);
    }
  }
  EXPECT_EQ(RemoveUnusedPoints(mesh).points, sphere.points);
}

TEST(TestMeshes, TwoComponentsAreDisjointSpheres)
{
  const MeshData mesh = TwoComponents();
  ExpectClosedOutwardSpheres(mesh, 2);
  const std::int64_t half = mesh.NumberOfPoints() / 2;
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const Vec3 center{ p < half ? -2.0 : 2.0, 0.0, 0.0 };
    EXPECT_NEAR(Norm(Point(mesh, p) - center), 1.0, 1e-12);
  }
  EXPECT_NEAR(Centroid(mesh)[0], 0.0, 1e-12);
}

TEST(TestMeshes, NoisyIsDeterministicAndBounded)
{
  const MeshData sphere = Icosphere(3);
  const double amplitude = 0.01;
  const MeshData a = Noisy(sphere, amplitude, 42), b = Noisy(sphere, amplitude, 42),
                 c = Noisy(sphere, amplitude, 43);
  EXPECT_EQ(a.points, b.points);
  EXPECT_NE(a.points, c.points);
  EXPECT_EQ(a.triangles, sphere.triangles);
  double largest = 0.0;
  Vec3 meanShift{ 0.0, 0.0, 0.0 };
  for (std::int64_t p = 0; p < sphere.NumberOfPoints(); ++p)
  {
    const Vec3 shift = Point(a, p) - Point(sphere, p);
    largest = std::max(largest, Norm(shift));
    meanShift = meanShift + (1.0 / static_cast<double>(sphere.NumberOfPoints())) * shift;
  }
  EXPECT_LE(largest, amplitude);
  EXPECT_GT(largest, 0.9 * amplitude);
  EXPECT_LT(Norm(meanShift), 0.1 * amplitude); // no drift: the directions are uniform
  EXPECT_EQ(Noisy(sphere, 0.0, 1).points, sphere.points);
}

TEST(TestMeshes, MeasurementsOfKnownMeshes)
{
  // A 3 x 2 grid of unit squares: 3*3 horizontal + 4*2 vertical unit edges, 6 diagonals.
  const MeshData grid = PlaneGrid(4, 3);
  EXPECT_EQ(UniqueEdges(grid).size(), 23u);
  EXPECT_NEAR(MeanEdgeLength(grid), (17.0 + 6.0 * std::sqrt(2.0)) / 23.0, 1e-15);
  const Vec3 gridCentre{ 1.5, 1.0, 0.0 };
  EXPECT_EQ(Centroid(grid), gridCentre);

  const MeshData box = BoxSurface(3, 1.0, 2.0, 3.0);
  const MeshData moved = Transformed(box, 2.0, { 1.0, -2.0, 3.0 });
  const Vec3 movedCentre{ 1.0, -2.0, 3.0 };
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(Centroid(moved)[c], movedCentre[c], 1e-12);
  }
  EXPECT_NEAR(SignedVolume(moved), 8.0 * SignedVolume(box), 1e-12);
  EXPECT_NEAR(MeanEdgeLength(moved), 2.0 * MeanEdgeLength(box), 1e-12);
  EXPECT_EQ(Bounds(moved)[0], (Vec3{ 0.0, -4.0, 0.0 }));

  // The centroid falls back to the mean of the points without area.
  MeshData points;
  AddPoint(points, { 0.0, 0.0, 0.0 });
  AddPoint(points, { 2.0, 4.0, 6.0 });
  EXPECT_EQ(Centroid(points), (Vec3{ 1.0, 2.0, 3.0 }));
  EXPECT_EQ(MeanEdgeLength(points), 0.0);
}

} // namespace
