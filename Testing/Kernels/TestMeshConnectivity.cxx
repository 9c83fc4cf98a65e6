// MeshConnectivity against brute-force computations written from its
// definitions, on meshes with the defects users have (non-manifold edges,
// repeated ids, isolated points, duplicate points), on 1 and 2 threads; and
// TriangleMesh over a shared connectivity with moved points against a fresh build.
#include "MeshConnectivity.h"
#include "TestMeshes.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>
#include <vector>

namespace
{

using shocktest::MeshData;

/// Triangles that use point p, by scanning every triangle.
std::vector<std::int64_t> TrianglesOf(const MeshData& m, std::int64_t p)
{
  std::vector<std::int64_t> list;
  for (std::int64_t f = 0; f < m.NumberOfTriangles(); ++f)
  {
    const std::int64_t* t = &m.triangles[static_cast<size_t>(3 * f)];
    if (t[0] == p || t[1] == p || t[2] == p)
    {
      list.push_back(f);
    }
  }
  return list;
}

/// Points that share a triangle with p (every two corners of a triangle are joined).
std::vector<std::int64_t> RingOf(const MeshData& m, std::int64_t p)
{
  std::set<std::int64_t> ring;
  for (std::int64_t f : TrianglesOf(m, p))
  {
    for (int c = 0; c < 3; ++c)
    {
      if (m.triangles[static_cast<size_t>(3 * f + c)] != p)
      {
        ring.insert(m.triangles[static_cast<size_t>(3 * f + c)]);
      }
    }
  }
  return { ring.begin(), ring.end() };
}

/// The triangle across edge (a, b) of f: the only other triangle with both a and b, else -1.
std::int64_t Across(const MeshData& m, std::int64_t f, std::int64_t a, std::int64_t b)
{
  if (a == b)
  {
    return -1;
  }
  std::vector<std::int64_t> others;
  for (std::int64_t g : TrianglesOf(m, a))
  {
    const std::int64_t* t = &m.triangles[static_cast<size_t>(3 * g)];
    if (g != f && (t[0] == b || t[1] == b || t[2] == b))
    {
      others.push_back(g);
    }
  }
  return others.size() == 1 ? others[0] : -1;
}

std::vector<std::int64_t> List(const shock::CompressedLists& lists, std::int64_t i)
{
  return { lists.items.begin() + lists.Begin(i), lists.items.begin() + lists.End(i) };
}

void ExpectMatchesDefinitions(const MeshData& m, int threads)
{
  shock::MeshConnectivity c;
  ASSERT_TRUE(c.Build(m.NumberOfPoints(), m.triangles, threads).Ok());
  ASSERT_EQ(c.NumberOfTriangles(), m.NumberOfTriangles());
  std::set<std::pair<std::int64_t, std::int64_t>> edges;
  for (std::int64_t p = 0; p < m.NumberOfPoints(); ++p)
  {
    ASSERT_EQ(List(c.PointTriangles(), p), TrianglesOf(m, p)) << "point " << p;
    const std::vector<std::int64_t> ring = RingOf(m, p);
    ASSERT_EQ(List(c.OneRing(), p), ring) << "point " << p;
    for (std::int64_t w : ring)
    {
      edges.insert({ std::min(p, w), std::max(p, w) });
    }
  }
  EXPECT_EQ(c.NumberOfEdges(), static_cast<std::int64_t>(edges.size()));
  int joined = 0;
  for (std::int64_t f = 0; f < m.NumberOfTriangles(); ++f)
  {
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = m.triangles[static_cast<size_t>(3 * f + e)];
      const std::int64_t b = m.triangles[static_cast<size_t>(3 * f + (e + 1) % 3)];
      ASSERT_EQ(c.Neighbour(f, e), Across(m, f, a, b)) << "triangle " << f << " edge " << e;
      joined += c.Neighbour(f, e) >= 0 ? 1 : 0;
    }
  }
  EXPECT_GT(joined, 0); // not a mesh of isolated triangles
}

TEST(MeshConnectivity, MatchesItsDefinitionsOnMeshesWithDefects)
{
  const MeshData meshes[] = { shocktest::Icosphere(1), shocktest::NonManifoldFan(),
    shocktest::WithDegenerateTriangles(shocktest::PlaneGrid(5, 4)),
    shocktest::WithIsolatedPoints(shocktest::Cylinder(7, 3, 1.0, 2.0), 3),
    shocktest::WithDuplicatePoints(shocktest::Icosphere(1)), shocktest::TwoComponents(1) };
  for (const MeshData& m : meshes)
  {
    for (int threads : { 1, 2 })
    {
      ExpectMatchesDefinitions(m, threads);
    }
  }
}

TEST(MeshConnectivity, RejectsIdsOutOfRange)
{
  shock::MeshConnectivity c;
  EXPECT_FALSE(c.Build(3, { 0, 1, 3 }, 1).Ok());
  EXPECT_FALSE(c.Build(3, { 0, -1, 2 }, 1).Ok());
  EXPECT_FALSE(c.Build(3, { 0, 1 }, 1).Ok());
  EXPECT_TRUE(c.Build(3, { 0, 1, 2 }, 1).Ok());
}

TEST(MeshConnectivity, MovedPointsOverASharedConnectivityEqualAFreshBuild)
{
  const MeshData sphere = shocktest::Icosphere(2);
  shock::TriangleMesh first;
  ASSERT_TRUE(first.Build({ sphere.NumberOfPoints(), sphere.points.data(), sphere.NumberOfTriangles(),
                            sphere.triangles.data() },
    2)
                .Ok());
  const MeshData moved = shocktest::Noisy(shocktest::Transformed(sphere, 2.5, { 1.0, -2.0, 0.5 }), 0.05, 7);
  shock::TriangleMesh shared;
  ASSERT_TRUE(shared.Build(first.SharedConnectivity(), moved.points.data(), 2).Ok());
  EXPECT_EQ(&shared.Connectivity(), &first.Connectivity()); // shared, not copied
  shock::TriangleMesh fresh;
  ASSERT_TRUE(fresh.Build({ moved.NumberOfPoints(), moved.points.data(), moved.NumberOfTriangles(),
                            moved.triangles.data() },
    1)
                .Ok());
  EXPECT_NE(shared.MeanEdgeLength(), first.MeanEdgeLength()); // the geometry did change
  EXPECT_EQ(shared.MeanEdgeLength(), fresh.MeanEdgeLength());
  for (std::int64_t f = 0; f < fresh.NumberOfTriangles(); ++f)
  {
    ASSERT_EQ(shared.Area(f), fresh.Area(f));
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(shared.Neighbour(f, c), fresh.Neighbour(f, c));
      for (int k = 0; k < 3; ++k)
      {
        ASSERT_EQ(shared.HatGradient(f, c)[k], fresh.HatGradient(f, c)[k]);
      }
    }
  }
  // A non-finite coordinate is refused.
  std::vector<double> bad = moved.points;
  bad[4] = std::numeric_limits<double>::quiet_NaN();
  shock::TriangleMesh refused;
  EXPECT_FALSE(refused.Build(first.SharedConnectivity(), bad.data(), 1).Ok());
}

} // namespace
