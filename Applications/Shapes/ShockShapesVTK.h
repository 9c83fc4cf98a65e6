/**
 * @file   ShockShapesVTK.h
 * @brief  The shapes of ShockShapes.h as vtkPolyData.
 */
#ifndef ShockShapesVTK_h
#define ShockShapesVTK_h

#include "ShockShapes.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

namespace shockshapes
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

} // namespace shockshapes

#endif
