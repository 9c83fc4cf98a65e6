/**
 * @file   ShockMeshFaces.h
 * @brief  What the face formats (OFF, PLY, STL) take of a mesh: its polygons
 *         and its colours.
 */
#ifndef ShockMeshFaces_h
#define ShockMeshFaces_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

namespace shockio
{

/// Name of the per-point colour array that ReadMesh() creates and WriteMesh() looks for.
inline constexpr const char* PointColorsName = "Colors";
/// Name of the per-face colour array that ReadMesh() creates and WriteMesh() looks for.
inline constexpr const char* FaceColorsName = "FaceColors";

/**
 * The colours among point or cell data: the active scalars, else the array
 * `name`, if it is an unsigned-char array of 3 or 4 components with `count`
 * tuples; else null.
 */
vtkUnsignedCharArray* FindColors(vtkDataSetAttributes* data, const char* name, vtkIdType count);

/**
 * The polygons of `mesh` followed by the triangles of its strips, with the
 * matching cell data (a strip's data goes to each of its triangles), and its
 * points and point data; vertex and line cells are dropped. `mesh` itself when
 * it has polygons only.
 */
vtkSmartPointer<vtkPolyData> FacesOnly(vtkPolyData* mesh);

/// The largest number of points of a polygon of `mesh`.
vtkIdType LargestPolygon(vtkPolyData* mesh);

/// Number of triangles of the polygons and strips of `mesh` (n - 2 per cell of n points).
vtkIdType CountTriangles(vtkPolyData* mesh);

} // namespace shockio

#endif
