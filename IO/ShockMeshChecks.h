/**
 * @file   ShockMeshChecks.h
 * @brief  Checks that keep VTK 9.2's mesh readers from crashing, aborting or
 *         misreading: each tells whether the reader can take a file.
 *
 * The readers of this VTK trust their input: vtkPLYReader aborts (an
 * assertion) on a truncated body or a blank line in it, crashes on a header
 * without vertex coordinates or with a list where it reads a value, misreads
 * the data when other elements precede the vertices and faces, and reads
 * non-numbers as 0; vtkSTLReader aborts allocating the triangles a bogus
 * binary header announces; vtkOBJReader crashes on texture coordinate ids out
 * of range, keeps faces of missing vertices and reads "nan" as 0. Each check
 * returns false with `error` set to "<path>: <what is wrong>".
 *
 * The same rules hold in every format: a face has at least 3 vertices, and a
 * coordinate is a finite number.
 */
#ifndef ShockMeshChecks_h
#define ShockMeshChecks_h

#include <cstdint>
#include <string>

namespace shockio
{

/**
 * Whether vtkPLYReader can read `path` safely: a header it reads right (vertex
 * element first, with x, y and z; then optionally the faces with an integer
 * vertex_indices list), and data as the header describes it: complete,
 * numeric, finite, 3 to 255 vertices per face, every vertex id in range.
 */
bool CheckPly(const std::string& path, std::string& error);

/**
 * Whether `path`, if vtkSTLReader takes it for a binary STL file, holds at
 * least the triangles its header announces (50 bytes each after 84 bytes).
 */
bool CheckStl(const std::string& path, std::string& error);

/**
 * Whether vtkOBJReader can read `path` safely. It uses the ids of the faces'
 * vertices, texture coordinates and normals (and of the lines' and points'
 * vertices) unchecked, and copies material names into a 100-byte buffer: so
 * every id ("v", "v/t", "v//n" or "v/t/n") must refer to an element, every
 * material name be shorter and every coordinate a finite number.
 */
bool CheckObj(const std::string& path, std::string& error);

/**
 * Whether the counts a legacy VTK file declares (POINTS, POLYGONS, CELLS,
 * POINT_DATA, ...) are at most `maxElements` and fit in the file (a value
 * takes at least a byte): VTK's legacy readers allocate them unchecked.
 */
bool CheckLegacyCounts(const std::string& path, std::uint64_t maxElements, std::string& error);

/**
 * Whether the counts a VTK XML file declares (NumberOfPoints, NumberOfPolys,
 * ...) are at most `maxElements` and, for uncompressed data, fit in the file:
 * VTK's XML readers allocate them unchecked (an abort).
 */
bool CheckXmlCounts(const std::string& path, std::uint64_t maxElements, std::string& error);

/**
 * Whether a VTK XML file (.vti, .vtp) holds all it declares: a single piece
 * covers the whole extent, and the raw appended data of every array lies
 * within the file (VTK reads what is missing as zeros). False with `problem`
 * (without the path) set.
 */
bool CheckXmlCompleteness(const std::string& path, std::string& problem);

} // namespace shockio

#endif
