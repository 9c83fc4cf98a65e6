#include "ShockMeshIO.h"

#include "ShockIOFiles.h"
#include "ShockIOMessages.h"
#include "ShockMeshChecks.h"
#include "ShockOffFormat.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkGeometryFilter.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkOBJWriter.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyDataReader.h"
#include "vtkPolyDataWriter.h"
#include "vtkSTLReader.h"
#include "vtkSTLWriter.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGridReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLReader.h"

#include <algorithm>
#include <new>
#include <tuple>
#include <type_traits>

namespace shockio
{

const std::vector<MeshFormat>& MeshFormats()
{
  static const std::vector<MeshFormat> formats = {
    { MeshFormat::PLY, "PLY", { "ply" }, MeshArrays::Colours },
    { MeshFormat::OFF, "OFF", { "off" }, MeshArrays::Colours },
    { MeshFormat::OBJ, "OBJ", { "obj" }, MeshArrays::None },
    { MeshFormat::STL, "STL", { "stl" }, MeshArrays::None },
    { MeshFormat::VTP, "VTK XML polydata", { "vtp" }, MeshArrays::All },
    { MeshFormat::VTK, "legacy VTK", { "vtk" }, MeshArrays::All },
  };
  return formats;
}

const MeshFormat* MeshFormatOf(const std::string& path, std::string& error)
{
  return FormatOfPath(MeshFormats(), path, "mesh", error);
}

namespace
{

/// A new mesh sharing the data of an algorithm's output but not tied to the algorithm.
vtkSmartPointer<vtkPolyData> Detached(vtkPolyData* output)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(output);
  return mesh;
}

/**
 * Whether `mesh` as a reader made it is sound: consistent cell arrays whose ids
 * refer to its points, and point and cell data arrays with a tuple for every
 * point and cell (corrupt files, such as legacy ones with wrong counts, break
 * these; vtkOBJReader leaves extra ones when it skips faces). Else sets `error`.
 */
bool CheckStructure(vtkPolyData* mesh, const std::string& path, std::string& error)
{
  const vtkIdType numberOfPoints = mesh->GetNumberOfPoints();
  for (vtkCellArray* cells :
    { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(), mesh->GetStrips() })
  {
    vtkDataArray* ids = cells->GetConnectivityArray();
    double range[2] = { 0.0, 0.0 };
    if (ids->GetNumberOfValues() > 0)
    {
      ids->GetRange(range, 0);
    }
    if (!cells->IsValid() || range[0] < 0.0 || range[1] >= static_cast<double>(numberOfPoints))
    {
      error = path + ": a cell refers to a point the file does not have";
      return false;
    }
  }
  const std::pair<vtkFieldData*, vtkIdType> attributes[] = {
    { mesh->GetPointData(), numberOfPoints }, { mesh->GetCellData(), mesh->GetNumberOfCells() }
  };
  for (const auto& [data, count] : attributes)
  {
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = data->GetAbstractArray(a);
      if (array->GetNumberOfTuples() < count)
      {
        error = path + ": the array '" + (array->GetName() ? array->GetName() : "") + "' has " +
          std::to_string(array->GetNumberOfTuples()) + " values for " + std::to_string(count) +
          (data == mesh->GetPointData() ? " points" : " cells");
        return false;
      }
    }
  }
  return true;
}

// --- VTK readers and writers ---------------------------------------------------------
// They report their problems to the MessageTrap of the ReadMesh() or WriteMesh() call.

/// Runs a VTK reader of polygonal data on `path`; its output, complete or not.
template <typename Reader>
vtkSmartPointer<vtkPolyData> ReadWith(const std::string& path, MessageTrap* trap)
{
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  trap->Watch(reader);
  if constexpr (std::is_base_of_v<vtkXMLReader, Reader>)
  {
    reader->SetParserErrorObserver(trap); // the XML parser reports its own errors
  }
  reader->Update();
  return Detached(reader->GetOutput());
}

/// Reads a PLY file, its colour arrays renamed PointColorsName and FaceColorsName.
vtkSmartPointer<vtkPolyData> ReadPly(const std::string& path, MessageTrap* trap)
{
  vtkSmartPointer<vtkPolyData> mesh = ReadWith<vtkPLYReader>(path, trap);
  // vtkPLYReader names them "RGB" or "RGBA".
  const std::pair<vtkDataSetAttributes*, const char*> renames[] = {
    { mesh->GetPointData(), PointColorsName }, { mesh->GetCellData(), FaceColorsName }
  };
  for (const auto& [data, name] : renames)
  {
    for (const char* plyName : { "RGB", "RGBA" })
    {
      if (vtkDataArray* colors = data->GetArray(plyName))
      {
        colors->SetName(name);
        data->SetActiveScalars(name);
      }
    }
  }
  return mesh;
}

/// Reads a legacy VTK file of polydata, or of an unstructured grid whose surface is taken.
vtkSmartPointer<vtkPolyData> ReadLegacy(
  const std::string& path, MessageTrap* trap, std::string& error)
{
  vtkNew<vtkPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  trap->Watch(reader);
  if (reader->IsFilePolyData())
  {
    reader->Update();
    return Detached(reader->GetOutput());
  }
  vtkNew<vtkUnstructuredGridReader> gridReader;
  gridReader->SetFileName(path.c_str());
  trap->Watch(gridReader);
  if (!gridReader->IsFileUnstructuredGrid())
  {
    // Unless the header checks reported why (not a VTK file).
    error = path + ": the legacy VTK file holds neither polydata nor an unstructured grid";
    return nullptr;
  }
  vtkNew<vtkGeometryFilter> surface;
  surface->SetInputConnection(gridReader->GetOutputPort());
  trap->Watch(surface);
  surface->Update();
  return Detached(surface->GetOutput());
}

/// Writes a binary PLY file, with the colours, normals and texture coordinates vtkPLYWriter takes.
bool WritePly(vtkPolyData* mesh, const std::string& path, MessageTrap* trap, std::string& error,
  const WrittenFileCheck& check)
{
  const vtkSmartPointer<vtkPolyData> faces = FacesOnly(mesh);
  if (const vtkIdType largest = LargestPolygon(faces); largest > 255)
  {
    error = path + ": a polygon has " + std::to_string(largest) +
      " points; PLY polygons have at most 255";
    return false;
  }
  // vtkPLYWriter takes the point and the face colours from arrays of one name
  // and reads normals and texture coordinates as floats only: it gets a copy
  // made so, which leaves the caller's arrays alone.
  const char* colorsName = "PLYColors";
  vtkNew<vtkPolyData> copy;
  copy->SetPoints(faces->GetPoints());
  copy->SetPolys(faces->GetPolys());
  const std::tuple<vtkDataSetAttributes*, vtkDataSetAttributes*, const char*, vtkIdType>
    colorSources[] = { { faces->GetPointData(), copy->GetPointData(), PointColorsName,
                         faces->GetNumberOfPoints() },
      { faces->GetCellData(), copy->GetCellData(), FaceColorsName, faces->GetNumberOfPolys() } };
  for (const auto& [from, to, name, count] : colorSources)
  {
    if (vtkUnsignedCharArray* colors = FindColors(from, name, count))
    {
      vtkNew<vtkUnsignedCharArray> renamed;
      renamed->ShallowCopy(colors);
      renamed->SetName(colorsName);
      to->AddArray(renamed);
    }
  }
  const auto asFloat = [](vtkDataArray* array) {
    auto floats = vtkSmartPointer<vtkFloatArray>::New();
    floats->DeepCopy(array);
    return floats;
  };
  vtkPointData* pointData = faces->GetPointData();
  if (vtkDataArray* normals = pointData->GetNormals();
      normals && normals->GetNumberOfComponents() == 3)
  {
    copy->GetPointData()->SetNormals(asFloat(normals));
  }
  if (vtkDataArray* tcoords = pointData->GetTCoords();
      tcoords && tcoords->GetNumberOfComponents() == 2)
  {
    copy->GetPointData()->SetTCoords(asFloat(tcoords));
  }
  vtkNew<vtkPLYWriter> writer;
  writer->SetInputData(copy);
  writer->SetFileTypeToBinary();
  writer->SetArrayName(colorsName);
  writer->SetEnableAlpha(true); // RGBA arrays keep their alpha, RGB ones stay RGB
  // (OutputFile keeps the lower-case extension: vtkPLY appends ".ply" to
  // any other file name.)
  return RunWriter(writer.GetPointer(), path, trap, error, check);
}

/// Writes a binary STL file of the triangulated polygons and strips of `mesh`.
bool WriteStl(vtkPolyData* mesh, const std::string& path, MessageTrap* trap, std::string& error,
  const WrittenFileCheck& check)
{
  if (mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
  {
    error = path + ": STL files hold triangles, and the mesh has no polygons";
    return false;
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mesh);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  trap->Watch(triangles);
  vtkNew<vtkSTLWriter> writer;
  writer->SetInputConnection(triangles->GetOutputPort());
  writer->SetFileTypeToBinary();
  return RunWriter(writer.GetPointer(), path, trap, error, check);
}

/**
 * Whether a file just written reads back as `mesh` written in `format`: as
 * many points (but STL, whose reader merges them) and triangles. VTK's PLY,
 * OBJ and TIFF writers ignore failed writes (a full disk): this finds them.
 */
WrittenFileCheck ReadsBack(const MeshFormat& format, vtkPolyData* mesh)
{
  const bool faces = format.arrays != MeshArrays::All && format.id != MeshFormat::OBJ;
  const vtkIdType points = mesh->GetNumberOfPoints();
  const vtkIdType triangles = CountTriangles(faces ? FacesOnly(mesh).Get() : mesh);
  const bool stl = format.id == MeshFormat::STL;
  return [points, triangles, stl](const std::string& written)
  {
    std::string error;
    const vtkSmartPointer<vtkPolyData> back = ReadMesh(written, error);
    return back && (stl || back->GetNumberOfPoints() == points) && CountTriangles(back) == triangles;
  };
}

/// Reads the file in `format`; null with `error` set when a check of this module fails.
vtkSmartPointer<vtkPolyData> ReadFormat(const MeshFormat& format, const std::string& path,
  std::uint64_t maxSamples, MessageTrap* trap, std::string& error)
{
  switch (format.id)
  {
    case MeshFormat::PLY:
      return CheckPly(path, error) ? ReadPly(path, trap) : nullptr;
    case MeshFormat::OBJ:
      return CheckObj(path, error) ? ReadWith<vtkOBJReader>(path, trap) : nullptr;
    case MeshFormat::STL:
      return CheckStl(path, error) ? ReadWith<vtkSTLReader>(path, trap) : nullptr;
    case MeshFormat::VTP:
    {
      std::string problem;
      if (CheckXmlCounts(path, maxSamples, error) && !CheckXmlCompleteness(path, problem))
      {
        error = path + ": " + problem;
      }
      return error.empty() ? ReadWith<vtkXMLPolyDataReader>(path, trap) : nullptr;
    }
    case MeshFormat::VTK:
      return CheckLegacyCounts(path, maxSamples, error) ? ReadLegacy(path, trap, error) : nullptr;
    case MeshFormat::OFF:
      return ReadOff(path, error);
  }
  return nullptr;
}

/// Writes the file in `format`; false with `error` set when this module finds a problem.
bool WriteFormat(const MeshFormat& format, vtkPolyData* mesh, const std::string& path,
  MessageTrap* trap, std::string& error, const WrittenFileCheck& check)
{
  switch (format.id)
  {
    case MeshFormat::PLY:
      return WritePly(mesh, path, trap, error, check);
    case MeshFormat::OBJ:
    {
      vtkNew<vtkOBJWriter> writer;
      writer->SetInputData(0, mesh);
      return RunWriter(writer.GetPointer(), path, trap, error, check);
    }
    case MeshFormat::STL:
      return WriteStl(mesh, path, trap, error, check);
    case MeshFormat::VTP:
    {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetInputData(mesh);
      return RunWriter(writer.GetPointer(), path, trap, error, check);
    }
    case MeshFormat::VTK:
    {
      vtkNew<vtkPolyDataWriter> writer;
      writer->SetInputData(mesh);
      writer->SetFileTypeToBinary();
      return RunWriter(writer.GetPointer(), path, trap, error, check);
    }
    case MeshFormat::OFF:
      return WriteOff(mesh, path, error);
  }
  return false;
}

} // namespace

vtkSmartPointer<vtkPolyData> ReadMesh(
  const std::string& path, std::string& error, std::uint64_t maxSamples)
{
  error.clear();
  const MeshFormat* format = MeshFormatOf(path, error);
  if (!format || !CheckReadable(path, error))
  {
    return nullptr;
  }
  vtkNew<MessageTrap> trap;
  vtkSmartPointer<vtkPolyData> mesh;
  try
  {
    mesh = ReadFormat(*format, path, maxSamples, trap, error);
  }
  catch (const std::bad_alloc&)
  {
    // VTK's readers allocate what corrupt counts in binary files announce.
    error = path + ": out of memory (is the file corrupt?)";
  }
  // What VTK reported explains a failure best, even one found here after it.
  // The OBJ reader only warns when it drops a face (one whose vertex references
  // take another form than the faces before it): a lost face is an error.
  const Strictness strictness =
    format->id == MeshFormat::OBJ ? Strictness::WarningsFail : Strictness::MessagesFail;
  if (!trap->Finish(path, error, strictness) || !mesh)
  {
    const size_t skipped = error.find("Skipping poly ");
    if (skipped != std::string::npos)
    {
      const std::string face = error.substr(skipped + 14, error.find(' ', skipped + 14) - skipped - 14);
      error = path + ": face " + face + " (counting from 1) writes its vertex references in another form (v, "
        "v/vt, v//vn or v/vt/vn) than the faces before it, and VTK's OBJ reader drops such faces; write every "
        "face in one form";
    }
    return nullptr;
  }
  if (mesh->GetNumberOfPoints() == 0)
  {
    error = path + ": no points could be read (is the file valid for its extension?)";
    return nullptr;
  }
  return CheckStructure(mesh, path, error) ? mesh : nullptr;
}

bool WriteMesh(vtkPolyData* mesh, const std::string& path, std::string& error)
{
  error.clear();
  const MeshFormat* format = MeshFormatOf(path, error);
  if (!format || !CheckWritable(path, error))
  {
    return false;
  }
  if (!mesh || mesh->GetNumberOfPoints() == 0)
  {
    error = path + ": the mesh has no points to write";
    return false;
  }
  vtkNew<MessageTrap> trap;
  const bool written = WriteFormat(*format, mesh, path, trap, error, ReadsBack(*format, mesh));
  return trap->Finish(path, error) && written;
}

} // namespace shockio
