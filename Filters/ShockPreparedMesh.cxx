/**
 * @file ShockPreparedMesh.cxx
 * @brief ShockPolyDataInternals::PrepareMesh and MeshCache: a surface's
 * triangle mesh in its length unit, renumbered for locality, coincident
 * points merged, kept between executions.
 */
#include "vtkLogger.h"
#include "ShockPolyDataInternals.h"

#include "MeshOrder.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkShockAdvectionFilter.h"
#include "vtkCellArrayIterator.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "ShockFilterInternals.h"
#include "ShockParallel.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>


namespace ShockPolyDataInternals
{
namespace
{
/**
 * The bounds of float or double points whose coordinates are all finite,
 * computed in parallel (the same values as vtkPoints::GetBounds: a minimum
 * and a maximum of finite numbers). False for other arrays or when a
 * coordinate is not finite.
 */
template <typename T>
bool FiniteBounds(const T* values, vtkIdType n, int threads, double bounds[6])
{
  const int pieces = static_cast<int>(std::min<vtkIdType>(
    std::min(8, shock::ResolveThreadCount(threads)), std::max<vtkIdType>(1, n / 65536)));
  std::vector<std::array<double, 6>> partial(static_cast<size_t>(pieces));
  std::vector<char> finite(static_cast<size_t>(pieces), 1);
  shock::ParallelFor(pieces, pieces, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t i = first; i < last; ++i)
    {
      std::array<double, 6> b{ std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
      bool ok = true;
      const vtkIdType begin = n / pieces * i + std::min<vtkIdType>(i, n % pieces);
      const vtkIdType end = n / pieces * (i + 1) + std::min<vtkIdType>(i + 1, n % pieces);
      for (vtkIdType p = begin; p < end; ++p)
      {
        for (int a = 0; a < 3; ++a)
        {
          const double x = static_cast<double>(values[3 * p + a]);
          ok = ok && std::isfinite(x);
          b[2 * a] = std::min(b[2 * a], x);
          b[2 * a + 1] = std::max(b[2 * a + 1], x);
        }
      }
      partial[static_cast<size_t>(i)] = b;
      finite[static_cast<size_t>(i)] = ok ? 1 : 0;
    }
  });
  for (int i = 0; i < pieces; ++i)
  {
    if (!finite[static_cast<size_t>(i)])
    {
      return false;
    }
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = i == 0 ? partial[0][2 * a] : std::min(bounds[2 * a], partial[static_cast<size_t>(i)][2 * a]);
      bounds[2 * a + 1] =
        i == 0 ? partial[0][2 * a + 1] : std::max(bounds[2 * a + 1], partial[static_cast<size_t>(i)][2 * a + 1]);
    }
  }
  return true;
}

bool FiniteBounds(vtkDataArray* points, int threads, double bounds[6])
{
  if (!points || points->GetNumberOfComponents() != 3 || points->GetNumberOfTuples() == 0)
  {
    return false;
  }
  if (auto* f = vtkAOSDataArrayTemplate<float>::FastDownCast(points))
  {
    return FiniteBounds(f->GetPointer(0), f->GetNumberOfTuples(), threads, bounds);
  }
  if (auto* d = vtkAOSDataArrayTemplate<double>::FastDownCast(points))
  {
    return FiniteBounds(d->GetPointer(0), d->GetNumberOfTuples(), threads, bounds);
  }
  return false;
}
}

namespace
{
/**
 * The bounds of the points the polygons and strips use, when some points are
 * used by none (isolated points, vertex or line cells pass through the filters
 * and must not set the mesh's length unit: one point at 1e200 would shrink the
 * surface below what doubles resolve). False when every point is used (or none).
 */
bool UsedPointBounds(vtkPolyData* piece, double bounds[6])
{
  const vtkIdType n = piece->GetNumberOfPoints();
  std::vector<char> used(static_cast<size_t>(n), 0);
  vtkIdType count = 0;
  // Every point id of the polygons and strips, read straight from their connectivity arrays.
  const auto mark = [&](const auto* ids, vtkIdType size) {
    for (vtkIdType k = 0; k < size; ++k)
    {
      const vtkIdType id = static_cast<vtkIdType>(ids[k]);
      if (id >= 0 && id < n && !used[static_cast<size_t>(id)])
      {
        used[static_cast<size_t>(id)] = 1;
        ++count;
      }
    }
  };
  for (vtkCellArray* cells : { piece->GetPolys(), piece->GetStrips() })
  {
    if (!cells || cells->GetNumberOfConnectivityIds() == 0)
    {
      continue;
    }
    if (cells->IsStorage64Bit())
    {
      mark(cells->GetConnectivityArray64()->GetPointer(0), cells->GetNumberOfConnectivityIds());
    }
    else
    {
      mark(cells->GetConnectivityArray32()->GetPointer(0), cells->GetNumberOfConnectivityIds());
    }
  }
  if (count == 0 || count == n)
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = std::numeric_limits<double>::infinity();
    bounds[2 * a + 1] = -std::numeric_limits<double>::infinity();
  }
  double x[3];
  for (vtkIdType p = 0; p < n; ++p)
  {
    if (!used[static_cast<size_t>(p)])
    {
      continue;
    }
    piece->GetPoint(p, x);
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], x[a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], x[a]);
    }
  }
  return true;
}
}

double MeshUnit(vtkMultiProcessController* controller, vtkPolyData* piece, int threads)
{
  double side = 0.0;
  if (piece && piece->GetNumberOfPoints() > 0)
  {
    double bounds[6];
    if (!UsedPointBounds(piece, bounds) && !FiniteBounds(piece->GetPoints()->GetData(), threads, bounds))
    {
      piece->GetBounds(bounds); // VTK's rules for non-finite coordinates
    }
    for (int a = 0; a < 3; ++a)
    {
      side = std::max(side, bounds[2 * a + 1] - bounds[2 * a]);
    }
    side = std::isnan(side) ? std::numeric_limits<double>::infinity() : side;
  }
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    double largest = side;
    controller->AllReduce(&side, &largest, 1, vtkCommunicator::MAX_OP);
    side = largest;
  }
  if (!std::isfinite(side))
  {
    return 0.0;
  }
  if (side == 0.0 || (side >= std::ldexp(1.0, -64) && side <= std::ldexp(1.0, 64)))
  {
    return 1.0;
  }
  int exponent = 0;
  std::frexp(side, &exponent); // side = m 2^exponent, m in [0.5, 1)
  return std::ldexp(1.0, exponent);
}

namespace
{
/// Renumber the extracted points and triangles (ids and source cells) as `numbering` says.
void Renumber(shock::MeshNumbering numbering, int threads, PreparedMesh& out)
{
  Triangles& extracted = out.triangles;
  const auto np = static_cast<std::int64_t>(numbering.points.size());
  const auto nt = static_cast<std::int64_t>(numbering.triangles.size());
  const shock::IdVector& rank = numbering.rank;
  shock::ValueVector points(extracted.points.size());
  shock::ParallelFor(np, shock::ThreadsForWork(threads, np), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i)
    {
      const auto p = static_cast<size_t>(numbering.points[static_cast<size_t>(i)]);
      std::copy(&extracted.points[3 * p], &extracted.points[3 * p] + 3, &points[static_cast<size_t>(3 * i)]);
    }
  });
  shock::IdVector ids(extracted.triangles.size());
  std::vector<vtkIdType> cells(extracted.sourceCell.size());
  shock::ParallelFor(nt, shock::ThreadsForWork(threads, nt), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t f = begin; f < end; ++f)
    {
      const auto old = static_cast<size_t>(numbering.triangles[static_cast<size_t>(f)]);
      for (int c = 0; c < 3; ++c)
      {
        ids[static_cast<size_t>(3 * f + c)] = rank[static_cast<size_t>(extracted.triangles[3 * old + c])];
      }
      cells[static_cast<size_t>(f)] = extracted.sourceCell[old];
    }
  });
  extracted.points.swap(points);
  extracted.triangles.swap(ids);
  extracted.sourceCell.swap(cells);
  out.pointOrder = std::move(numbering.points);
}
}

namespace
{
/**
 * The points in Morton order, on a grid that spans the triangles' points: a
 * point no triangle uses (an isolated point far away) is clamped to its
 * border, not allowed to stretch the grid until the mesh fills one cell.
 */
shock::MeshNumbering MortonNumbering(const Triangles& triangles, int threads)
{
  const shock::ValueVector& points = triangles.points;
  const auto numberOfPoints = static_cast<std::int64_t>(points.size() / 3);
  std::vector<char> used(static_cast<size_t>(numberOfPoints), 0);
  for (const auto id : triangles.triangles)
  {
    used[static_cast<size_t>(id)] = 1;
  }
  const bool allUsed = std::all_of(used.begin(), used.end(), [](char u) { return u != 0; });
  std::array<double, 6> box{ std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  for (std::int64_t p = 0; p < numberOfPoints && !allUsed; ++p)
  {
    for (int a = 0; a < 3 && used[static_cast<size_t>(p)]; ++a)
    {
      box[2 * a] = std::min(box[2 * a], points[static_cast<size_t>(3 * p + a)]);
      box[2 * a + 1] = std::max(box[2 * a + 1], points[static_cast<size_t>(3 * p + a)]);
    }
  }
  return shock::MortonOrder(
    numberOfPoints, points.data(), threads, allUsed || triangles.triangles.empty() ? nullptr : box.data());
}

/// Coincident points (found through the Morton order) become one: the triangles use each group's representative.
void MergeCoincidentPoints(const shock::MeshNumbering& numbering, int threads, PreparedMesh& out)
{
  out.representative = shock::CoincidentPoints(numbering, out.triangles.points.data(), threads);
  shock::IdVector& ids = out.triangles.triangles;
  const auto count = static_cast<std::int64_t>(ids.size());
  shock::ParallelFor(count, shock::ThreadsForWork(threads, count), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i)
    {
      ids[static_cast<size_t>(i)] = out.representative[static_cast<size_t>(ids[static_cast<size_t>(i)])];
    }
  });
}
}

bool PrepareMesh(vtkPolyData* input, bool mergeCoincidentPoints, int threads, PreparedMesh& out,
  std::string& error, double unit, bool localityOrder)
{
  const auto start = std::chrono::steady_clock::now();
  out.representative.clear();
  out.pointOrder.clear();
  vtkLogStartScope(TRACE, "shock: mesh: triangles");
  const bool extracted = ExtractTriangles(input, out.triangles, error);
  vtkLogEndScope("shock: mesh: triangles");
  if (!extracted)
  {
    error = "Cannot read the mesh: " + error + ".";
    return false;
  }
  const shock::ValueVector& points = out.triangles.points;
  if (!std::all_of(points.begin(), points.end(), [](double v) { return std::isfinite(v); }))
  {
    error = "Cannot use the mesh: a point coordinate is not finite (NaN or infinity).";
    return false;
  }
  if (!(unit > 0.0))
  {
    error = "Cannot use the mesh: it spans more than the double range (its size is not a finite number).";
    return false;
  }
  if (unit != 1.0)
  {
    for (double& x : out.triangles.points)
    {
      x /= unit; // a power of two: exact
    }
  }
  const auto numberOfPoints = static_cast<std::int64_t>(out.triangles.points.size() / 3);
  // The Morton order serves the renumbering and the search for coincident
  // points (copies share its cells), whether or not the mesh is renumbered.
  shock::MeshNumbering numbering;
  vtkLogStartScope(TRACE, "shock: mesh: locality order");
  if (localityOrder || mergeCoincidentPoints)
  {
    numbering = MortonNumbering(out.triangles, threads);
  }
  if (mergeCoincidentPoints)
  {
    MergeCoincidentPoints(numbering, threads, out);
  }
  if (localityOrder)
  {
    shock::OrderTriangles(numbering, static_cast<std::int64_t>(out.triangles.triangles.size() / 3),
      out.triangles.triangles.data(), threads);
    Renumber(std::move(numbering), threads, out);
  }
  vtkLogEndScope("shock: mesh: locality order");
  vtkLogScopeF(TRACE, "shock: mesh: connectivity");
  // The ids are taken over by the mesh (not copied): read them back with mesh.Corners.
  const shock::Status built = out.mesh.Build(
    numberOfPoints, out.triangles.points.data(), std::move(out.triangles.triangles), threads);
  out.triangles.triangles.clear();
  if (!built.Ok())
  {
    error = "Cannot use the mesh: " + built.error + ".";
    return false;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

namespace
{
/// `values` (C per point) moved between the input's numbering and the mesh's `order` (new -> old).
std::vector<double> Renumbered(const shock::IdVector& order, std::vector<double> values,
  int components, int threads, bool toMesh, const char* caller)
{
  if (order.empty())
  {
    return values;
  }
  if (values.size() != order.size() * static_cast<size_t>(components))
  {
    throw std::invalid_argument(std::string("PreparedMesh::") + caller + ": not one tuple per point of the mesh");
  }
  std::vector<double> moved(values.size());
  const auto n = static_cast<std::int64_t>(order.size());
  const size_t C = static_cast<size_t>(components);
  shock::ParallelFor(n, shock::ThreadsForWork(threads, n), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i)
    {
      const size_t mesh = static_cast<size_t>(i) * C;
      const size_t input = static_cast<size_t>(order[static_cast<size_t>(i)]) * C;
      for (size_t c = 0; c < C; ++c)
      {
        // A loop: a copy of C values (C known at run time) would call memmove.
        moved[(toMesh ? mesh : input) + c] = values[(toMesh ? input : mesh) + c];
      }
    }
  });
  return moved;
}
}

std::vector<double> PreparedMesh::ToMeshPoints(std::vector<double> values, int components, int threads) const
{
  return Renumbered(this->pointOrder, std::move(values), components, threads, true, "ToMeshPoints");
}

std::vector<double> PreparedMesh::FromMeshPoints(std::vector<double> values, int components, int threads) const
{
  return Renumbered(this->pointOrder, std::move(values), components, threads, false, "FromMeshPoints");
}

namespace
{
/// What PrepareMesh reads from `input`, as numbers (see MeshCache).
/// A hash of an array's values (its bytes, 8 at a time), or its modification time when its values are not in one block.
unsigned long long ContentHash(vtkDataArray* array)
{
  if (!array)
  {
    return 0;
  }
  if (!array->HasStandardMemoryLayout() || array->GetDataTypeSize() <= 0)
  {
    return array->GetMTime();
  }
  const auto* bytes = static_cast<const unsigned char*>(array->GetVoidPointer(0));
  const size_t size = static_cast<size_t>(array->GetNumberOfValues()) * static_cast<size_t>(array->GetDataTypeSize());
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ size;
  size_t at = 0;
  for (; at + 8 <= size; at += 8)
  {
    std::uint64_t word;
    std::memcpy(&word, bytes + at, 8);
    h = (h ^ word) * 0xBF58476D1CE4E5B9ull;
    h ^= h >> 31;
  }
  for (; at < size; ++at)
  {
    h = (h ^ bytes[at]) * 0x94D049BB133111EBull;
  }
  return h;
}

std::vector<unsigned long long> PreparationKey(vtkPolyData* input, bool mergeCoincidentPoints)
{
  using Number = unsigned long long;
  // The coordinates' and the cells' contents too: edited in place and announced
  // with input->Modified() (VTK's idiom), the arrays keep their times. (Not the
  // data set's time: it changes whenever upstream runs again, also when only
  // its point data changed, and the mesh would be prepared again for nothing.)
  std::vector<Number> key{ mergeCoincidentPoints ? 1ULL : 0ULL };
  vtkPoints* points = input->GetPoints();
  key.push_back(points ? ContentHash(points->GetData()) : 0ULL);
  for (vtkCellArray* cells : { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    key.push_back(cells ? ContentHash(cells->GetOffsetsArray()) : 0ULL);
    key.push_back(cells ? ContentHash(cells->GetConnectivityArray()) : 0ULL);
  }
  key.insert(key.end(),
    { reinterpret_cast<Number>(points), points ? Number{ points->GetMTime() } : 0ULL,
      points ? static_cast<Number>(points->GetDataType()) : 0ULL,
      static_cast<Number>(input->GetNumberOfPoints()) });
  for (vtkCellArray* cells :
    { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    key.insert(key.end(),
      { reinterpret_cast<Number>(cells), cells ? Number{ cells->GetMTime() } : 0ULL,
        cells ? static_cast<Number>(cells->GetNumberOfCells()) : 0ULL });
  }
  return key;
}
}

const PreparedMesh* MeshCache::Get(vtkPolyData* input, bool mergeCoincidentPoints, int threads,
  std::string& error, double* seconds, double unit, bool localityOrder)
{
  const auto start = std::chrono::steady_clock::now();
  std::vector<unsigned long long> key = PreparationKey(input, mergeCoincidentPoints);
  key.push_back(localityOrder ? 1ULL : 0ULL);
  unsigned long long unitBits = 0; // the unit is agreed over processes: it can change alone
  std::memcpy(&unitBits, &unit, sizeof(unit));
  key.push_back(unitBits);
  if (key != this->Key)
  {
    this->Clear();
    ++this->Preparations;
    if (!PrepareMesh(input, mergeCoincidentPoints, threads, this->Mesh, error, unit, localityOrder))
    {
      this->Clear();
      return nullptr;
    }
    this->Key = std::move(key);
  }
  if (seconds)
  {
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return &this->Mesh;
}

void MeshCache::Clear()
{
  this->Key.clear();
  this->Mesh = PreparedMesh();
}
}
