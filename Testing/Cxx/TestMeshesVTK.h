/**
 * @file   TestMeshesVTK.h
 * @brief  Conversions between the VTK-free test meshes (TestMeshes.h) and vtkPolyData.
 */
#ifndef TestMeshesVTK_h
#define TestMeshesVTK_h

#include "ShockShapesVTK.h"
#include "TestMeshes.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

namespace shocktest
{

using shockshapes::ToPolyData;

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
