/**
 * @file   ShockMeshIO.h
 * @brief  Reading and writing surface meshes, in the format the file name's
 *         extension names (any letter case).
 *
 *  - `.ply`  Stanford PLY (vtkPLYReader, vtkPLYWriter; written binary little-endian);
 *  - `.obj`  Wavefront OBJ (vtkOBJReader, vtkOBJWriter);
 *  - `.stl`  STL (vtkSTLReader, vtkSTLWriter; written binary; triangles only, so
 *            polygons and strips are triangulated on writing, by vtkTriangleFilter);
 *  - `.vtp`  VTK XML polydata (vtkXMLPolyDataReader, vtkXMLPolyDataWriter);
 *  - `.vtk`  VTK legacy polydata (written binary); a legacy unstructured grid is
 *            read as its surface (vtkGeometryFilter);
 *  - `.off`  Object File Format, OFF and COFF (ShockOffFormat.h).
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
 * wrong>" (a MessageTrap catches VTK's messages; the warnings of a successful
 * call go on to VTK's output window afterwards). Not for use from several
 * threads at once (VTK's output window is global).
 *
 * Malformed files give errors rather than crashes: the VTK readers of PLY, STL
 * and OBJ files get checked files only (ShockMeshChecks.h), and every mesh read
 * is checked for cells of missing points and short data arrays. VTK's XML and
 * legacy readers still trust the binary data of their files: corrupt
 * compressed or binary payloads in .vtp and .vtk files can crash them.
 * Outputs are written to a temporary file renamed over the target when
 * complete (OutputFile): a failed write leaves an existing file untouched.
 *
 * Memory: a mesh read takes about 24 bytes per point (double coordinates) and
 * 8 bytes per triangle corner plus 8 per cell (vtkCellArray offsets), plus its
 * arrays (1 byte per colour component); the readers hold the file's text
 * besides while they parse it.
 */
#ifndef ShockMeshIO_h
#define ShockMeshIO_h

#include "ShockIOFiles.h"    // DefaultMaxSamples
#include "ShockMeshFaces.h" // PointColorsName, FaceColorsName

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace shockio
{

/// What a mesh format keeps of a mesh's arrays.
enum class MeshArrays
{
  None,    ///< geometry only (and for PLY normals, texture coordinates)
  Colours, ///< unsigned char RGB(A) point and cell colours
  All      ///< every array
};

/// A mesh file format.
struct MeshFormat
{
  enum Id
  {
    PLY,
    OFF,
    OBJ,
    STL,
    VTP,
    VTK
  } id;
  const char* name;
  std::vector<std::string> extensions; ///< lower case, without the dot
  MeshArrays arrays;
};

/// The mesh formats, in the order of the file comment.
const std::vector<MeshFormat>& MeshFormats();

/// The format of `path` by its extension; null with `error` set if there is none.
const MeshFormat* MeshFormatOf(const std::string& path, std::string& error);

/**
 * Reads the surface mesh in `path`, in the format its extension names.
 *
 * @param path   the file to read
 * @param error  cleared, then set to a one-line message naming the file on failure
 * @return the mesh (with at least one point), or nullptr on failure: unknown
 *   extension, missing, unreadable or empty file, an error of a reader or of
 *   the checks, more than `maxSamples` points or cells declared (the default
 *   is DefaultMaxSamples of ShockIOFiles.h), or no points read.
 */
vtkSmartPointer<vtkPolyData> ReadMesh(
  const std::string& path, std::string& error, std::uint64_t maxSamples = DefaultMaxSamples);

/**
 * Writes `mesh` to `path` in the format its extension names (see the file
 * comment for what each format keeps).
 *
 * @param mesh   the mesh to write: not null, with at least one point
 * @param path   the file to create or replace
 * @param error  cleared, then set to a one-line message naming the file on failure
 * @return true on success; false on an unknown extension, an empty mesh, a
 *   mesh the format cannot hold (STL without polygons, PLY polygons of more
 *   than 255 points), or a writer error (then an existing `path` is untouched).
 */
bool WriteMesh(vtkPolyData* mesh, const std::string& path, std::string& error);

} // namespace shockio

#endif
