#include "ShockMeshFaces.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkPointData.h"

#include <algorithm>

namespace shockio
{

/**
 * The colours among point or cell data: the active scalars, else the array
 * `name`, if it is an unsigned-char array of 3 or 4 components with `count`
 * tuples; else null.
 */
vtkUnsignedCharArray* FindColors(vtkDataSetAttributes* data, const char* name, vtkIdType count)
{
  for (vtkDataArray* array : { data->GetScalars(), data->GetArray(name) })
  {
    auto* colors = vtkUnsignedCharArray::SafeDownCast(array);
    if (colors && (colors->GetNumberOfComponents() == 3 || colors->GetNumberOfComponents() == 4) &&
      colors->GetNumberOfTuples() == count)
    {
      return colors;
    }
  }
  return nullptr;
}

/**
 * The polygons of `mesh` followed by the triangles of its strips, with the
 * matching cell data (a strip's data goes to each of its triangles), and its
 * points and point data; vertex and line cells are dropped. `mesh` itself when
 * it has polygons only.
 */
vtkSmartPointer<vtkPolyData> FacesOnly(vtkPolyData* mesh)
{
  if (mesh->GetNumberOfVerts() == 0 && mesh->GetNumberOfLines() == 0 &&
    mesh->GetNumberOfStrips() == 0)
  {
    return mesh;
  }
  auto faces = vtkSmartPointer<vtkPolyData>::New();
  faces->SetPoints(mesh->GetPoints());
  faces->GetPointData()->PassData(mesh->GetPointData());
  vtkCellData* inCells = mesh->GetCellData();
  vtkCellData* outCells = faces->GetCellData();
  outCells->CopyAllocate(inCells);
  vtkNew<vtkCellArray> polys;
  // Cell data is ordered vertices, lines, polygons, strips.
  vtkIdType cellId = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* inPolys = mesh->GetPolys();
  for (inPolys->InitTraversal(); inPolys->GetNextCell(size, ids); ++cellId)
  {
    outCells->CopyData(inCells, cellId, polys->InsertNextCell(size, ids));
  }
  vtkCellArray* strips = mesh->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(size, ids); ++cellId)
  {
    for (vtkIdType k = 0; k + 2 < size; ++k)
    {
      // The orientation alternates along a strip.
      const vtkIdType triangle[3] = { ids[k + k % 2], ids[k + 1 - k % 2], ids[k + 2] };
      outCells->CopyData(inCells, cellId, polys->InsertNextCell(3, triangle));
    }
  }
  faces->SetPolys(polys);
  return faces;
}

/// The largest number of points of a polygon of `mesh`.
vtkIdType LargestPolygon(vtkPolyData* mesh)
{
  vtkIdType largest = 0;
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    largest = std::max(largest, size);
  }
  return largest;
}

vtkIdType CountTriangles(vtkPolyData* mesh)
{
  vtkIdType triangles = 0;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
    {
      triangles += std::max<vtkIdType>(0, cells->GetCellSize(c) - 2);
    }
  }
  return triangles;
}

} // namespace shockio
