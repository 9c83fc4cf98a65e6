/**
 * @file   TestMeshesVTK.h
 * @brief  Conversions between the VTK-free test meshes (TestMeshes.h) and vtkPolyData.
 */
#ifndef TestMeshesVTK_h
#define TestMeshesVTK_h

#include "TestMeshes.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

namespace shocktest
{

/// The mesh as polydata: double-precision points, one polygon cell per triangle, same ids and
/// order.
inline vtkSmartPointer<vtkPolyData> ToPolyData(const MeshData& mesh)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.NumberOfPoints()));
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    points->SetPoint(static_cast<vtkIdType>(p), mesh.points.data() + 3 * p);
  }
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(mesh.NumberOfTriangles()),
    static_cast<vtkIdType>(mesh.triangles.size()));
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    const vtkIdType ids[3] = { static_cast<vtkIdType>(mesh.triangles[3 * t]),
      static_cast<vtkIdType>(mesh.triangles[3 * t + 1]),
      static_cast<vtkIdType>(mesh.triangles[3 * t + 2]) };
    polys->InsertNextCell(3, ids);
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetPolys(polys);
  return polyData;
}

/**
 * The points and the polygons of `polyData` as a triangle mesh: a polygon
 * (p0, p1, ..., pn) becomes the fan (p0, pk, pk+1); vertex, line and strip cells
 * are ignored.
 */
inline MeshData FromPolyData(vtkPolyData* polyData)
{
  MeshData mesh;
  mesh.points.reserve(3 * static_cast<size_t>(polyData->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < polyData->GetNumberOfPoints(); ++p)
  {
    double x[3];
    polyData->GetPoint(p, x);
    mesh.points.insert(mesh.points.end(), x, x + 3);
  }
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = polyData->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    for (vtkIdType k = 1; k + 1 < size; ++k)
    {
      AddTriangle(mesh, ids[0], ids[k], ids[k + 1]);
    }
  }
  return mesh;
}

} // namespace shocktest

#endif
