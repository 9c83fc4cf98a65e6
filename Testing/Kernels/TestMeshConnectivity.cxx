// MeshConnectivity against brute-force computations written from its
// definitions, on meshes with the defects users have (non-manifold edges,
// repeated ids, isolated points, duplicate points), on 1 and 2 threads; and
// TriangleMesh over a shared connectivity with moved points against a fresh build.
#include "MeshConnectivity.h"
#include "MeshOrder.h"
#include "TestMeshes.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
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
  EXPECT_FALSE(c.Build(3, shock::IdVector{ 0, 1, 3 }, 1).Ok());
  EXPECT_FALSE(c.Build(3, shock::IdVector{ 0, -1, 2 }, 1).Ok());
  EXPECT_FALSE(c.Build(3, shock::IdVector{ 0, 1 }, 1).Ok());
  EXPECT_TRUE(c.Build(3, shock::IdVector{ 0, 1, 2 }, 1).Ok());
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

/// Every list, neighbour and geometry value of `a` equals those of `b`.
void ExpectSameMesh(const shock::TriangleMesh& a, const shock::TriangleMesh& b)
{
  ASSERT_EQ(a.NumberOfPoints(), b.NumberOfPoints());
  ASSERT_EQ(a.NumberOfTriangles(), b.NumberOfTriangles());
  EXPECT_EQ(a.NumberOfEdges(), b.NumberOfEdges());
  EXPECT_EQ(a.MeanEdgeLength(), b.MeanEdgeLength());
  EXPECT_EQ(a.PointTriangles().offsets, b.PointTriangles().offsets);
  EXPECT_EQ(a.PointTriangles().items, b.PointTriangles().items);
  EXPECT_EQ(a.OneRing().offsets, b.OneRing().offsets);
  EXPECT_EQ(a.OneRing().items, b.OneRing().items);
  for (std::int64_t p = 0; p < a.NumberOfPoints(); ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      ASSERT_EQ(a.Point(p)[k], b.Point(p)[k]);
    }
  }
  for (std::int64_t f = 0; f < a.NumberOfTriangles(); ++f)
  {
    ASSERT_EQ(a.Area(f), b.Area(f));
    ASSERT_EQ(a.Degenerate(f), b.Degenerate(f));
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(a.Corners(f)[c], b.Corners(f)[c]);
      ASSERT_EQ(a.Connectivity().Neighbour(f, c), b.Connectivity().Neighbour(f, c)) << "triangle " << f;
      ASSERT_EQ(a.Neighbour(f, c), b.Neighbour(f, c));
      ASSERT_EQ(a.Normal(f)[c], b.Normal(f)[c]);
      ASSERT_EQ(a.Centroid(f)[c], b.Centroid(f)[c]);
      for (int k = 0; k < 3; ++k)
      {
        ASSERT_EQ(a.HatGradient(f, c)[k], b.HatGradient(f, c)[k]);
      }
    }
  }
}

TEST(MeshConnectivity, SplitPointsDerivedFromTheSourceEqualAFreshBuild)
{
  const MeshData meshes[] = { shocktest::Icosphere(2), shocktest::NonManifoldFan(),
    shocktest::WithDegenerateTriangles(shocktest::PlaneGrid(6, 5)),
    shocktest::WithIsolatedPoints(shocktest::Cylinder(7, 3, 1.0, 2.0), 3),
    shocktest::WithDuplicatePoints(shocktest::Icosphere(1)), shocktest::TwoComponents(1) };
  for (const MeshData& m : meshes)
  {
    shock::TriangleMesh source;
    ASSERT_TRUE(source.Build({ m.NumberOfPoints(), m.points.data(), m.NumberOfTriangles(), m.triangles.data() }, 2).Ok());
    for (int pattern = 0; pattern < 3; ++pattern)
    {
      // Points split into 1 to 3 copies (none, some or most of them), each
      // triangle using one copy of each of its points (chosen by a hash).
      const std::int64_t np = m.NumberOfPoints();
      std::vector<std::int64_t> firstCopy(static_cast<size_t>(np) + 1, 0);
      for (std::int64_t p = 0; p < np; ++p)
      {
        const std::int64_t count = pattern == 0 ? 1 : 1 + (p * 7 + pattern) % (pattern == 1 ? 5 : 2) % 3;
        firstCopy[static_cast<size_t>(p) + 1] = firstCopy[static_cast<size_t>(p)] + count;
      }
      std::vector<std::int64_t> original;
      std::vector<double> points;
      for (std::int64_t p = 0; p < np; ++p)
      {
        for (std::int64_t q = firstCopy[static_cast<size_t>(p)]; q < firstCopy[static_cast<size_t>(p) + 1]; ++q)
        {
          original.push_back(p);
          points.insert(points.end(), m.points.begin() + 3 * p, m.points.begin() + 3 * p + 3);
        }
      }
      std::vector<std::int64_t> triangles(m.triangles.size());
      for (size_t i = 0; i < triangles.size(); ++i)
      {
        const std::int64_t p = m.triangles[i];
        const std::int64_t f = static_cast<std::int64_t>(i / 3);
        const std::int64_t count = firstCopy[static_cast<size_t>(p) + 1] - firstCopy[static_cast<size_t>(p)];
        triangles[i] = firstCopy[static_cast<size_t>(p)] + (f * 31 + p * 17) % count;
      }
      for (int threads : { 1, 2 })
      {
        shock::TriangleMesh split;
        ASSERT_TRUE(split.BuildSplit(source, original, shock::IdVector(triangles.begin(), triangles.end()), threads).Ok());
        EXPECT_TRUE(split.Connectivity().DerivedFromSource());
        shock::TriangleMesh fresh;
        ASSERT_TRUE(fresh.Build({ static_cast<std::int64_t>(original.size()), points.data(),
                                  m.NumberOfTriangles(), triangles.data() },
          threads)
                      .Ok());
        ExpectSameMesh(split, fresh);
      }
    }
  }
  // Not a split of the source (a corner that is no copy of the source's): built the general way.
  const MeshData sphere = shocktest::Icosphere(1);
  shock::TriangleMesh source;
  ASSERT_TRUE(source.Build({ sphere.NumberOfPoints(), sphere.points.data(), sphere.NumberOfTriangles(),
                             sphere.triangles.data() },
    1)
                .Ok());
  std::vector<std::int64_t> original(static_cast<size_t>(sphere.NumberOfPoints()));
  for (size_t p = 0; p < original.size(); ++p)
  {
    original[p] = static_cast<std::int64_t>(p);
  }
  std::vector<std::int64_t> triangles = sphere.triangles;
  std::swap(triangles[0], triangles[3]);
  shock::TriangleMesh other;
  ASSERT_TRUE(other.BuildSplit(source, original, shock::IdVector(triangles.begin(), triangles.end()), 2).Ok());
  EXPECT_FALSE(other.Connectivity().DerivedFromSource());
  shock::TriangleMesh fresh;
  ASSERT_TRUE(fresh.Build({ sphere.NumberOfPoints(), sphere.points.data(), sphere.NumberOfTriangles(),
                            triangles.data() },
    1)
                .Ok());
  ExpectSameMesh(other, fresh);
}

} // namespace

namespace
{
/// The Morton code from its definition: bit k of a point's cell index along axis a
/// is bit 3k + a of the code; the cell index is floor(1024 (x - low) / side), at most 1023.
std::uint64_t MortonByDefinition(const double* x, const double low[3], const double side[3])
{
  std::uint64_t code = 0;
  for (int a = 0; a < 3; ++a)
  {
    double cell = side[a] > 0.0 ? std::floor(1024.0 * (x[a] - low[a]) / side[a]) : 0.0;
    cell = std::min(std::max(cell, 0.0), 1023.0);
    const auto index = static_cast<std::uint64_t>(cell);
    for (int k = 0; k < 10; ++k)
    {
      code |= ((index >> k) & 1u) << (3 * k + a);
    }
  }
  return code;
}
/// (smallest corner's rank, index) of every triangle, sorted: the expected triangle order.
std::vector<std::pair<std::int64_t, std::int64_t>> ByFirstCorner(const MeshData& m, const shock::IdVector& rank)
{
  std::vector<std::pair<std::int64_t, std::int64_t>> byCorner;
  for (std::int64_t f = 0; f < m.NumberOfTriangles(); ++f)
  {
    const std::int64_t* t = &m.triangles[static_cast<size_t>(3 * f)];
    byCorner.push_back({ std::min({ rank[static_cast<size_t>(t[0])], rank[static_cast<size_t>(t[1])],
                           rank[static_cast<size_t>(t[2])] }),
      f });
  }
  std::sort(byCorner.begin(), byCorner.end());
  return byCorner;
}
}

TEST(MeshOrder, PointsFollowTheMortonCurveAndTrianglesTheirFirstCorner)
{
  // Meshes with defects, their points shuffled so that the order has work to do;
  // the expected orders are computed by sorting on keys from the definitions.
  const MeshData meshes[] = { shocktest::Icosphere(3), shocktest::NonManifoldFan(),
    shocktest::WithIsolatedPoints(shocktest::Cylinder(9, 5, 1.0, 2.0), 3),
    shocktest::WithDuplicatePoints(shocktest::Icosphere(2)), shocktest::PlaneGrid(6, 2) }; // flat: one side 0
  for (MeshData m : meshes)
  {
    // Reverse the point numbering (an order unlike the Morton curve's).
    const std::int64_t np = m.NumberOfPoints();
    std::vector<double> points(m.points.size());
    for (std::int64_t p = 0; p < np; ++p)
    {
      std::copy(&m.points[static_cast<size_t>(3 * p)], &m.points[static_cast<size_t>(3 * p)] + 3,
        &points[static_cast<size_t>(3 * (np - 1 - p))]);
    }
    m.points = points;
    for (std::int64_t& id : m.triangles)
    {
      id = np - 1 - id;
    }
    double low[3];
    double high[3];
    for (int a = 0; a < 3; ++a)
    {
      low[a] = std::numeric_limits<double>::infinity();
      high[a] = -low[a];
      for (std::int64_t p = 0; p < np; ++p)
      {
        low[a] = std::min(low[a], m.points[static_cast<size_t>(3 * p + a)]);
        high[a] = std::max(high[a], m.points[static_cast<size_t>(3 * p + a)]);
      }
    }
    const double side[3] = { high[0] - low[0], high[1] - low[1], high[2] - low[2] };
    std::vector<std::pair<std::uint64_t, std::int64_t>> byCode;
    for (std::int64_t p = 0; p < np; ++p)
    {
      byCode.push_back({ MortonByDefinition(&m.points[static_cast<size_t>(3 * p)], low, side), p });
    }
    std::sort(byCode.begin(), byCode.end()); // equal codes: old order
    const shock::MeshNumbering one = shock::LocalityNumbering(np, m.points.data(), m.NumberOfTriangles(), m.triangles.data(), 1);
    ASSERT_EQ(one.points.size(), static_cast<size_t>(np));
    for (std::int64_t i = 0; i < np; ++i)
    {
      ASSERT_EQ(one.points[static_cast<size_t>(i)], byCode[static_cast<size_t>(i)].second) << i;
      ASSERT_EQ(one.rank[static_cast<size_t>(one.points[static_cast<size_t>(i)])], i);
    }
    const std::int64_t nt = m.NumberOfTriangles();
    const auto byCorner = ByFirstCorner(m, one.rank);
    ASSERT_EQ(one.triangles.size(), static_cast<size_t>(nt));
    for (std::int64_t f = 0; f < nt; ++f)
    {
      ASSERT_EQ(one.triangles[static_cast<size_t>(f)], byCorner[static_cast<size_t>(f)].second) << f;
    }
    // Something moved, and the thread count changes nothing.
    bool moved = false;
    for (std::int64_t i = 0; i < np; ++i)
    {
      moved = moved || one.points[static_cast<size_t>(i)] != i;
    }
    EXPECT_TRUE(moved || np < 3);
    const shock::MeshNumbering two = shock::LocalityNumbering(np, m.points.data(), m.NumberOfTriangles(), m.triangles.data(), 2);
    EXPECT_TRUE(std::equal(one.points.begin(), one.points.end(), two.points.begin(), two.points.end()));
    EXPECT_TRUE(std::equal(one.triangles.begin(), one.triangles.end(), two.triangles.begin(), two.triangles.end()));
  }
}

TEST(MeshOrder, CoincidentPointsAreTheFirstWithTheSameCoordinates)
{
  // Copies of seam points, copies far apart in the numbering, 0 and -0, and a
  // far outlier that puts many points in one cell of the Morton grid (a long run).
  MeshData m = shocktest::WithDuplicatePoints(shocktest::Icosphere(2));
  const std::int64_t n = m.NumberOfPoints();
  for (std::int64_t p = 0; p < n; p += 7)
  {
    m.points.insert(m.points.end(), &m.points[static_cast<size_t>(3 * p)], &m.points[static_cast<size_t>(3 * p)] + 3);
  }
  m.points.insert(m.points.end(), { 0.0, -0.0, 0.0, -0.0, 0.0, 0.0, 0.0, 0.0, -0.0 });
  std::vector<double> withOutlier = m.points;
  withOutlier.insert(withOutlier.end(), { 1e6, 1e6, 1e6 });
  for (const std::vector<double>* points : { &m.points, &withOutlier })
  {
    const auto np = static_cast<std::int64_t>(points->size() / 3);
    std::vector<std::int64_t> expected(static_cast<size_t>(np));
    std::int64_t copies = 0;
    for (std::int64_t p = 0; p < np; ++p)
    {
      expected[static_cast<size_t>(p)] = p;
      for (std::int64_t q = 0; q < p; ++q)
      {
        const double* a = &(*points)[static_cast<size_t>(3 * p)];
        const double* b = &(*points)[static_cast<size_t>(3 * q)];
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
        {
          expected[static_cast<size_t>(p)] = q;
          ++copies;
          break;
        }
      }
    }
    ASSERT_GT(copies, 20);
    for (int threads : { 1, 2 })
    {
      const shock::MeshNumbering numbering = shock::MortonOrder(np, points->data(), threads);
      EXPECT_EQ(shock::CoincidentPoints(numbering, points->data(), threads), expected) << threads;
    }
  }
}

TEST(MeshOrder, LargeMeshesGiveTheSameOrdersOnOneAndTwoThreads)
{
  // Above the work size at which ThreadsForWork gives a second thread, so that the
  // parallel counting sort and the parallel search of copies really run on two.
  MeshData m = shocktest::WithDuplicatePoints(shocktest::Icosphere(6));
  const std::int64_t np = m.NumberOfPoints();
  const std::int64_t nt = m.NumberOfTriangles();
  ASSERT_GT(std::min(np, nt), 2 * shock::MinimumWorkPerThread);
  ASSERT_EQ(shock::ThreadsForWork(2, np), 2);
  const shock::MeshNumbering one = shock::LocalityNumbering(np, m.points.data(), nt, m.triangles.data(), 1);
  const shock::MeshNumbering two = shock::LocalityNumbering(np, m.points.data(), nt, m.triangles.data(), 2);
  EXPECT_TRUE(std::equal(one.points.begin(), one.points.end(), two.points.begin(), two.points.end()));
  EXPECT_TRUE(std::equal(one.rank.begin(), one.rank.end(), two.rank.begin(), two.rank.end()));
  EXPECT_TRUE(std::equal(one.triangles.begin(), one.triangles.end(), two.triangles.begin(), two.triangles.end()));
  // The triangle order against a sort by (first corner, index).
  const auto byCorner = ByFirstCorner(m, one.rank);
  for (std::int64_t f = 0; f < nt; ++f)
  {
    ASSERT_EQ(two.triangles[static_cast<size_t>(f)], byCorner[static_cast<size_t>(f)].second) << f;
  }
  // The copies against the first index of each coordinate triple.
  std::map<std::array<double, 3>, std::int64_t> first;
  std::vector<std::int64_t> expected(static_cast<size_t>(np));
  for (std::int64_t p = 0; p < np; ++p)
  {
    const std::array<double, 3> x{ m.points[static_cast<size_t>(3 * p)], m.points[static_cast<size_t>(3 * p + 1)],
      m.points[static_cast<size_t>(3 * p + 2)] };
    expected[static_cast<size_t>(p)] = first.emplace(x, p).first->second;
  }
  EXPECT_LT(first.size(), static_cast<size_t>(np)); // there are copies
  EXPECT_EQ(shock::CoincidentPoints(one, m.points.data(), 1), expected);
  EXPECT_EQ(shock::CoincidentPoints(two, m.points.data(), 2), expected);
}
