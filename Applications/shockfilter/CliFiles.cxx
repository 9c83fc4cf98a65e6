#include "CliFiles.h"

#include "ShockIOFiles.h"
#include "ShockImageChecks.h"

#include "vtkCellArray.h"

#include <algorithm>
#include <iostream>

namespace shockcli
{

OptionSpec MaxSamplesOptionSpec(std::uint64_t& target)
{
  return { "--max-samples", "N",
    "most samples (pixels, voxels, points, cells) an input may declare" +
      DefaultText(std::to_string(shockio::DefaultMaxSamples)),
    [&target](const std::string& v)
    { target = ParseInRange<std::uint64_t>("--max-samples", v, 1, 1000000000000ull); } };
}

const shockio::ImageFormat& ImageFormatOfPath(const std::string& path)
{
  std::string error;
  const shockio::ImageFormat* format = shockio::ImageFormatOf(path, error);
  Require(format != nullptr, error);
  return *format;
}

const shockio::MeshFormat& MeshFormatOfPath(const std::string& path)
{
  std::string error;
  const shockio::MeshFormat* format = shockio::MeshFormatOf(path, error);
  Require(format != nullptr, error);
  return *format;
}

void RequireWritable(const std::string& path)
{
  std::string error;
  Require(shockio::CheckWritable(path, error), error);
}

namespace
{

/// The error of a reader, naming the option that raises the limit when it is the reason.
std::string WithLimitHint(std::string error)
{
  return error.find("more than the limit of") != std::string::npos
    ? error + " (raise it with --max-samples)"
    : error;
}

} // namespace

vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& path, std::uint64_t maxSamples)
{
  std::string error;
  vtkSmartPointer<vtkImageData> image = shockio::ReadImage(path, maxSamples, error);
  Require(image != nullptr, WithLimitHint(error));
  return image;
}

void WriteImageFile(vtkImageData* image, const std::string& path, const std::string& arrayName)
{
  std::string error, note;
  const bool written = shockio::WriteImage(image, path, arrayName, error, note);
  if (!note.empty())
  {
    std::cerr << ProgramName << ": note: " << note << '\n';
  }
  Require(written, error);
}

vtkSmartPointer<vtkPolyData> ReadMeshFile(const std::string& path, std::uint64_t maxSamples)
{
  std::string error;
  vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(path, error, maxSamples);
  Require(mesh != nullptr, error.empty() ? path + ": cannot be read" : WithLimitHint(error));
  return mesh;
}

void WriteMeshFile(vtkPolyData* mesh, const std::string& path)
{
  std::string error;
  Require(shockio::WriteMesh(mesh, path, error), error.empty() ? path + ": cannot be written" : error);
}

std::string MeshExtensionsKeeping(shockio::MeshArrays arrays)
{
  std::vector<std::string> extensions;
  for (const shockio::MeshFormat& format : shockio::MeshFormats())
  {
    if (format.arrays >= arrays)
    {
      extensions.insert(extensions.end(), format.extensions.begin(), format.extensions.end());
    }
  }
  std::string text;
  for (std::size_t i = 0; i < extensions.size(); ++i)
  {
    text += (i == 0 ? "." : (i + 1 == extensions.size() ? " or ." : ", .")) + extensions[i];
  }
  return text;
}

std::string MeshFormatsHelp()
{
  std::string extensions;
  for (const shockio::MeshFormat& format : shockio::MeshFormats())
  {
    for (const std::string& extension : format.extensions)
    {
      extensions += " " + extension;
    }
  }
  return "  Mesh formats, chosen by extension (case-insensitive), read and written:\n   " + extensions +
    " (vtk: legacy polydata, or an unstructured\n"
    "    grid read as its surface). ply and off keep vertex and face colours\n"
    "    (unsigned char RGB or RGBA), obj and stl the geometry only, vtp and vtk\n"
    "    every array.\n";
}

} // namespace shockcli
