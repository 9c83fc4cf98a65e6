/**
 * @file   ShockShapes.h
 * @brief  Synthetic shapes as triangle meshes (VTK-free, header-only): the box
 *         surface and the rounded box (a cube whose creases are rounded; a
 *         sphere when fully rounded) that the program's demo, the tests and
 *         the benchmarks share.
 *
 * Deterministic: the same arguments give the same points, ids and triangle
 * order. Triangles are counter-clockwise seen from outside. Invalid arguments
 * throw std::invalid_argument. The tests' own meshes (Testing/Kernels/TestMeshes.h)
 * build on these.
 */
#ifndef ShockShapes_h
#define ShockShapes_h

#include "Vec3.h" // Filters/Kernels: shock::Vec3

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace shockshapes
{

using shock::Vec3;

/// A triangle mesh as two flat arrays.
struct MeshData
{
  std::vector<double> points;          ///< 3 coordinates per point
  std::vector<std::int64_t> triangles; ///< 3 point ids per triangle, counter-clockwise from outside

  std::int64_t NumberOfPoints() const { return static_cast<std::int64_t>(this->points.size() / 3); }
  std::int64_t NumberOfTriangles() const
  {
    return static_cast<std::int64_t>(this->triangles.size() / 3);
  }
};

/// The coordinates of point `id`.
inline Vec3 Point(const MeshData& mesh, std::int64_t id)
{
  const double* p = mesh.points.data() + 3 * id;
  return { p[0], p[1], p[2] };
}

/// Appends a point and returns its id.
inline std::int64_t AddPoint(MeshData& mesh, const Vec3& p)
{
  mesh.points.insert(mesh.points.end(), p.begin(), p.end());
  return mesh.NumberOfPoints() - 1;
}

/// Appends the triangle (a, b, c).
inline void AddTriangle(MeshData& mesh, std::int64_t a, std::int64_t b, std::int64_t c)
{
  mesh.triangles.insert(mesh.triangles.end(), { a, b, c });
}

/// Closed surface of the box [-sx/2, sx/2] x [-sy/2, sy/2] x [-sz/2, sz/2], normals outward.
///
/// Each face is a grid of n x n squares (n = subdivisionsPerEdge >= 1) of two triangles, the
/// faces welded along the edges and corners.
inline MeshData BoxSurface(int subdivisionsPerEdge, double sx, double sy, double sz)
{
  const int n = subdivisionsPerEdge;
  if (n < 1)
  {
    throw std::invalid_argument("BoxSurface: subdivisionsPerEdge must be at least 1");
  }
  const Vec3 size{ sx, sy, sz };
  // The points are the lattice nodes (i, j, k) in [0, n]^3 on the surface, numbered in z-y-x order.
  const auto nodes = static_cast<size_t>(n + 1);
  std::vector<std::int64_t> idOf(nodes * nodes * nodes, -1);
  auto node = [&](const std::array<int, 3>& ijk) -> std::int64_t& {
    return idOf[(static_cast<size_t>(ijk[2]) * nodes + ijk[1]) * nodes + ijk[0]];
  };
  MeshData mesh;
  for (int k = 0; k <= n; ++k)
  {
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= n; ++i)
      {
        const std::array<int, 3> ijk{ i, j, k };
        if (std::any_of(ijk.begin(), ijk.end(), [n](int c) { return c == 0 || c == n; }))
        {
          Vec3 p;
          for (int c = 0; c < 3; ++c)
          {
            p[c] = (static_cast<double>(ijk[c]) / n - 0.5) * size[c];
          }
          node(ijk) = AddPoint(mesh, p);
        }
      }
    }
  }
  // The face normal to `axis` on side `sign` is a grid in the in-plane axes (u, v)
  // ordered so that e_u x e_v = sign * e_axis: counter-clockwise in (u, v) is outward.
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int sign : { -1, 1 })
    {
      const int u = sign > 0 ? (axis + 1) % 3 : (axis + 2) % 3;
      const int v = sign > 0 ? (axis + 2) % 3 : (axis + 1) % 3;
      for (int iv = 0; iv < n; ++iv)
      {
        for (int iu = 0; iu < n; ++iu)
        {
          auto corner = [&](int du, int dv) {
            std::array<int, 3> ijk{};
            ijk[axis] = sign > 0 ? n : 0;
            ijk[u] = iu + du;
            ijk[v] = iv + dv;
            return node(ijk);
          };
          AddTriangle(mesh, corner(0, 0), corner(1, 0), corner(1, 1));
          AddTriangle(mesh, corner(0, 0), corner(1, 1), corner(0, 1));
        }
      }
    }
  }
  return mesh;
}

/// BoxSurface(n, size, size, size) moved onto the cube whose creases are rounded with that radius.
///
/// 0 <= roundingRadius <= size/2; size/2 gives a sphere.
inline MeshData RoundedBox(int subdivisionsPerEdge, double size, double roundingRadius)
{
  if (roundingRadius < 0.0 || roundingRadius > 0.5 * size)
  {
    throw std::invalid_argument("RoundedBox: roundingRadius must be in [0, size/2]");
  }
  MeshData mesh = BoxSurface(subdivisionsPerEdge, size, size, size);
  // The rounded box is the inner cube of half side h grown by the ball of radius r:
  // a point goes to distance r from the inner cube along the direction from its
  // nearest point there (points on the flat parts are already at distance r).
  const double h = 0.5 * size - roundingRadius;
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const Vec3 x = Point(mesh, p);
    const Vec3 nearest{ std::clamp(x[0], -h, h), std::clamp(x[1], -h, h), std::clamp(x[2], -h, h) };
    const Vec3 away = shock::Combine(1.0, x, -1.0, nearest);
    const double distance = std::sqrt(shock::Dot(away, away));
    if (distance > 0.0)
    {
      const Vec3 moved = shock::Combine(1.0, nearest, roundingRadius / distance, away);
      std::copy(moved.begin(), moved.end(), mesh.points.begin() + 3 * p);
    }
  }
  return mesh;
}

} // namespace shockshapes

#endif
