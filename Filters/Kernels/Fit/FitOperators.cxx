#include "FitOperators.h"

#include "Vec3.h"

namespace shock
{

namespace
{
/// Entries `value(f, i, j)` for every non-degenerate triangle f and corner pair (i, j).
template <typename Value>
std::vector<SparseEntry> TriangleEntries(const TriangleMesh& mesh, Value value)
{
  std::vector<SparseEntry> entries;
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    if (mesh.Degenerate(f))
    {
      continue;
    }
    const std::int64_t* t = mesh.Corners(f);
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        entries.push_back({ t[i], t[j], value(f, i, j) });
      }
    }
  }
  return entries;
}
} // namespace

std::vector<SparseEntry> MassMatrix(const TriangleMesh& mesh)
{
  return TriangleEntries(
    mesh, [&](std::int64_t f, int i, int j) { return TriangleMass(mesh.Area(f), i, j); });
}

std::vector<SparseEntry> StiffnessMatrix(const TriangleMesh& mesh)
{
  return TriangleEntries(mesh, [&](std::int64_t f, int i, int j) {
    return mesh.Area(f) * Dot(Load(mesh.HatGradient(f, i)), Load(mesh.HatGradient(f, j)));
  });
}

std::vector<double> Divergence(const TriangleMesh& mesh, const double* gradients)
{
  std::vector<double> divergence(static_cast<size_t>(3 * mesh.NumberOfPoints()), 0.0);
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    if (mesh.Degenerate(f))
    {
      continue;
    }
    const std::int64_t* t = mesh.Corners(f);
    for (int i = 0; i < 3; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        divergence[static_cast<size_t>(3 * t[i] + k)] +=
          mesh.Area(f) * Dot(Load(mesh.HatGradient(f, i)), Load(gradients + 9 * f + 3 * k));
      }
    }
  }
  return divergence;
}

} // namespace shock
