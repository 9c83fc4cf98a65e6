#include "vtkShockPolyDataInternals.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkShockFilterInternals.h"

namespace vtkShockPolyDataInternals
{

shock::TriangleMeshView Triangles::View() const
{
  shock::TriangleMeshView view;
  view.numberOfPoints = static_cast<std::int64_t>(this->points.size() / 3);
  view.points = this->points.data();
  view.numberOfTriangles = static_cast<std::int64_t>(this->triangles.size() / 3);
  view.triangles = this->triangles.data();
  return view;
}

bool ExtractTriangles(vtkPolyData* input, Triangles& out, std::string& error)
{
  out = Triangles();
  vtkPoints* points = input->GetPoints();
  if (points && points->GetNumberOfPoints() > 0)
  {
    out.points = vtkShockFilterInternals::ToDoubles(points->GetData());
  }
  const vtkIdType numberOfPoints = input->GetNumberOfPoints();
  const vtkIdType firstPolygon = input->GetNumberOfVerts() + input->GetNumberOfLines();
  out.triangles.reserve(static_cast<size_t>(3 * input->GetNumberOfPolys()));
  out.sourceCell.reserve(static_cast<size_t>(input->GetNumberOfPolys()));
  auto add = [&out](vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cell) {
    out.triangles.insert(out.triangles.end(), { a, b, c });
    out.sourceCell.push_back(cell);
  };

  vtkNew<vtkPolygon> polygon;
  vtkNew<vtkIdList> fan;
  vtkIdType cellId = firstPolygon;
  auto polys = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell(), ++cellId)
  {
    vtkIdType size;
    const vtkIdType* ids;
    polys->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k < size; ++k)
    {
      if (ids[k] < 0 || ids[k] >= numberOfPoints)
      {
        error = "cell " + std::to_string(cellId) + " refers to point " + std::to_string(ids[k]) +
          ", outside [0, " + std::to_string(numberOfPoints) + ")";
        return false;
      }
    }
    if (size < 3)
    {
      ++out.degenerateCells;
      continue;
    }
    if (size == 3)
    {
      add(ids[0], ids[1], ids[2], cellId);
      continue;
    }
    ++out.nonTriangleCells;
    // Ear cutting handles non-convex polygons; it returns local corner indices.
    polygon->Initialize(static_cast<int>(size), ids, points);
    fan->Reset();
    if (polygon->Triangulate(fan) && fan->GetNumberOfIds() == 3 * (size - 2))
    {
      for (vtkIdType k = 0; k < fan->GetNumberOfIds(); k += 3)
      {
        add(ids[fan->GetId(k)], ids[fan->GetId(k + 1)], ids[fan->GetId(k + 2)], cellId);
      }
    }
    else
    {
      for (vtkIdType k = 1; k + 1 < size; ++k)
      {
        add(ids[0], ids[k], ids[k + 1], cellId); // degenerate polygon: a fan keeps the points used
      }
    }
  }

  auto strips = vtk::TakeSmartPointer(input->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell(), ++cellId)
  {
    vtkIdType size;
    const vtkIdType* ids;
    strips->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k < size; ++k)
    {
      if (ids[k] < 0 || ids[k] >= numberOfPoints)
      {
        error = "strip " + std::to_string(cellId) + " refers to point " + std::to_string(ids[k]) +
          ", outside [0, " + std::to_string(numberOfPoints) + ")";
        return false;
      }
    }
    ++out.nonTriangleCells;
    for (vtkIdType k = 0; k + 2 < size; ++k)
    {
      // Every other triangle of a strip is flipped to keep one orientation.
      if (k % 2 == 0)
      {
        add(ids[k], ids[k + 1], ids[k + 2], cellId);
      }
      else
      {
        add(ids[k + 1], ids[k], ids[k + 2], cellId);
      }
    }
  }
  return true;
}

}
