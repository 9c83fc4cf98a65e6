/**
 * @file   CliFiles.h
 * @brief  The files of shockfilter: the IO library's readers and writers
 *         (VTK::IOShock), their one-line errors thrown as CliError.
 */
#ifndef CliFiles_h
#define CliFiles_h

#include "CliOptions.h"
#include "ShockImageIO.h"
#include "ShockMeshIO.h"

#include "vtkImageData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>

namespace shockcli
{

/// --max-samples N: the most samples (pixels, voxels; mesh points, cells) an input may declare.
OptionSpec MaxSamplesOptionSpec(std::uint64_t& target);

/// The image format of `path` by its extension; throws if unsupported.
const shockio::ImageFormat& ImageFormatOfPath(const std::string& path);
/// The mesh format of `path` by its extension; throws if unsupported.
const shockio::MeshFormat& MeshFormatOfPath(const std::string& path);
/// Throws unless `path` could be written (its directory exists, it is no directory).
void RequireWritable(const std::string& path);

/// Reads an image or volume of at most `maxSamples` samples; throws the IO library's message.
vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& path, std::uint64_t maxSamples);
/// Writes an image (raster formats: the point array `arrayName`); throws on failure, prints conversions.
void WriteImageFile(vtkImageData* image, const std::string& path, const std::string& arrayName);

/// Reads a mesh file of at most `maxSamples` points and cells; throws the IO library's message.
vtkSmartPointer<vtkPolyData> ReadMeshFile(const std::string& path, std::uint64_t maxSamples);
/// Writes a mesh file; throws the IO library's message.
void WriteMeshFile(vtkPolyData* mesh, const std::string& path);

using shockio::CountTriangles;

/// ".ply, .off, .vtp or .vtk": the extensions of the formats keeping at least `arrays`.
std::string MeshExtensionsKeeping(shockio::MeshArrays arrays);

/// The help lines on mesh file formats.
std::string MeshFormatsHelp();

} // namespace shockcli

#endif
