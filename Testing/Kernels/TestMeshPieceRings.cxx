// A piece of a mesh with R rings of the neighbouring triangles around its own
// (what a process of a distributed run filters): the mesh kernel reports how
// deep the traces of the own points went (AdvectionReport::deepestRing), and
// whenever that is at most R - MeshStencilRings the own points' results must
// be the whole mesh's. The rings are grown here breadth-first over the whole
// mesh, independently of the filters' distributed code.
#include "MeshShockAdvection.h"
#include "TestMeshes.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

using namespace shock;
using shocktest::MeshData;

namespace
{
TriangleMesh Build(const MeshData& data)
{
  TriangleMeshView view;
  view.numberOfPoints = data.NumberOfPoints();
  view.points = data.points.data();
  view.numberOfTriangles = data.NumberOfTriangles();
  view.triangles = data.triangles.data();
  TriangleMesh mesh;
  const Status status = mesh.Build(view, 1);
  EXPECT_TRUE(status.Ok()) << status.error;
  return mesh;
}

/**
 * Each triangle's ring around the own ones (0): a point's distance is the
 * fewest triangles between it and an own triangle's corner, and a triangle
 * not owned is in ring 1 + the smallest distance of its corners.
 */
std::vector<int> Rings(const MeshData& mesh, const std::vector<char>& own)
{
  const std::int64_t nt = mesh.NumberOfTriangles();
  const int far = 1 << 20;
  std::vector<int> distance(static_cast<size_t>(mesh.NumberOfPoints()), far);
  for (std::int64_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3 && own[t]; ++k)
    {
      distance[mesh.triangles[3 * t + k]] = 0;
    }
  }
  for (bool changed = true; changed;)
  {
    changed = false;
    for (std::int64_t t = 0; t < nt; ++t)
    {
      int nearest = far;
      for (int k = 0; k < 3; ++k)
      {
        nearest = std::min(nearest, distance[mesh.triangles[3 * t + k]]);
      }
      for (int k = 0; k < 3 && nearest < far; ++k)
      {
        int& d = distance[mesh.triangles[3 * t + k]];
        if (d > nearest + 1)
        {
          d = nearest + 1;
          changed = true;
        }
      }
    }
  }
  std::vector<int> ring(static_cast<size_t>(nt));
  for (std::int64_t t = 0; t < nt; ++t)
  {
    int nearest = far;
    for (int k = 0; k < 3; ++k)
    {
      nearest = std::min(nearest, distance[mesh.triangles[3 * t + k]]);
    }
    ring[t] = own[t] ? 0 : nearest + 1;
  }
  return ring;
}

/// The piece: the triangles of ring <= R, their points renumbered in order of first use.
struct Piece
{
  MeshData mesh;
  std::vector<std::int64_t> whole;     ///< whole-mesh point of each piece point
  std::vector<std::int64_t> triangles; ///< whole-mesh triangle of each piece triangle
  std::vector<unsigned char> ring;     ///< per piece triangle
};

Piece Cut(const MeshData& mesh, const std::vector<int>& ring, int R)
{
  Piece piece;
  std::map<std::int64_t, std::int64_t> local;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    if (ring[t] > R)
    {
      continue;
    }
    std::int64_t ids[3];
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t p = mesh.triangles[3 * t + k];
      const auto found = local.find(p);
      if (found == local.end())
      {
        ids[k] = static_cast<std::int64_t>(piece.whole.size());
        local.emplace(p, ids[k]);
        piece.whole.push_back(p);
        shocktest::AddPoint(piece.mesh, shocktest::Point(mesh, p));
      }
      else
      {
        ids[k] = found->second;
      }
    }
    shocktest::AddTriangle(piece.mesh, ids[0], ids[1], ids[2]);
    piece.triangles.push_back(t);
    piece.ring.push_back(static_cast<unsigned char>(ring[t]));
  }
  return piece;
}

/**
 * The runs of one case over R: a run whose traces stayed within R - stencil
 * must give the whole mesh's results; the others are counted, and some must
 * differ. Both sides of the bound must be seen, and the bound met with
 * equality (the most the check allows is exercised).
 */
struct RingRuns
{
  int exact = 0, flagged = 0, flaggedAndDifferent = 0, tight = 0;

  void Add(const std::string& name, int R, int stencil, int deepest, double difference)
  {
    if (deepest <= R - stencil)
    {
      EXPECT_LE(difference, 1e-12) << name << ", " << R << " rings, traces read ring " << deepest;
      ++this->exact;
      this->tight += deepest == R - stencil ? 1 : 0;
    }
    else
    {
      ++this->flagged;
      this->flaggedAndDifferent += difference > 1e-9 ? 1 : 0;
    }
  }

  void Check(const std::string& name) const
  {
    EXPECT_GT(this->exact, 0) << name;
    EXPECT_GT(this->flagged, 0) << name;
    EXPECT_GT(this->flaggedAndDifferent, 0) << name << ": too few rings must show somewhere";
    EXPECT_GT(this->tight, 0) << name;
  }
};

std::string CaseName(std::string name)
{
  std::replace_if(name.begin(), name.end(), [](char ch) { return !std::isalnum(static_cast<unsigned char>(ch)); }, '_');
  return name;
}

struct Case
{
  std::string name;
  MeshLocation location;
  int smoothingPasses;
  double contrast;
  Tracing tracing;
};

class PieceRings : public ::testing::TestWithParam<Case>
{
};

TEST_P(PieceRings, OwnResultsAreTheWholeMeshsWhenTheTracesStayedWithinTheExactRings)
{
  const Case c = GetParam();
  // An irregular bumpy sheet with a blurred step across it; the own triangles
  // are a band along the step, so that the back-traces of their points (away
  // from the step's centre) run out of the band into the rings.
  const MeshData mesh = shocktest::Noisy(shocktest::PlaneGrid(44, 36, 1.0), 0.3, 7u);
  const std::int64_t nt = mesh.NumberOfTriangles();
  const bool cells = c.location == MeshLocation::Triangles;
  std::vector<double> values;
  std::vector<char> own(static_cast<size_t>(nt), 0);
  for (std::int64_t t = 0; t < nt; ++t)
  {
    const auto corners = shocktest::TriangleCorners(mesh, t);
    using shocktest::operator+;
    using shocktest::operator*;
    const shock::Vec3 centre = (1.0 / 3.0) * (corners[0] + corners[1] + corners[2]);
    own[t] = std::abs(centre[0] + 0.2 * centre[1] - 22.0) < 3.0 ? 1 : 0;
    if (cells)
    {
      values.push_back(std::tanh((centre[0] + 0.2 * centre[1] - 22.0) / 3.0));
    }
  }
  for (std::int64_t p = 0; !cells && p < mesh.NumberOfPoints(); ++p)
  {
    const shock::Vec3 x = shocktest::Point(mesh, p);
    values.push_back(std::tanh((x[0] + 0.2 * x[1] - 22.0) / 3.0) + 0.1 * std::sin(x[1] / 3.0));
  }
  AdvectionParameters p;
  p.time = 4096.0;
  p.smoothingPasses = c.smoothingPasses;
  p.tracing = c.tracing;
  p.numberOfThreads = 1;
  const TriangleMesh wholeMesh = Build(mesh);
  MeshSignal signal;
  signal.location = c.location;
  signal.values = values.data();
  signal.potentialContrast = c.contrast;
  signal.contrastRings = 2;
  // The pieces are normalised as the whole mesh (as the filters pass the global scales).
  signal.valueScale = *std::max_element(values.begin(), values.end()) - *std::min_element(values.begin(), values.end());
  signal.lengthScale = wholeMesh.MeanEdgeLength();
  std::vector<double> whole(values.size());
  ASSERT_TRUE(AdvectMeshSignal(wholeMesh, signal, whole.data(), p).Ok());
  double moved = 0.0;
  for (size_t i = 0; i < values.size(); ++i)
  {
    moved = std::max(moved, std::abs(whole[i] - values[i]));
  }
  EXPECT_GT(moved, 0.05) << "the filter must change the signal";

  const int stencil = MeshStencilRings(signal, p);
  EXPECT_EQ(stencil, (cells ? 1 : 0) + 2 * c.smoothingPasses + 1 + (c.contrast > 0.0 ? 2 : 0));
  const std::vector<int> ring = Rings(mesh, own);
  RingRuns runs;
  for (int R = 1; R <= stencil + 12; ++R)
  {
    const Piece piece = Cut(mesh, ring, R);
    const TriangleMesh pieceMesh = Build(piece.mesh);
    std::vector<double> pieceValues;
    const auto rows = cells ? piece.triangles : piece.whole;
    for (std::int64_t r : rows)
    {
      pieceValues.push_back(values[r]);
    }
    MeshSignal pieceSignal = signal;
    pieceSignal.values = pieceValues.data();
    pieceSignal.triangleRing = piece.ring.data();
    std::vector<double> result(pieceValues.size());
    AdvectionReport report;
    ASSERT_TRUE(AdvectMeshSignal(pieceMesh, pieceSignal, result.data(), p, &report).Ok());
    ASSERT_GE(report.deepestRing, 0);
    // The own samples: the own triangles, or the points of the own triangles.
    double difference = 0.0;
    for (std::int64_t f = 0; f < pieceMesh.NumberOfTriangles(); ++f)
    {
      if (piece.ring[f] != 0)
      {
        continue;
      }
      if (cells)
      {
        difference = std::max(difference, std::abs(result[f] - whole[piece.triangles[f]]));
        continue;
      }
      for (int k = 0; k < 3; ++k)
      {
        const std::int64_t q = piece.mesh.triangles[3 * f + k];
        difference = std::max(difference, std::abs(result[q] - whole[piece.whole[q]]));
      }
    }
    runs.Add(c.name, R, stencil, report.deepestRing, difference);
  }
  runs.Check(c.name);
}

INSTANTIATE_TEST_SUITE_P(MeshKernel, PieceRings,
  ::testing::Values(Case{ "points", MeshLocation::Points, 1, 0.0, Tracing::FaceCrossing },
    Case{ "points, no smoothing", MeshLocation::Points, 0, 0.0, Tracing::FaceCrossing },
    Case{ "points, 2 passes, stepped", MeshLocation::Points, 2, 0.0, Tracing::Stepped },
    Case{ "points, contrast", MeshLocation::Points, 1, 1.5, Tracing::FaceCrossing },
    Case{ "cells", MeshLocation::Triangles, 1, 0.0, Tracing::FaceCrossing }),
  [](const ::testing::TestParamInfo<Case>& info) { return CaseName(info.param.name); });

TEST(PieceRings, NoRingsNoRecord)
{
  // A whole mesh (no ring array) reports no depth; Composed flows have no stencil bound.
  const MeshData mesh = shocktest::Noisy(shocktest::PlaneGrid(12, 10, 1.0), 0.2, 3u);
  std::vector<double> values;
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    values.push_back(std::tanh(shocktest::Point(mesh, p)[0] - 6.0));
  }
  MeshSignal signal;
  signal.values = values.data();
  AdvectionParameters p;
  p.time = 64.0;
  std::vector<double> out(values.size());
  AdvectionReport report;
  ASSERT_TRUE(AdvectMeshSignal(Build(mesh), signal, out.data(), p, &report).Ok());
  EXPECT_EQ(report.deepestRing, -1);
  EXPECT_EQ(MeshStencilRings(signal, p), 3);
  p.flowMode = FlowMode::Composed;
  p.flowUpdates = 4;
  EXPECT_EQ(MeshStencilRings(signal, p), -1);
  p.flowUpdates = 1; // one update: the fixed flow's
  EXPECT_EQ(MeshStencilRings(signal, p), 3);
}
}

namespace
{
TEST(PieceRings, TheTraceCapIsTheWholeMeshs)
{
  // A flow turning about the sheet's centre: traces circle until the step cap
  // (a few diameters of the mesh) stops them. A piece caps them as the whole
  // mesh it is cut from would (MeshSignal::wholeTriangles), not as itself.
  const MeshData data = shocktest::PlaneGrid(21, 21, 1.0);
  const TriangleMesh mesh = Build(data);
  std::vector<double> velocity(static_cast<size_t>(3 * mesh.NumberOfTriangles()));
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const auto c = shocktest::TriangleCorners(data, f);
    const double x = (c[0][0] + c[1][0] + c[2][0]) / 3.0 - 10.0, y = (c[0][1] + c[1][1] + c[2][1]) / 3.0 - 10.0;
    velocity[3 * f] = -y;
    velocity[3 * f + 1] = x;
  }
  AdvectionParameters p;
  std::int64_t steps[2];
  for (int k = 0; k < 2; ++k)
  {
    const SurfaceTracer tracer(mesh, velocity.data(), p, 1.0, k == 0 ? 0 : 16 * mesh.NumberOfTriangles());
    SurfacePoint q;
    q.triangle = mesh.NumberOfTriangles() / 2 + 41; // off the centre: a circle of a few edges
    bool truncated = false;
    steps[k] = tracer.Trace(q, 1e12, truncated);
    EXPECT_TRUE(truncated);
  }
  // The cap grows with the diameter, sqrt(triangles): 16 times the triangles, about 4 times the steps.
  EXPECT_GT(steps[1], 3 * steps[0]);
  EXPECT_LT(steps[1], 5 * steps[0]);
}
}

// Geometry sharpening on a piece: the sharpened normals of the own triangles
// (what the filters' distributed fit reads, SharpeningParameters::triangleRing)
// are the whole mesh's whenever the traces stayed within R - SharpeningStencilRings.
#include "MeshSharpening.h"

namespace
{
struct SharpenCase
{
  std::string name;
  int smoothingPasses;
  int normalPasses;
  double contrast;
  double featureAngle;
  Tracing tracing;
};

class SharpenPieceRings : public ::testing::TestWithParam<SharpenCase>
{
};

/// An irregular sheet folded into a rounded ridge along x + 0.2 y = 20 (a blurred crease).
MeshData RoundedRidge()
{
  MeshData mesh = shocktest::PlaneGrid(40, 32, 1.0);
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    const double d = mesh.points[3 * p] + 0.2 * mesh.points[3 * p + 1] - 20.0;
    mesh.points[3 * p + 2] = 6.0 - 0.7 * std::sqrt(d * d + 4.0);
  }
  return shocktest::Noisy(mesh, 0.15, 5u);
}

TEST_P(SharpenPieceRings, OwnNormalsAreTheWholeMeshsWhenTheTracesStayedWithinTheExactRings)
{
  const SharpenCase c = GetParam();
  const MeshData mesh = RoundedRidge();
  const std::int64_t nt = mesh.NumberOfTriangles();
  std::vector<char> own(static_cast<size_t>(nt), 0);
  for (std::int64_t t = 0; t < nt; ++t)
  {
    const auto corners = shocktest::TriangleCorners(mesh, t);
    const double x = (corners[0][0] + corners[1][0] + corners[2][0]) / 3.0;
    const double y = (corners[0][1] + corners[1][1] + corners[2][1]) / 3.0;
    own[t] = std::abs(x + 0.2 * y - 20.0) < 3.0 ? 1 : 0; // a band along the ridge
  }
  const TriangleMesh wholeMesh = Build(mesh);
  SharpeningParameters p;
  p.advection.time = 4096.0;
  p.advection.smoothingPasses = c.smoothingPasses;
  p.advection.tracing = c.tracing;
  p.advection.numberOfThreads = 1;
  p.normalSmoothingPasses = c.normalPasses;
  p.featureAngle = c.featureAngle;
  p.curvatureContrast = c.contrast;
  p.contrastRings = 2;
  p.fit.iterations = 1; // the normals are compared, not the positions
  // A piece is measured as the whole mesh (as the filters pass the global unit and size).
  p.lengthScale = wholeMesh.MeanEdgeLength();
  p.wholeTriangles = nt;
  std::vector<double> positions(mesh.points.size()), whole(static_cast<size_t>(3 * nt));
  SharpeningReport wholeReport;
  ASSERT_TRUE(SharpenMeshGeometry(wholeMesh, p, positions.data(), whole.data(), &wholeReport).Ok());
  EXPECT_EQ(wholeReport.advection.deepestRing, -1) << "no rings given, no record";
  if (c.featureAngle < 180.0)
  {
    EXPECT_GT(wholeReport.featureEdges, 0) << c.name << ": the feature split must be exercised";
  }
  double turned = 0.0; // the largest angle between a sharpened and an input normal, as 1 - cos
  for (std::int64_t f = 0; f < nt; ++f)
  {
    turned = std::max(turned, 1.0 - Dot(Vec3{ whole[3 * f], whole[3 * f + 1], whole[3 * f + 2] },
                                    Vec3{ wholeMesh.Normal(f)[0], wholeMesh.Normal(f)[1], wholeMesh.Normal(f)[2] }));
  }
  EXPECT_GT(turned, 0.01) << c.name << ": the sharpening must turn some normals";

  const int stencil = SharpeningStencilRings(p);
  EXPECT_EQ(stencil, c.normalPasses + 1 + 2 * c.smoothingPasses + 1 + (c.contrast > 0.0 ? 2 : 0));
  const std::vector<int> ring = Rings(mesh, own);
  RingRuns runs;
  for (int R = 1; R <= stencil + 12; ++R)
  {
    const Piece piece = Cut(mesh, ring, R);
    const TriangleMesh pieceMesh = Build(piece.mesh);
    SharpeningParameters q = p;
    q.triangleRing = piece.ring.data();
    std::vector<double> piecePositions(piece.mesh.points.size());
    std::vector<double> normals(static_cast<size_t>(3 * pieceMesh.NumberOfTriangles()));
    SharpeningReport report;
    ASSERT_TRUE(SharpenMeshGeometry(pieceMesh, q, piecePositions.data(), normals.data(), &report).Ok());
    ASSERT_GE(report.advection.deepestRing, 0);
    double difference = 0.0;
    for (std::int64_t f = 0; f < pieceMesh.NumberOfTriangles(); ++f)
    {
      for (int k = 0; k < 3 && piece.ring[f] == 0; ++k)
      {
        difference = std::max(difference, std::abs(normals[3 * f + k] - whole[3 * piece.triangles[f] + k]));
      }
    }
    runs.Add(c.name, R, stencil, report.advection.deepestRing, difference);
  }
  runs.Check(c.name);
}

INSTANTIATE_TEST_SUITE_P(MeshKernel, SharpenPieceRings,
  ::testing::Values(SharpenCase{ "defaults", 1, 0, 16.0, 30.0, Tracing::FaceCrossing },
    SharpenCase{ "normal smoothing", 1, 2, 16.0, 12.0, Tracing::FaceCrossing },
    SharpenCase{ "paper potential, no split", 1, 0, 0.0, 180.0, Tracing::FaceCrossing },
    SharpenCase{ "normal smoothing, paper potential", 1, 2, 0.0, 12.0, Tracing::FaceCrossing },
    SharpenCase{ "feature split, stepped", 0, 1, 16.0, 12.0, Tracing::Stepped }),
  [](const ::testing::TestParamInfo<SharpenCase>& info) { return CaseName(info.param.name); });

TEST(SharpenPieceRings, RecomputedFlowsHaveNoBound)
{
  SharpeningParameters p;
  p.advection.flowMode = FlowMode::Composed;
  p.advection.flowUpdates = 3;
  EXPECT_EQ(SharpeningStencilRings(p), -1);
  p.advection.flowUpdates = 1;
  p.normalSmoothingPasses = 3;
  p.curvatureContrast = 0.0;
  EXPECT_EQ(SharpeningStencilRings(p), 3 + 1 + 2 * p.advection.smoothingPasses + 1);
}
}

namespace
{
TEST(SharpenPieceRings, ARepeatedTriangleKeepsItsRing)
{
  // A piece with a repeated triangle: the repeat is removed before the
  // sharpening (SharpFeatures), and the kept triangle keeps the lowest ring of
  // the two, so the depth is still recorded and the own normals are those of
  // the piece without the repeat.
  const MeshData mesh = RoundedRidge();
  std::vector<char> own(static_cast<size_t>(mesh.NumberOfTriangles()), 0);
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const auto c = shocktest::TriangleCorners(mesh, t);
    own[t] = std::abs((c[0][0] + c[1][0] + c[2][0]) / 3.0 - 20.0) < 3.0 ? 1 : 0;
  }
  const Piece piece = Cut(mesh, Rings(mesh, own), 14);
  SharpeningParameters p;
  p.advection.time = 1024.0;
  p.advection.numberOfThreads = 1;
  p.fit.iterations = 1;
  p.lengthScale = Build(mesh).MeanEdgeLength();
  p.triangleRing = piece.ring.data();
  const TriangleMesh plain = Build(piece.mesh);
  std::vector<double> positions(piece.mesh.points.size()), normals(static_cast<size_t>(3 * plain.NumberOfTriangles()));
  SharpeningReport report;
  ASSERT_TRUE(SharpenMeshGeometry(plain, p, positions.data(), normals.data(), &report).Ok());

  // An own triangle's copy put first (so it is the one kept, and every later
  // triangle moves by one in the mesh without the repeat), given a deep ring.
  std::int64_t first = 0;
  while (piece.ring[static_cast<size_t>(first)] != 0)
  {
    ++first;
  }
  MeshData repeated = piece.mesh;
  repeated.triangles.insert(repeated.triangles.begin(), piece.mesh.triangles.begin() + 3 * first,
    piece.mesh.triangles.begin() + 3 * first + 3);
  std::vector<unsigned char> rings = piece.ring;
  rings.insert(rings.begin(), 9);
  SharpeningParameters q = p;
  q.triangleRing = rings.data();
  const TriangleMesh withRepeat = Build(repeated);
  std::vector<double> normalsWithRepeat(static_cast<size_t>(3 * withRepeat.NumberOfTriangles()));
  SharpeningReport reportWithRepeat;
  ASSERT_TRUE(SharpenMeshGeometry(withRepeat, q, positions.data(), normalsWithRepeat.data(), &reportWithRepeat).Ok());
  EXPECT_EQ(reportWithRepeat.repeatedTriangles, 1);
  EXPECT_EQ(reportWithRepeat.advection.deepestRing, report.advection.deepestRing);
  EXPECT_GE(report.advection.deepestRing, 0);
  for (std::int64_t f = 0; f < plain.NumberOfTriangles(); ++f)
  {
    for (int k = 0; k < 3 && piece.ring[static_cast<size_t>(f)] == 0; ++k)
    {
      EXPECT_NEAR(normalsWithRepeat[3 * (f + 1) + k], normals[3 * f + k], 1e-12) << "triangle " << f;
    }
  }
}
}
