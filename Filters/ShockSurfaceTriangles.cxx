/**
 * @file ShockSurfaceTriangles.cxx
 * @brief ShockPolyDataInternals::ExtractTriangles: the triangles of a surface's
 * polygons and strips, with the cells they come from.
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

namespace
{
/// True when the quad's two fan triangles (0,1,2) and (0,2,3) have the same orientation.
bool ConvexQuad(vtkPoints* points, const vtkIdType* ids)
{
  double x[4][3];
  for (int k = 0; k < 4; ++k)
  {
    points->GetPoint(ids[k], x[k]);
  }
  auto normal = [&x](int a, int b, int c, double n[3]) {
    const double u[3] = { x[b][0] - x[a][0], x[b][1] - x[a][1], x[b][2] - x[a][2] };
    const double v[3] = { x[c][0] - x[a][0], x[c][1] - x[a][1], x[c][2] - x[a][2] };
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
  };
  double n1[3], n2[3], m1[3], m2[3];
  normal(0, 1, 2, n1);
  normal(0, 2, 3, n2);
  normal(1, 2, 3, m1); // the other diagonal must agree too, or the quad is not convex
  normal(1, 3, 0, m2);
  const double d1 = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
  const double d2 = m1[0] * m2[0] + m1[1] * m2[1] + m1[2] * m2[2];
  return d1 > 0.0 && d2 > 0.0;
}

/**
 * The common case of ExtractTriangles: polygons that are all triangles, no
 * strips. The cell array's connectivity then is the triangle list: copied in
 * parallel, while checking that every cell has 3 points (offset 3 i for cell
 * i). False (nothing kept) when the case does not apply or an id is out of
 * range (the general path then reports it).
 */
template <typename IdArray>
bool CopyTriangles(IdArray* offsetArray, IdArray* ids, vtkIdType firstPolygon,
  vtkIdType numberOfPoints, shock::IdVector& triangles, std::vector<vtkIdType>& sourceCell)
{
  const auto* offsets = offsetArray->GetPointer(0);
  const auto* from = ids->GetPointer(0);
  const std::int64_t n = ids->GetNumberOfValues() / 3;
  triangles.resize(static_cast<size_t>(3 * n));
  sourceCell.resize(static_cast<size_t>(n));
  std::atomic<bool> valid{ true };
  shock::ParallelFor(n, shock::ThreadsForWork(0, n), [&](std::int64_t begin, std::int64_t end) {
    bool ok = true;
    for (std::int64_t f = begin; f < end; ++f)
    {
      ok = ok && offsets[f + 1] == 3 * (f + 1);
      for (std::int64_t k = 3 * f; k < 3 * f + 3; ++k)
      {
        triangles[static_cast<size_t>(k)] = from[k];
        ok = ok && from[k] >= 0 && from[k] < numberOfPoints;
      }
      sourceCell[static_cast<size_t>(f)] = firstPolygon + f;
    }
    if (!ok)
    {
      valid = false;
    }
  });
  return valid;
}

bool OnlyTriangles(vtkPolyData* input, shock::IdVector& triangles,
  std::vector<vtkIdType>& sourceCell)
{
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType n = polys->GetNumberOfCells();
  if (input->GetNumberOfStrips() > 0 || n == 0 || polys->GetNumberOfConnectivityIds() != 3 * n ||
    polys->GetNumberOfOffsets() != n + 1)
  {
    return false;
  }
  const vtkIdType first = input->GetNumberOfVerts() + input->GetNumberOfLines();
  const vtkIdType points = input->GetNumberOfPoints();
  return polys->IsStorage64Bit()
    ? CopyTriangles(polys->GetOffsetsArray64(), polys->GetConnectivityArray64(), first, points,
        triangles, sourceCell)
    : CopyTriangles(polys->GetOffsetsArray32(), polys->GetConnectivityArray32(), first, points,
        triangles, sourceCell);
}
}

namespace ShockPolyDataInternals
{

bool IdsInRange(const char* kind, vtkIdType cellId, vtkIdType size, const vtkIdType* ids,
  vtkIdType numberOfPoints, std::string& error)
{
  for (vtkIdType k = 0; k < size; ++k)
  {
    if (ids[k] < 0 || ids[k] >= numberOfPoints)
    {
      error = std::string(kind) + " " + std::to_string(cellId) + " refers to point " +
        std::to_string(ids[k]) + ", outside [0, " + std::to_string(numberOfPoints) + ")";
      return false;
    }
  }
  return true;
}


shock::TriangleMeshView Triangles::View() const
{
  shock::TriangleMeshView view;
  view.numberOfPoints = static_cast<std::int64_t>(this->points.size() / 3);
  view.points = this->points.data();
  view.numberOfTriangles = static_cast<std::int64_t>(this->triangles.size() / 3);
  view.triangles = this->triangles.data();
  return view;
}

namespace
{

void AddTriangle(Triangles& out, vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cell)
{
  out.triangles.insert(out.triangles.end(), { a, b, c });
  out.sourceCell.push_back(cell);
}

/// The triangles of a polygon of 4 or more corners.
void AddPolygon(vtkPoints* points, vtkIdType size, const vtkIdType* ids, vtkIdType cellId,
  vtkPolygon* polygon, vtkIdList* fan, Triangles& out)
{
  if (size == 4 && ConvexQuad(points, ids))
  {
    // One fixed diagonal for every convex quad: structured quad meshes get a
    // uniform triangulation (ear cutting would mix the diagonals).
    AddTriangle(out, ids[0], ids[1], ids[2], cellId);
    AddTriangle(out, ids[0], ids[2], ids[3], cellId);
    return;
  }
  // Ear cutting handles non-convex polygons; it returns local corner indices.
  polygon->Initialize(static_cast<int>(size), ids, points);
  fan->Reset();
  if (polygon->Triangulate(fan) && fan->GetNumberOfIds() == 3 * (size - 2))
  {
    for (vtkIdType k = 0; k < fan->GetNumberOfIds(); k += 3)
    {
      AddTriangle(out, ids[fan->GetId(k)], ids[fan->GetId(k + 1)], ids[fan->GetId(k + 2)], cellId);
    }
    return;
  }
  for (vtkIdType k = 1; k + 1 < size; ++k)
  {
    AddTriangle(out, ids[0], ids[k], ids[k + 1], cellId); // degenerate polygon: a fan keeps the points used
  }
}

/// The triangles of the strips, whose cell ids continue from `cellId`.
bool AddStrips(vtkPolyData* input, vtkIdType cellId, Triangles& out, std::string& error)
{
  auto strips = vtk::TakeSmartPointer(input->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell(), ++cellId)
  {
    vtkIdType size;
    const vtkIdType* ids;
    strips->GetCurrentCell(size, ids);
    if (!IdsInRange("strip", cellId, size, ids, input->GetNumberOfPoints(), error))
    {
      return false;
    }
    ++out.nonTriangleCells;
    for (vtkIdType k = 0; k + 2 < size; ++k)
    {
      // Every other triangle of a strip is flipped to keep one orientation.
      if (k % 2 == 0)
      {
        AddTriangle(out, ids[k], ids[k + 1], ids[k + 2], cellId);
      }
      else
      {
        AddTriangle(out, ids[k + 1], ids[k], ids[k + 2], cellId);
      }
    }
  }
  return true;
}
}

bool ExtractTriangles(vtkPolyData* input, Triangles& out, std::string& error)
{
  out = Triangles();
  vtkPoints* points = input->GetPoints();
  if (points && points->GetNumberOfPoints() > 0)
  {
    out.points.resize(static_cast<size_t>(3 * points->GetNumberOfPoints()));
    ShockFilterInternals::ToDoubles(
      points->GetData(), out.points.data(), shock::ThreadsForWork(0, points->GetNumberOfPoints()));
  }
  if (OnlyTriangles(input, out.triangles, out.sourceCell))
  {
    return true;
  }
  out.triangles.clear();
  out.sourceCell.clear();
  out.triangles.reserve(static_cast<size_t>(3 * input->GetNumberOfPolys()));
  out.sourceCell.reserve(static_cast<size_t>(input->GetNumberOfPolys()));

  vtkNew<vtkPolygon> polygon;
  vtkNew<vtkIdList> fan;
  vtkIdType cellId = input->GetNumberOfVerts() + input->GetNumberOfLines();
  auto polys = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell(), ++cellId)
  {
    vtkIdType size;
    const vtkIdType* ids;
    polys->GetCurrentCell(size, ids);
    if (!IdsInRange("cell", cellId, size, ids, input->GetNumberOfPoints(), error))
    {
      return false;
    }
    if (size < 3)
    {
      ++out.degenerateCells;
    }
    else if (size == 3)
    {
      AddTriangle(out, ids[0], ids[1], ids[2], cellId);
    }
    else
    {
      ++out.nonTriangleCells;
      AddPolygon(points, size, ids, cellId, polygon, fan, out);
    }
  }
  return AddStrips(input, cellId, out, error);
}
}
