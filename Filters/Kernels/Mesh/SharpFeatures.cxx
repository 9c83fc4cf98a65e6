#include "SharpFeatures.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace shock
{

namespace
{
/// The corners of triangle f sorted, so that equal vertex sets compare equal.
std::array<std::int64_t, 3> SortedCorners(const TriangleMesh& mesh, std::int64_t f)
{
  const std::int64_t* t = mesh.Corners(f);
  std::array<std::int64_t, 3> s{ t[0], t[1], t[2] };
  std::sort(s.begin(), s.end());
  return s;
}

/// Per edge (3 f + e): 1 when the edge is a feature edge.
std::vector<unsigned char> FeatureEdgeFlags(
  const TriangleMesh& mesh, const double* normals, double cosine, int threads)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  std::vector<unsigned char> feature(static_cast<size_t>(3 * nt), 0);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t g = mesh.Neighbour(f, e);
      if (g < 0)
      {
        continue;
      }
      const double* a = normals + 3 * f;
      const double* b = normals + 3 * g;
      feature[static_cast<size_t>(3 * f + e)] = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < cosine) ? 1 : 0;
    }
  }
  return feature;
}

/// Root of i in a union-find forest (with path halving).
std::int64_t Root(std::vector<std::int64_t>& parent, std::int64_t i)
{
  while (parent[static_cast<size_t>(i)] != i)
  {
    parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    i = parent[static_cast<size_t>(i)];
  }
  return i;
}

/**
 * Group the triangles around point p by the non-feature edges through p:
 * label[k] for each entry k of PointTriangles(p), numbered from 0 in order of
 * first appearance. Returns the number of groups (1 when no feature edge
 * touches p, so that p is not split).
 */
std::int64_t GroupAroundPoint(const TriangleMesh& mesh, const std::vector<unsigned char>& feature,
  std::int64_t p, std::int64_t* label)
{
  const CompressedLists& around = mesh.PointTriangles();
  const std::int64_t begin = around.Begin(p);
  const std::int64_t count = around.End(p) - begin;
  const std::int64_t* items = around.items.data() + begin;
  bool touched = false;
  for (std::int64_t k = 0; k < count && !touched; ++k)
  {
    const std::int64_t* t = mesh.Corners(items[k]);
    for (int e = 0; e < 3; ++e)
    {
      touched = touched ||
        (feature[static_cast<size_t>(3 * items[k] + e)] && (t[e] == p || t[(e + 1) % 3] == p));
    }
  }
  if (!touched)
  {
    std::fill(label, label + count, 0);
    return 1;
  }
  std::vector<std::int64_t> parent(static_cast<size_t>(count));
  for (std::int64_t k = 0; k < count; ++k)
  {
    parent[static_cast<size_t>(k)] = k;
  }
  for (std::int64_t k = 0; k < count; ++k)
  {
    const std::int64_t f = items[k];
    const std::int64_t* t = mesh.Corners(f);
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t g = mesh.Neighbour(f, e);
      if (g < 0 || feature[static_cast<size_t>(3 * f + e)] || (t[e] != p && t[(e + 1) % 3] != p))
      {
        continue;
      }
      const std::int64_t j = std::find(items, items + count, g) - items;
      if (j < count)
      {
        parent[static_cast<size_t>(Root(parent, k))] = Root(parent, j);
      }
    }
  }
  std::vector<std::int64_t> number(static_cast<size_t>(count), -1);
  std::int64_t groups = 0;
  for (std::int64_t k = 0; k < count; ++k)
  {
    std::int64_t& n = number[static_cast<size_t>(Root(parent, k))];
    if (n < 0)
    {
      n = groups++;
    }
    label[k] = n;
  }
  return groups;
}
} // namespace

std::vector<std::int64_t> FindRepeatedTriangles(const TriangleMesh& mesh, int threads)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  const CompressedLists& around = mesh.PointTriangles();
  std::vector<std::int64_t> first(static_cast<size_t>(nt), -1);
#pragma omp parallel for num_threads(ResolveThreadCount(threads)) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::array<std::int64_t, 3> corners = SortedCorners(mesh, f);
    // Every copy of f has each of f's edges. An edge joined to one other triangle
    // g (two triangles have both its ends) leaves g as the only candidate.
    const MeshConnectivity& connectivity = mesh.Connectivity();
    std::int64_t only = -1;
    for (int e = 0; e < 3 && only < 0; ++e)
    {
      only = connectivity.Neighbour(f, e);
    }
    if (only >= 0)
    {
      first[static_cast<size_t>(f)] = only < f && SortedCorners(mesh, only) == corners ? only : -1;
      continue;
    }
    // Else: every copy of f uses f's smallest point: look among that point's triangles.
    std::int64_t earliest = f;
    for (std::int64_t k = around.Begin(corners[0]); k < around.End(corners[0]); ++k)
    {
      const std::int64_t g = around.items[static_cast<size_t>(k)];
      if (g < earliest && SortedCorners(mesh, g) == corners)
      {
        earliest = g;
      }
    }
    first[static_cast<size_t>(f)] = earliest < f ? earliest : -1;
  }
  return first;
}

namespace
{
/// The number of feature edges (each counted once, from its lower triangle).
std::int64_t CountFeatureEdges(const TriangleMesh& mesh, const std::vector<unsigned char>& feature)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  std::int64_t edges = 0;
  for (std::int64_t f = 0; f < nt; ++f)
  {
    for (int e = 0; e < 3; ++e)
    {
      edges += (feature[static_cast<size_t>(3 * f + e)] && mesh.Neighbour(f, e) > f) ? 1 : 0;
    }
  }
  return edges;
}

/// Per point: 1 when it is on a feature edge (only those points can split).
std::vector<unsigned char> PointsOnFeatureEdges(
  const TriangleMesh& mesh, const std::vector<unsigned char>& feature)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  std::vector<unsigned char> touched(static_cast<size_t>(mesh.NumberOfPoints()), 0);
  for (std::int64_t f = 0; f < nt; ++f)
  {
    for (int e = 0; e < 3; ++e)
    {
      if (feature[static_cast<size_t>(3 * f + e)])
      {
        touched[static_cast<size_t>(mesh.Corners(f)[e])] = 1;
        touched[static_cast<size_t>(mesh.Corners(f)[(e + 1) % 3])] = 1;
      }
    }
  }
  return touched;
}

/**
 * The copies of the points: returns the first copy of each point (np + 1
 * entries, the last one the number of copies), and fills `label` with the
 * group of each (point, triangle) entry of a touched point (the only ones read).
 */
std::vector<std::int64_t> CopiesOfPoints(const TriangleMesh& mesh,
  const std::vector<unsigned char>& feature, const std::vector<unsigned char>& touched, int threads,
  IdVector& label)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const CompressedLists& around = mesh.PointTriangles();
  std::vector<std::int64_t> firstCopy(static_cast<size_t>(np) + 1, 0);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
  for (std::int64_t p = 0; p < np; ++p)
  {
    firstCopy[static_cast<size_t>(p) + 1] = touched[static_cast<size_t>(p)]
      ? GroupAroundPoint(mesh, feature, p, label.data() + around.Begin(p))
      : 1;
  }
  for (std::int64_t p = 0; p < np; ++p)
  {
    firstCopy[static_cast<size_t>(p) + 1] += firstCopy[static_cast<size_t>(p)];
  }
  return firstCopy;
}

/// For each copy, the point it copies.
std::vector<std::int64_t> OriginalPoints(const std::vector<std::int64_t>& firstCopy, int threads)
{
  const auto np = static_cast<std::int64_t>(firstCopy.size()) - 1;
  std::vector<std::int64_t> original(static_cast<size_t>(firstCopy.back()));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    for (std::int64_t q = firstCopy[static_cast<size_t>(p)]; q < firstCopy[static_cast<size_t>(p) + 1]; ++q)
    {
      original[static_cast<size_t>(q)] = p;
    }
  }
  return original;
}

/// The triangles on the copies: each corner the copy of its point for the corner's group.
IdVector SplitTriangles(const TriangleMesh& mesh, const std::vector<unsigned char>& touched,
  const std::vector<std::int64_t>& firstCopy, const IdVector& label, int threads)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  const CompressedLists& around = mesh.PointTriangles();
  IdVector triangles(static_cast<size_t>(3 * nt));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const std::int64_t* t = mesh.Corners(f);
    for (int c = 0; c < 3; ++c)
    {
      const std::int64_t p = t[c];
      if (!touched[static_cast<size_t>(p)])
      {
        triangles[static_cast<size_t>(3 * f + c)] = firstCopy[static_cast<size_t>(p)]; // its only copy
        continue;
      }
      std::int64_t k = around.Begin(p);
      while (around.items[static_cast<size_t>(k)] != f)
      {
        ++k;
      }
      triangles[static_cast<size_t>(3 * f + c)] =
        firstCopy[static_cast<size_t>(p)] + label[static_cast<size_t>(k)];
    }
  }
  return triangles;
}
} // namespace

Status SplitAtFeatureEdges(const TriangleMesh& mesh, const double* normals,
  double featureAngleDegrees, int threads, FeatureSplitMesh& split)
{
  split = FeatureSplitMesh();
  if (!(featureAngleDegrees >= 0.0 && featureAngleDegrees <= 180.0))
  {
    return { "the feature angle must be in [0, 180] degrees" };
  }
  if (featureAngleDegrees >= 180.0 || mesh.NumberOfTriangles() == 0)
  {
    return {};
  }
  const int nthreads = ResolveThreadCount(threads);
  const double cosine = std::cos(featureAngleDegrees * 3.14159265358979323846 / 180.0);
  const std::vector<unsigned char> feature = FeatureEdgeFlags(mesh, normals, cosine, nthreads);
  const std::int64_t edges = CountFeatureEdges(mesh, feature);
  if (edges == 0)
  {
    return {};
  }
  const std::vector<unsigned char> touched = PointsOnFeatureEdges(mesh, feature);
  IdVector label(mesh.PointTriangles().items.size());
  const std::vector<std::int64_t> firstCopy = CopiesOfPoints(mesh, feature, touched, nthreads, label);
  split.original = OriginalPoints(firstCopy, nthreads);
  IdVector triangles = SplitTriangles(mesh, touched, firstCopy, label, nthreads);
  split.featureEdges = edges;
  // The same mesh as built from the copied points and these triangles, derived from `mesh`.
  return split.mesh.BuildSplit(mesh, split.original, std::move(triangles), nthreads);
}

} // namespace shock
