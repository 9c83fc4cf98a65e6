/**
 * @file   ShockMeshIO.h
 * @brief  Reading and writing surface meshes for the `shockfilter` program.
 *
 * The format follows the file name's extension, in any letter case:
 *  - `.ply`  Stanford PLY (vtkPLYReader, vtkPLYWriter; written binary little-endian);
 *  - `.obj`  Wavefront OBJ (vtkOBJReader, vtkOBJWriter);
 *  - `.stl`  STL (vtkSTLReader, vtkSTLWriter; written binary; triangles only, so
 *            polygons and strips are triangulated on writing, by vtkTriangleFilter);
 *  - `.vtp`  VTK XML polydata (vtkXMLPolyDataReader, vtkXMLPolyDataWriter);
 *  - `.vtk`  VTK legacy polydata (written binary); a legacy unstructured grid is
 *            read as its surface (vtkGeometryFilter);
 *  - `.off`  Object File Format, OFF and COFF, by this module (see ReadMesh()).
 *
 * Colours: PLY and OFF store per-vertex and per-face RGB(A) colours. On reading
 * they become unsigned-char arrays named PointColorsName (point data) and
 * FaceColorsName (cell data), each the active scalars. On writing, the point
 * colours are the active point scalars when they are an unsigned-char array of
 * 3 or 4 components, otherwise the point array PointColorsName if it is one; the
 * face colours likewise from the cell data and FaceColorsName. PLY also keeps
 * point normals and 2-D texture coordinates; .vtp and .vtk keep every array.
 *
 * The face formats (PLY, OFF, STL) hold polygons only: a mesh's vertex and line
 * cells are not written to them, and its triangle strips are written as
 * triangles (with their cells' colours).
 *
 * Errors are never printed: they come back as one line "<path>: <what is
 * wrong>". The messages of VTK's readers and writers are caught by observers
 * and, for VTK's generic messages, by taking over VTK's output window (and
 * muting vtkLogger's standard error output) while a call runs; the warnings of
 * a successful call go on to the output window afterwards. This uses VTK's
 * global output window: do not read or write meshes from several threads.
 *
 * Malformed files give errors rather than crashes: the VTK readers of PLY, STL
 * and OBJ files, which trust their input, get checked files only, and every
 * mesh read is checked for cells of missing points and short data arrays. VTK's
 * XML and legacy readers still trust the binary data of their files: corrupt
 * compressed or binary payloads in .vtp and .vtk files can crash them.
 */
#ifndef ShockMeshIO_h
#define ShockMeshIO_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>

namespace shockio
{

/// Name of the per-point colour array that ReadMesh() creates and WriteMesh() looks for.
inline constexpr const char* PointColorsName = "Colors";
/// Name of the per-face colour array that ReadMesh() creates and WriteMesh() looks for.
inline constexpr const char* FaceColorsName = "FaceColors";

/**
 * Reads the surface mesh in `path`, in the format its extension names.
 *
 * OFF files: an `OFF` or `COFF` header, alone on its line or followed by the
 * counts; then the counts "vertices faces [edges]" (the edge count is ignored);
 * one vertex per line, "x y z" followed for COFF by an RGB or RGBA colour; one
 * face per line, "n i_1 ... i_n" (n >= 3, ids from 0) optionally followed by an
 * RGB or RGBA colour. '#' starts a comment; blank lines are skipped. Colours
 * are 0..255 integers, or 0..1 reals when any colour value in the file is
 * written as a real (with '.', 'e' or 'E'). Every vertex line, and every face
 * line, must have the same number of colour values. Coordinates are doubles.
 *
 * @param path   the file to read
 * @param error  cleared, then set to a one-line message naming the file on failure
 * @return the mesh (with at least one point), or nullptr on failure: unknown
 *   extension, missing, unreadable or empty file, an error of a reader or of
 *   the checks, or no points read.
 */
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error);

/**
 * Writes `mesh` to `path` in the format its extension names (see the file
 * comment for what each format keeps). OFF files get a `COFF` header when the
 * mesh has point colours, the coordinates in the shortest text that reads back
 * exactly, colours as 0..255 integers and 0 as the edge count.
 *
 * @param mesh   the mesh to write: not null, with at least one point
 * @param path   the file to create or overwrite
 * @param error  cleared, then set to a one-line message naming the file on failure
 * @return true on success; false on an unknown extension, an empty mesh, a
 *   mesh the format cannot hold (STL without polygons, PLY polygons of more
 *   than 255 points), or a writer error.
 */
bool WriteMesh(vtkPolyData* mesh, const std::string& path, std::string& error);

} // namespace shockio

#endif
