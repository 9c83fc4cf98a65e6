/**
 * @file TestSharpShapes.h
 * @brief Already sharp test shapes (header-only, VTK-free): CAD-like blocks and a capped cylinder.
 *
 * Geometry sharpening must leave these as they are (their creases are sharp
 * already), and their rounded or blurred versions must move towards them.
 */
#ifndef TestSharpShapes_h
#define TestSharpShapes_h

#include "TestMeshes.h"

#include <functional>
#include <map>

namespace shocktest
{

/**
 * Closed surface of the occupied cells of an nx x ny x nz grid of cubes of side
 * h, centred at the origin: every face between an occupied and an empty cell is
 * two triangles, normals outward, points shared. Unions of cells give CAD-like
 * solids with convex and concave creases, uniformly triangulated.
 */
inline MeshData CellBlockSurface(int nx, int ny, int nz, double h, const std::function<bool(int, int, int)>& occupied)
{
  auto inside = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz && occupied(i, j, k);
  };
  MeshData mesh;
  std::map<std::array<int, 3>, std::int64_t> ids;
  auto id = [&](const std::array<int, 3>& g) {
    auto found = ids.find(g);
    if (found != ids.end())
    {
      return found->second;
    }
    const std::int64_t n = AddPoint(mesh, { (g[0] - 0.5 * nx) * h, (g[1] - 0.5 * ny) * h, (g[2] - 0.5 * nz) * h });
    ids.emplace(g, n);
    return n;
  };
  const int square[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
        for (int axis = 0; axis < 3 && inside(i, j, k); ++axis)
          for (int side = 0; side < 2; ++side)
          {
            std::array<int, 3> next{ i, j, k };
            next[axis] += side ? 1 : -1;
            if (inside(next[0], next[1], next[2]))
            {
              continue;
            }
            // Counter-clockwise seen from outside: (u, v, axis) is right-handed.
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            std::int64_t q[4];
            for (int c = 0; c < 4; ++c)
            {
              std::array<int, 3> g{ i, j, k };
              g[axis] += side;
              g[u] += square[side ? c : 3 - c][0];
              g[v] += square[side ? c : 3 - c][1];
              q[c] = id(g);
            }
            AddTriangle(mesh, q[0], q[1], q[2]);
            AddTriangle(mesh, q[0], q[2], q[3]);
          }
  return mesh;
}

/// A CAD-like part: an L-shaped block with a slot through one leg (cells of side h, 32 x 24 x 14).
inline MeshData SlottedLBlock(double h = 1.0 / 24.0)
{
  return CellBlockSurface(32, 24, 14, h, [](int i, int j, int k) {
    return (i < 12 || j < 10) && !(i >= 20 && i < 26 && k >= 6);
  });
}

/// Cylinder(around, along, radius, height) closed by two flat caps (fans around a centre point).
inline MeshData CappedCylinder(int around, int along, double radius, double height)
{
  MeshData mesh = Cylinder(around, along, radius, height);
  const std::int64_t bottom = AddPoint(mesh, { 0.0, 0.0, 0.0 });
  const std::int64_t top = AddPoint(mesh, { 0.0, 0.0, height });
  const std::int64_t last = static_cast<std::int64_t>(along) * around;
  for (int k = 0; k < around; ++k)
  {
    const std::int64_t a = k, b = (k + 1) % around;
    AddTriangle(mesh, bottom, b, a);                 // normal -z
    AddTriangle(mesh, top, last + a, last + b);      // normal +z
  }
  return mesh;
}

} // namespace shocktest

#endif
