// The screened Poisson fit on a mesh split into pieces (MeshPartition), run in
// one process: each piece in its own thread, the "communication" a shared
// buffer and a barrier. The pieces' positions must equal the serial fit's.
#include "MeshPartition.h"
#include "ScreenedPoissonFit.h"
#include "TestMeshes.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <map>
#include <mutex>
#include <set>
#include <tuple>
#include <thread>
#include <vector>

using namespace shock;
using shocktest::MeshData;

namespace
{
/// A reusable barrier for `count` threads (C++17 has none).
class Barrier
{
public:
  explicit Barrier(int count) : Count(count) {}
  void Wait()
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    const int generation = this->Generation;
    if (++this->Arrived == this->Count)
    {
      this->Arrived = 0;
      ++this->Generation;
      this->Done.notify_all();
      return;
    }
    this->Done.wait(lock, [&] { return generation != this->Generation; });
  }

private:
  std::mutex Mutex;
  std::condition_variable Done;
  int Count, Arrived = 0, Generation = 0;
};

/// One piece: owned triangles (by centroid) plus every triangle touching their points.
struct Piece
{
  MeshData mesh;
  std::vector<std::int64_t> global; ///< global id of each local point
  MeshPartition partition;
};

Piece Cut(const MeshData& whole, const std::vector<int>& owner, int me)
{
  const std::int64_t nt = whole.NumberOfTriangles();
  std::vector<char> touched(static_cast<size_t>(whole.NumberOfPoints()), 0);
  for (std::int64_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3 && owner[t] == me; ++k)
    {
      touched[whole.triangles[3 * t + k]] = 1;
    }
  }
  // The point's owner: the lowest piece whose own triangles use it.
  std::vector<int> pointOwner(touched.size(), 1 << 30);
  for (std::int64_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      int& o = pointOwner[whole.triangles[3 * t + k]];
      o = std::min(o, owner[t]);
    }
  }
  Piece piece;
  std::map<std::int64_t, std::int64_t> local;
  for (std::int64_t t = 0; t < nt; ++t)
  {
    const std::int64_t* c = &whole.triangles[3 * t];
    if (owner[t] != me && !touched[c[0]] && !touched[c[1]] && !touched[c[2]])
    {
      continue; // neither owned nor in the ghost layer
    }
    std::int64_t ids[3];
    for (int k = 0; k < 3; ++k)
    {
      auto found = local.find(c[k]);
      if (found == local.end())
      {
        found = local.emplace(c[k], piece.global.size()).first;
        piece.global.push_back(c[k]);
        const double* x = &whole.points[3 * c[k]];
        piece.mesh.points.insert(piece.mesh.points.end(), x, x + 3);
        piece.partition.ownedPoints.push_back(pointOwner[c[k]] == me ? 1 : 0);
      }
      ids[k] = found->second;
    }
    shocktest::AddTriangle(piece.mesh, ids[0], ids[1], ids[2]);
    piece.partition.ownedTriangles.push_back(owner[t] == me ? 1 : 0);
  }
  return piece;
}

/**
 * Each piece's sharedPoints, written from the pieces' global ids alone: the
 * points a piece owns that another piece holds without owning them.
 */
void MarkSharedPoints(std::vector<Piece>& pieces)
{
  std::set<std::int64_t> readElsewhere;
  for (const Piece& piece : pieces)
  {
    for (size_t i = 0; i < piece.global.size(); ++i)
    {
      if (!piece.partition.ownedPoints[i])
      {
        readElsewhere.insert(piece.global[i]);
      }
    }
  }
  size_t marked = 0, owned = 0;
  for (Piece& piece : pieces)
  {
    piece.partition.sharedPoints.assign(piece.global.size(), 0);
    for (size_t i = 0; i < piece.global.size(); ++i)
    {
      piece.partition.sharedPoints[i] = piece.partition.ownedPoints[i] && readElsewhere.count(piece.global[i]);
      marked += piece.partition.sharedPoints[i];
      owned += piece.partition.ownedPoints[i];
    }
  }
  // Every point read elsewhere has one owner; most owned points are read by no other piece.
  EXPECT_EQ(marked, readElsewhere.size());
  EXPECT_LT(2 * marked, owned);
}

TriangleMesh Build(const MeshData& m)
{
  TriangleMesh mesh;
  EXPECT_TRUE(mesh.Build({ m.NumberOfPoints(), m.points.data(), m.NumberOfTriangles(), m.triangles.data() }, 1).Ok());
  return mesh;
}

/// Target normals: the triangle normals tilted by a smooth field, the same function of position everywhere.
std::vector<double> Targets(const MeshData& m)
{
  std::vector<double> targets;
  for (std::int64_t t = 0; t < m.NumberOfTriangles(); ++t)
  {
    const shocktest::Vec3 n = shocktest::TriangleNormal(m, t);
    const shocktest::Vec3 c = shocktest::TriangleCentroid(m, t);
    targets.insert(targets.end(), { n[0] + 0.3 * std::sin(3 * c[1]), n[1], n[2] + 0.2 * c[0] });
  }
  return targets;
}
}

TEST(DistributedFit, PiecesGiveTheSerialFit)
{
  const MeshData whole = shocktest::Icosphere(3);
  const int pieces = 3;
  // Pieces by the angle of the triangle's centroid around z: uneven, with corners where three meet.
  std::vector<int> owner;
  for (std::int64_t t = 0; t < whole.NumberOfTriangles(); ++t)
  {
    const shocktest::Vec3 c = shocktest::TriangleCentroid(whole, t);
    const double angle = std::atan2(c[1], c[0]) + 3.14159265358979;
    owner.push_back(std::min(pieces - 1, static_cast<int>(angle / (2 * 3.14159265358979) * pieces)));
  }
  // The pieces' points that others read known (as the filter's exchange knows them) or not, on 1 and 2 threads a piece.
  for (const auto& [solver, sharedKnown, threadsPerPiece] :
    { std::make_tuple(FitSolver::ConjugateGradient, true, 1), std::make_tuple(FitSolver::ConjugateGradient, false, 1),
      std::make_tuple(FitSolver::ConjugateGradient, true, 2),
      std::make_tuple(FitSolver::ConjugateGradientTolerance, true, 1),
      std::make_tuple(FitSolver::ConjugateGradientTolerance, false, 2) })
  {
    FitParameters parameters;
    parameters.solver = solver;
    parameters.tolerance = 1e-12;
    parameters.numberOfThreads = threadsPerPiece;
    std::vector<double> serial(whole.points.size());
    ASSERT_TRUE(FitPositionsToNormals(Build(whole), Targets(whole).data(), serial.data(), parameters).Ok());

    Barrier barrier(pieces);
    std::vector<std::vector<double>> sums(pieces);
    std::vector<double> shared(whole.points.size());
    std::vector<std::vector<double>> results(pieces);
    std::vector<Piece> cut;
    for (int p = 0; p < pieces; ++p)
    {
      cut.push_back(Cut(whole, owner, p));
    }
    if (sharedKnown)
    {
      MarkSharedPoints(cut);
    }
    std::vector<std::thread> threads;
    for (int p = 0; p < pieces; ++p)
    {
      threads.emplace_back([&, p] {
        Piece& piece = cut[p];
        piece.partition.globalSum = [&, p](double* values, int count) {
          sums[p].assign(values, values + count);
          barrier.Wait();
          for (int k = 0; k < count; ++k)
          {
            values[k] = 0.0;
            for (int q = 0; q < pieces; ++q)
            {
              values[k] += sums[q][k]; // the same order on every piece
            }
          }
          barrier.Wait();
        };
        piece.partition.exchangePoints = [&, p](double* values) {
          for (size_t i = 0; i < piece.global.size(); ++i)
          {
            if (piece.partition.ownedPoints[i])
            {
              std::copy(values + 3 * i, values + 3 * i + 3, &shared[3 * piece.global[i]]);
            }
          }
          barrier.Wait();
          for (size_t i = 0; i < piece.global.size(); ++i)
          {
            if (!piece.partition.ownedPoints[i])
            {
              std::copy(&shared[3 * piece.global[i]], &shared[3 * piece.global[i]] + 3, values + 3 * i);
            }
          }
          barrier.Wait();
        };
        FitParameters distributed = parameters;
        distributed.partition = &piece.partition;
        results[p].resize(piece.mesh.points.size());
        EXPECT_TRUE(FitPositionsToNormals(Build(piece.mesh), Targets(piece.mesh).data(),
          results[p].data(), distributed).Ok());
      });
    }
    for (std::thread& thread : threads)
    {
      thread.join();
    }
    double moved = 0.0, largest = 0.0;
    int owned = 0;
    for (int p = 0; p < pieces; ++p)
    {
      for (size_t i = 0; i < cut[p].global.size(); ++i)
      {
        for (int k = 0; k < 3; ++k)
        {
          const double expected = serial[3 * cut[p].global[i] + k];
          moved = std::max(moved, std::abs(expected - whole.points[3 * cut[p].global[i] + k]));
          if (cut[p].partition.ownedPoints[i] || k == 0)
          {
            largest = std::max(largest, std::abs(results[p][3 * i + k] - expected));
          }
        }
        owned += cut[p].partition.ownedPoints[i];
      }
    }
    EXPECT_EQ(owned, whole.NumberOfPoints()); // each point owned once
    EXPECT_GT(moved, 1e-3);                   // the fit moved the points
    // Fixed iterations: the serial result up to the order of the sums; converged: equal.
    EXPECT_LT(largest, solver == FitSolver::ConjugateGradient ? 1e-9 : 1e-11)
      << static_cast<int>(solver) << " shared points known " << sharedKnown << ", threads " << threadsPerPiece;
  }
}

TEST(DistributedFit, TheExactSolverRefusesPieces)
{
  const MeshData whole = shocktest::Icosphere(1);
  MeshPartition partition;
  partition.ownedPoints.assign(static_cast<size_t>(whole.NumberOfPoints()), 1);
  partition.ownedTriangles.assign(static_cast<size_t>(whole.NumberOfTriangles()), 1);
  partition.globalSum = [](double*, int) {};
  partition.exchangePoints = [](double*) {};
  FitParameters parameters;
  parameters.solver = FitSolver::Exact;
  parameters.partition = &partition;
  std::vector<double> positions(whole.points.size());
  const Status status = FitPositionsToNormals(Build(whole), Targets(whole).data(), positions.data(), parameters);
  EXPECT_FALSE(status.Ok());
  EXPECT_NE(status.error.find("exact solver"), std::string::npos) << status.error;
}
