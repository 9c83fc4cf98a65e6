/**
 * @file   ShockOffFormat.h
 * @brief  The Object File Format (OFF and COFF, text), read and written by
 *         this library (vtkOFFReader and vtkOFFWriter are these functions as
 *         VTK algorithms).
 *
 * Reading: an `OFF` or `COFF` header, alone on its line or followed by the
 * counts; then the counts "vertices faces [edges]" (the edge count is ignored);
 * one vertex per line, "x y z" followed for COFF by an RGB or RGBA colour; one
 * face per line, "n i_1 ... i_n" (n >= 3, ids from 0) optionally followed by an
 * RGB or RGBA colour. '#' starts a comment; blank lines are skipped. Colours
 * are 0..255 integers, or 0..1 reals when any colour value in the file is
 * written as a real (with '.', 'e' or 'E'). Every vertex line, and every face
 * line, must have the same number of colour values. Coordinates are finite
 * doubles. Colours become the unsigned-char active scalars PointColorsName and
 * FaceColorsName (ShockMeshFaces.h).
 *
 * Writing: the polygons of the mesh (strips as triangles; vertices and lines
 * dropped), a `COFF` header when it has point colours, the coordinates in the
 * shortest text that reads back exactly, colours as 0..255 integers and 0 as
 * the edge count; through an OutputFile (the target is replaced only when the
 * file is complete).
 */
#ifndef ShockOffFormat_h
#define ShockOffFormat_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>

namespace shockio
{

/// Reads an OFF or COFF file; null with `error` set to "<path>: [line <n>: ]<what>" on failure.
vtkSmartPointer<vtkPolyData> ReadOff(const std::string& path, std::string& error);

/// Writes the polygons of `mesh` as an OFF (COFF) file; false with `error` set on failure.
bool WriteOff(vtkPolyData* mesh, const std::string& path, std::string& error);

} // namespace shockio

#endif
