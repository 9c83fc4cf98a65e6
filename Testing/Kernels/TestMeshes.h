/**
 * @file   TestMeshes.h
 * @brief  Synthetic triangle meshes for the tests of the mesh shock filters (VTK-free).
 *
 * Every generator is deterministic: the same arguments give the same points,
 * the same ids and the same triangle order on every platform (the random
 * generator is std::mt19937, whose output the standard fixes, turned into
 * numbers by hand because the standard distributions are not portable).
 * Triangles are counter-clockwise seen from outside, so on a closed mesh the
 * normals (p1 - p0) x (p2 - p0) point outwards and the signed volume is positive.
 * Invalid arguments throw std::invalid_argument.
 */
#ifndef TestMeshes_h
#define TestMeshes_h

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "ShockShapes.h"

namespace shocktest
{

using shock::Vec3;
using shockshapes::AddPoint;
using shockshapes::AddTriangle;
using shockshapes::BoxSurface;
using shockshapes::MeshData;
using shockshapes::Point;
using shockshapes::RoundedBox;
using shock::Cross;
using shock::Dot;

/// A ball, for WithHoles().
struct Ball
{
  Vec3 center;
  double radius;
};

// --- Small vector algebra -------------------------------------------------------

inline Vec3 operator+(const Vec3& a, const Vec3& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
inline Vec3 operator-(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline Vec3 operator*(double s, const Vec3& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}
inline double Norm(const Vec3& a)
{
  return std::sqrt(Dot(a, a));
}

// --- Access and measurements ------------------------------------------------------

/// The three corners of triangle `t`.
inline std::array<Vec3, 3> TriangleCorners(const MeshData& mesh, std::int64_t t)
{
  const std::int64_t* ids = mesh.triangles.data() + 3 * t;
  return { Point(mesh, ids[0]), Point(mesh, ids[1]), Point(mesh, ids[2]) };
}

/// Twice the area times the unit normal of triangle `t`: (p1 - p0) x (p2 - p0).
inline Vec3 TriangleCross(const MeshData& mesh, std::int64_t t)
{
  const auto c = TriangleCorners(mesh, t);
  return Cross(c[1] - c[0], c[2] - c[0]);
}

/// The area of triangle `t`.
inline double TriangleArea(const MeshData& mesh, std::int64_t t)
{
  return 0.5 * Norm(TriangleCross(mesh, t));
}

/// The unit normal of triangle `t` (right-hand rule), or zero for a zero-area triangle.
inline Vec3 TriangleNormal(const MeshData& mesh, std::int64_t t)
{
  const Vec3 n = TriangleCross(mesh, t);
  const double length = Norm(n);
  return length > 0.0 ? (1.0 / length) * n : Vec3{ 0.0, 0.0, 0.0 };
}

/// The centroid of the corners of triangle `t`.
inline Vec3 TriangleCentroid(const MeshData& mesh, std::int64_t t)
{
  const auto c = TriangleCorners(mesh, t);
  return (1.0 / 3.0) * (c[0] + c[1] + c[2]);
}

/// The total area of the triangles.
inline double SurfaceArea(const MeshData& mesh)
{
  double area = 0.0;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    area += TriangleArea(mesh, t);
  }
  return area;
}

/// The signed volume enclosed by the triangles (divergence theorem), positive for outward ones.
inline double SignedVolume(const MeshData& mesh)
{
  double volume = 0.0;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const auto c = TriangleCorners(mesh, t);
    volume += Dot(c[0], Cross(c[1], c[2]));
  }
  return volume / 6.0;
}

/// The distinct undirected edges (smaller id first), sorted, without point-to-itself edges.
inline std::vector<std::pair<std::int64_t, std::int64_t>> UniqueEdges(const MeshData& mesh)
{
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  edges.reserve(mesh.triangles.size());
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = mesh.triangles[3 * t + k], b = mesh.triangles[3 * t + (k + 1) % 3];
      if (a != b)
      {
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

/// The mean length of the distinct edges (UniqueEdges()), 0 without edges.
inline double MeanEdgeLength(const MeshData& mesh)
{
  const auto edges = UniqueEdges(mesh);
  double sum = 0.0;
  for (const auto& [a, b] : edges)
  {
    sum += Norm(Point(mesh, a) - Point(mesh, b));
  }
  return edges.empty() ? 0.0 : sum / static_cast<double>(edges.size());
}

/// The area-weighted centroid of the surface; the mean of the points when the area is zero.
inline Vec3 Centroid(const MeshData& mesh)
{
  Vec3 sum{ 0.0, 0.0, 0.0 };
  double area = 0.0;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const double a = TriangleArea(mesh, t);
    sum = sum + a * TriangleCentroid(mesh, t);
    area += a;
  }
  if (area > 0.0)
  {
    return (1.0 / area) * sum;
  }
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    sum = sum + Point(mesh, p);
  }
  return mesh.NumberOfPoints() > 0 ? (1.0 / static_cast<double>(mesh.NumberOfPoints())) * sum : sum;
}

/// The axis-aligned bounding box of the points: {min, max}.
inline std::array<Vec3, 2> Bounds(const MeshData& mesh)
{
  Vec3 low{ 0.0, 0.0, 0.0 }, high{ 0.0, 0.0, 0.0 };
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const Vec3 x = Point(mesh, p);
    for (int c = 0; c < 3; ++c)
    {
      low[c] = p == 0 ? x[c] : std::min(low[c], x[c]);
      high[c] = p == 0 ? x[c] : std::max(high[c], x[c]);
    }
  }
  return { low, high };
}

// --- Editing -----------------------------------------------------------------------

/// The mesh scaled about the origin by `scale`, then translated.
inline MeshData Transformed(MeshData mesh, double scale, const Vec3& translation)
{
  for (size_t i = 0; i < mesh.points.size(); ++i)
  {
    mesh.points[i] = scale * mesh.points[i] + translation[i % 3];
  }
  return mesh;
}

/// Drops the points no triangle uses; the others keep their order (ids are renumbered).
inline MeshData RemoveUnusedPoints(MeshData mesh)
{
  std::vector<std::int64_t> newId(static_cast<size_t>(mesh.NumberOfPoints()), -1);
  for (std::int64_t id : mesh.triangles)
  {
    newId[static_cast<size_t>(id)] = 0;
  }
  std::vector<double> points;
  std::int64_t next = 0;
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    if (newId[static_cast<size_t>(p)] == 0)
    {
      newId[static_cast<size_t>(p)] = next++;
      const Vec3 x = Point(mesh, p);
      points.insert(points.end(), x.begin(), x.end());
    }
  }
  for (std::int64_t& id : mesh.triangles)
  {
    id = newId[static_cast<size_t>(id)];
  }
  mesh.points = std::move(points);
  return mesh;
}

/// Appends the points and triangles of `other` (its ids shifted past those of `mesh`).
inline MeshData Merged(MeshData mesh, const MeshData& other)
{
  const std::int64_t offset = mesh.NumberOfPoints();
  mesh.points.insert(mesh.points.end(), other.points.begin(), other.points.end());
  for (std::int64_t id : other.triangles)
  {
    mesh.triangles.push_back(id + offset);
  }
  return mesh;
}

// --- Generators ----------------------------------------------------------------------

/// Sphere about the origin: an icosahedron split in four `subdivisions` (0..7) times, projected.
inline MeshData Icosphere(int subdivisions, double radius = 1.0)
{
  if (subdivisions < 0 || subdivisions > 7)
  {
    throw std::invalid_argument("Icosphere: subdivisions must be in 0..7");
  }
  MeshData mesh;
  // The icosahedron's 12 corners are the cyclic permutations of (0, +-1, +-phi).
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  for (int axis = 0; axis < 3; ++axis)
  {
    for (double s : { -1.0, 1.0 })
    {
      for (double t : { -1.0, 1.0 })
      {
        Vec3 p{ 0.0, 0.0, 0.0 };
        p[(axis + 1) % 3] = s;
        p[(axis + 2) % 3] = t * phi;
        AddPoint(mesh, p);
      }
    }
  }
  // Its 20 faces are the triples of corners at mutual distance 2 (the edge length),
  // turned so that their normal points away from the centre.
  auto isEdge = [&](std::int64_t a, std::int64_t b) {
    const Vec3 d = Point(mesh, a) - Point(mesh, b);
    return std::abs(Dot(d, d) - 4.0) < 1e-9;
  };
  for (std::int64_t a = 0; a < 12; ++a)
  {
    for (std::int64_t b = a + 1; b < 12; ++b)
    {
      for (std::int64_t c = b + 1; c < 12; ++c)
      {
        if (isEdge(a, b) && isEdge(b, c) && isEdge(a, c))
        {
          AddTriangle(mesh, a, b, c);
          if (Dot(TriangleCross(mesh, mesh.NumberOfTriangles() - 1), Point(mesh, a)) < 0.0)
          {
            std::swap(
              mesh.triangles[mesh.triangles.size() - 1], mesh.triangles[mesh.triangles.size() - 2]);
          }
        }
      }
    }
  }
  auto projected = [](const Vec3& p) { return (1.0 / Norm(p)) * p; };
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const Vec3 x = projected(Point(mesh, p));
    std::copy(x.begin(), x.end(), mesh.points.begin() + 3 * p);
  }

  // Each level splits every triangle (a, b, c) into four at the edge midpoints,
  // shared by the two triangles of an edge, keeping the orientation.
  for (int level = 0; level < subdivisions; ++level)
  {
    std::unordered_map<std::uint64_t, std::int64_t> midpoints;
    auto midpoint = [&](std::int64_t a, std::int64_t b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
        static_cast<std::uint64_t>(std::max(a, b));
      const auto [it, inserted] = midpoints.try_emplace(key, 0);
      if (inserted)
      {
        it->second = AddPoint(mesh, projected(Point(mesh, a) + Point(mesh, b)));
      }
      return it->second;
    };
    std::vector<std::int64_t> coarse;
    std::swap(coarse, mesh.triangles);
    mesh.triangles.reserve(4 * coarse.size());
    for (size_t t = 0; t < coarse.size(); t += 3)
    {
      const std::int64_t a = coarse[t], b = coarse[t + 1], c = coarse[t + 2];
      const std::int64_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      AddTriangle(mesh, a, ab, ca);
      AddTriangle(mesh, ab, b, bc);
      AddTriangle(mesh, ca, bc, c);
      AddTriangle(mesh, ab, bc, ca);
    }
  }
  for (double& x : mesh.points)
  {
    x *= radius;
  }
  return mesh;
}

/// Image samples (i, j, 0) * spacing, id j*nx + i, squares cut along (i,j)-(i+1,j+1), CCW from +z.
///
/// nx, ny >= 2.
inline MeshData PlaneGrid(int nx, int ny, double spacing = 1.0)
{
  if (nx < 2 || ny < 2)
  {
    throw std::invalid_argument("PlaneGrid: nx and ny must be at least 2");
  }
  MeshData mesh;
  mesh.points.reserve(3 * static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      AddPoint(mesh, { i * spacing, j * spacing, 0.0 });
    }
  }
  for (int j = 0; j + 1 < ny; ++j)
  {
    for (int i = 0; i + 1 < nx; ++i)
    {
      const std::int64_t a = static_cast<std::int64_t>(j) * nx + i, b = a + 1, c = a + nx,
                         d = c + 1;
      AddTriangle(mesh, a, b, d);
      AddTriangle(mesh, a, d, c);
    }
  }
  return mesh;
}

/// Open tube about the z axis from z = 0 to `height`, normals outward.
///
/// `along` + 1 rings (along >= 1) of `around` points (>= 3): point ring*around + k is at the
/// angle 2 pi k / around.
inline MeshData Cylinder(int around, int along, double radius, double height)
{
  if (around < 3 || along < 1)
  {
    throw std::invalid_argument("Cylinder: around must be at least 3 and along at least 1");
  }
  const double pi = std::acos(-1.0);
  MeshData mesh;
  for (int ring = 0; ring <= along; ++ring)
  {
    for (int k = 0; k < around; ++k)
    {
      const double angle = 2.0 * pi * k / around;
      AddPoint(mesh, { radius * std::cos(angle), radius * std::sin(angle), height * ring / along });
    }
  }
  // Going round (+angle) then up (+z) turns outwards: e_angle x e_z = e_radius.
  for (int ring = 0; ring < along; ++ring)
  {
    for (int k = 0; k < around; ++k)
    {
      const std::int64_t a = static_cast<std::int64_t>(ring) * around + k;
      const std::int64_t b = static_cast<std::int64_t>(ring) * around + (k + 1) % around;
      AddTriangle(mesh, a, b, b + around);
      AddTriangle(mesh, a, b + around, a + around);
    }
  }
  return mesh;
}

/// The mesh without the triangles whose centroid is inside a ball, and without unused points.
inline MeshData WithHoles(MeshData mesh, const std::vector<Ball>& balls)
{
  std::vector<std::int64_t> kept;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const Vec3 c = TriangleCentroid(mesh, t);
    const bool removed = std::any_of(balls.begin(), balls.end(),
      [&](const Ball& ball) { return Norm(c - ball.center) < ball.radius; });
    if (!removed)
    {
      kept.insert(kept.end(), mesh.triangles.begin() + 3 * t, mesh.triangles.begin() + 3 * t + 3);
    }
  }
  mesh.triangles = std::move(kept);
  return RemoveUnusedPoints(std::move(mesh));
}

/**
 * Non-manifold configurations: three triangles (0,1,2), (0,1,3), (1,0,4) sharing
 * the edge 0-1 (fins about the z axis); and the "bowtie" point 5 shared by two
 * fans (5,7,6), (5,8,7) and (5,10,9), (5,11,10) in the plane z = 0, which touch
 * only there. Points 0..11.
 */
inline MeshData NonManifoldFan()
{
  MeshData mesh;
  const double pi = std::acos(-1.0);
  AddPoint(mesh, { 0.0, 0.0, 0.0 });
  AddPoint(mesh, { 0.0, 0.0, 1.0 });
  for (int k = 0; k < 3; ++k)
  {
    AddPoint(mesh, { std::cos(2.0 * pi * k / 3.0), std::sin(2.0 * pi * k / 3.0), 0.5 });
  }
  AddTriangle(mesh, 0, 1, 2);
  AddTriangle(mesh, 0, 1, 3);
  AddTriangle(mesh, 1, 0, 4);

  AddPoint(mesh, { 3.0, 0.0, 0.0 }); // 5: the bowtie point
  for (const Vec3& p : { Vec3{ 2.0, -1.0, 0.0 }, Vec3{ 2.0, 0.0, 0.0 }, Vec3{ 2.0, 1.0, 0.0 },
         Vec3{ 4.0, 1.0, 0.0 }, Vec3{ 4.0, 0.0, 0.0 }, Vec3{ 4.0, -1.0, 0.0 } })
  {
    AddPoint(mesh, p); // 6..11
  }
  AddTriangle(mesh, 5, 7, 6);
  AddTriangle(mesh, 5, 8, 7);
  AddTriangle(mesh, 5, 10, 9);
  AddTriangle(mesh, 5, 11, 10);
  return mesh;
}

/**
 * The mesh cut along the plane x = Centroid(mesh).x by id only: every point used
 * both by triangles whose centroid lies below the plane and by triangles on or
 * above it gets a copy (same coordinates, appended in the order of the original
 * ids), which the triangles on or above the plane use instead.
 */
inline MeshData WithDuplicatePoints(MeshData mesh)
{
  const double cut = Centroid(mesh)[0];
  const auto n = static_cast<size_t>(mesh.NumberOfPoints());
  std::vector<bool> usedBelow(n, false), usedAbove(n, false);
  std::vector<bool> above(static_cast<size_t>(mesh.NumberOfTriangles()));
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    above[static_cast<size_t>(t)] = TriangleCentroid(mesh, t)[0] >= cut;
    for (int k = 0; k < 3; ++k)
    {
      (above[static_cast<size_t>(t)] ? usedAbove
                                     : usedBelow)[static_cast<size_t>(mesh.triangles[3 * t + k])] =
        true;
    }
  }
  std::vector<std::int64_t> copyOf(n, -1);
  for (size_t p = 0; p < n; ++p)
  {
    if (usedBelow[p] && usedAbove[p])
    {
      copyOf[p] = AddPoint(mesh, Point(mesh, static_cast<std::int64_t>(p)));
    }
  }
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    if (!above[static_cast<size_t>(t)])
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      std::int64_t& id = mesh.triangles[3 * t + k];
      if (copyOf[static_cast<size_t>(id)] >= 0)
      {
        id = copyOf[static_cast<size_t>(id)];
      }
    }
  }
  return mesh;
}

/**
 * The mesh (with at least one triangle (a, b, c), its first) plus four
 * degenerate triangles appended in this order: (a, a, b) with a repeated id;
 * (b, m, c) with m the midpoint of b-c (collinear); the cap (c, s, a) with s
 * 1e-9 |c - a| off the midpoint of c-a along the normal; the needle (a, b, e)
 * with e 1e-9 |c - b| from b towards c. The new points m, s, e are appended.
 */
inline MeshData WithDegenerateTriangles(MeshData mesh)
{
  if (mesh.NumberOfTriangles() < 1)
  {
    throw std::invalid_argument("WithDegenerateTriangles: the mesh needs a triangle");
  }
  const std::int64_t a = mesh.triangles[0], b = mesh.triangles[1], c = mesh.triangles[2];
  const Vec3 pa = Point(mesh, a), pb = Point(mesh, b), pc = Point(mesh, c);
  const Vec3 normal = TriangleNormal(mesh, 0);
  const std::int64_t m = AddPoint(mesh, 0.5 * (pb + pc));
  const std::int64_t s = AddPoint(mesh, 0.5 * (pc + pa) + (1e-9 * Norm(pc - pa)) * normal);
  const std::int64_t e = AddPoint(mesh, pb + 1e-9 * (pc - pb));
  AddTriangle(mesh, a, a, b);
  AddTriangle(mesh, b, m, c);
  AddTriangle(mesh, c, s, a);
  AddTriangle(mesh, a, b, e);
  return mesh;
}

/// The mesh plus `count` unused points, appended, spread along the diagonal of its bounding box.
inline MeshData WithIsolatedPoints(MeshData mesh, int count)
{
  const auto [low, high] = Bounds(mesh);
  for (int k = 0; k < count; ++k)
  {
    AddPoint(mesh, low + ((k + 1.0) / (count + 1.0)) * (high - low));
  }
  return mesh;
}

/// Two disjoint unit spheres: Icosphere(subdivisions) about (-2, 0, 0) (ids first) and (2, 0, 0).
inline MeshData TwoComponents(int subdivisions = 2)
{
  const MeshData sphere = Icosphere(subdivisions);
  return Merged(
    Transformed(sphere, 1.0, { -2.0, 0.0, 0.0 }), Transformed(sphere, 1.0, { 2.0, 0.0, 0.0 }));
}

/// The mesh with every point moved by up to `amplitude` in a random direction (seeded).
///
/// The length is uniform in [0, amplitude], the direction uniform on the sphere.
inline MeshData Noisy(MeshData mesh, double amplitude, unsigned seed)
{
  std::mt19937 generator(seed);
  auto uniform = [&generator] {
    return (static_cast<double>(generator()) + 0.5) / 4294967296.0;
  }; // in (0, 1)
  const double pi = std::acos(-1.0);
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const double z = 2.0 * uniform() - 1.0, angle = 2.0 * pi * uniform(),
                 length = amplitude * uniform();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 moved =
      Point(mesh, p) + length * Vec3{ r * std::cos(angle), r * std::sin(angle), z };
    std::copy(moved.begin(), moved.end(), mesh.points.begin() + 3 * p);
  }
  return mesh;
}

} // namespace shocktest

#endif
