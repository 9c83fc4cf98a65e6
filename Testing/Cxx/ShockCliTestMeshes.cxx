// Helper of the command-line tests of shockfilter (label "cli" in
// Testing/CMakeLists.txt): writes small mesh files for the program to read, and
// checks that the program's output is a sharpened version of its input.
//
//   ShockCliTestMeshes make DIR
//       writes into DIR (created if missing):
//         sphere_colors.ply, .off  sphere, blurred two-colour pattern as vertex colours "Colors"
//         sphere_faces.ply         the pattern as face colours "FaceColors"
//         sphere_cells.vtp         a blurred float cell array "Heat" and a point array "Label"
//                                  (unsigned char, 1 component, not active)
//         rounded_box.off          a cube with rounded creases, no colours
//         plain.obj                a sphere without arrays
//         broken.off               an OFF file whose face refers to a missing vertex
//         nan_point.vtp            a sphere with one NaN coordinate
//   ShockCliTestMeshes sharper BEFORE AFTER point|cell NAME
//   ShockCliTestMeshes sharper BEFORE AFTER geometry
//       exit 0 when AFTER has BEFORE's points and cells and a higher edge
//       contrast: the sum over mesh edges of the squared difference of the
//       array across the edge (point arrays: between the edge's ends; cell
//       arrays: between the two triangles; geometry: of the face normals).
//       Sharpening concentrates differences into few edges, which raises it.
#include "ShockMeshIO.h"
#include "TestMeshesVTK.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace
{
using shocktest::MeshData;
using shocktest::Vec3;

/// Blurred pattern in [0, 1] on the unit sphere: a smooth step across a tilted
/// great circle and a band around a pole, each about a tenth of the radius wide.
double Pattern(const Vec3& p)
{
  const double width = 0.1;
  const double tilted = std::tanh((0.8 * p[0] + 0.6 * p[2]) / width);
  const double band = std::tanh((0.35 - std::abs(p[1] - 0.5)) / width);
  return 0.25 * (2.0 + tilted + band);
}

/// Two colours blended by the pattern: orange on blue.
std::array<unsigned char, 3> PatternColour(const Vec3& p)
{
  const double w = Pattern(p);
  const double orange[3] = { 240, 140, 20 };
  const double blue[3] = { 30, 60, 200 };
  std::array<unsigned char, 3> rgb;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = static_cast<unsigned char>(std::lround(w * orange[c] + (1.0 - w) * blue[c]));
  }
  return rgb;
}

vtkSmartPointer<vtkUnsignedCharArray> Colours(const char* name, const std::vector<Vec3>& where)
{
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName(name);
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(static_cast<vtkIdType>(where.size()));
  for (std::size_t i = 0; i < where.size(); ++i)
  {
    const auto rgb = PatternColour(where[i]);
    colours->SetTypedTuple(static_cast<vtkIdType>(i), rgb.data());
  }
  return colours;
}

std::vector<Vec3> PointPositions(const MeshData& mesh)
{
  std::vector<Vec3> positions;
  for (std::int64_t p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    positions.push_back(shocktest::Point(mesh, p));
  }
  return positions;
}

std::vector<Vec3> TriangleCentres(const MeshData& mesh)
{
  std::vector<Vec3> centres;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    centres.push_back(shocktest::TriangleCentroid(mesh, t));
  }
  return centres;
}

bool Write(vtkPolyData* mesh, const std::filesystem::path& path)
{
  std::string error;
  if (!shockio::WriteMesh(mesh, path.string(), error))
  {
    std::cerr << "cannot write " << path << ": " << error << "\n";
    return false;
  }
  return true;
}

int Make(const std::filesystem::path& directory)
{
  std::filesystem::create_directories(directory);
  const MeshData sphere = shocktest::Icosphere(4); // 2562 points, 5120 triangles
  bool ok = true;

  vtkSmartPointer<vtkPolyData> pointColours = shocktest::ToPolyData(sphere);
  pointColours->GetPointData()->SetScalars(Colours(shockio::PointColorsName, PointPositions(sphere)));
  ok = Write(pointColours, directory / "sphere_colors.ply") && ok;
  ok = Write(pointColours, directory / "sphere_colors.off") && ok;

  vtkSmartPointer<vtkPolyData> faceColours = shocktest::ToPolyData(sphere);
  faceColours->GetCellData()->SetScalars(Colours(shockio::FaceColorsName, TriangleCentres(sphere)));
  ok = Write(faceColours, directory / "sphere_faces.ply") && ok;

  vtkSmartPointer<vtkPolyData> cellArray = shocktest::ToPolyData(sphere);
  vtkNew<vtkFloatArray> heat;
  heat->SetName("Heat");
  for (const Vec3& centre : TriangleCentres(sphere))
  {
    heat->InsertNextValue(static_cast<float>(100.0 * Pattern(centre)));
  }
  cellArray->GetCellData()->AddArray(heat);
  vtkNew<vtkUnsignedCharArray> label;
  label->SetName("Label");
  label->SetNumberOfTuples(cellArray->GetNumberOfPoints());
  label->FillValue(7);
  cellArray->GetPointData()->AddArray(label);
  ok = Write(cellArray, directory / "sphere_cells.vtp") && ok;

  ok = Write(shocktest::ToPolyData(shocktest::RoundedBox(12, 2.0, 0.5)), directory / "rounded_box.off") && ok;
  ok = Write(shocktest::ToPolyData(shocktest::Icosphere(2)), directory / "plain.obj") && ok;

  vtkSmartPointer<vtkPolyData> nanPoint = shocktest::ToPolyData(shocktest::Icosphere(2));
  nanPoint->GetPoints()->SetPoint(5, std::nan(""), 0.0, 0.0);
  ok = Write(nanPoint, directory / "nan_point.vtp") && ok;

  std::ofstream broken(directory / "broken.off");
  broken << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  ok = static_cast<bool>(broken) && ok;
  return ok ? 0 : 1;
}

/// Sum over the mesh's edges of the squared difference of a per-point or per-triangle signal.
double EdgeContrast(const MeshData& mesh, const std::vector<double>& values, int components, bool perTriangle)
{
  const auto squaredDifference = [&](std::int64_t a, std::int64_t b)
  {
    double sum = 0.0;
    for (int c = 0; c < components; ++c)
    {
      const double d = values[a * components + c] - values[b * components + c];
      sum += d * d;
    }
    return sum;
  };
  double contrast = 0.0;
  if (!perTriangle)
  {
    for (const auto& [a, b] : shocktest::UniqueEdges(mesh))
    {
      contrast += squaredDifference(a, b);
    }
    return contrast;
  }
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::int64_t>> trianglesOfEdge;
  for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = mesh.triangles[3 * t + k], b = mesh.triangles[3 * t + (k + 1) % 3];
      trianglesOfEdge[{ std::min(a, b), std::max(a, b) }].push_back(t);
    }
  }
  for (const auto& [edge, triangles] : trianglesOfEdge)
  {
    if (triangles.size() == 2)
    {
      contrast += squaredDifference(triangles[0], triangles[1]);
    }
  }
  return contrast;
}

/// The signal to compare, all values finite, or an empty vector (with a message) if there is none.
std::vector<double> Signal(vtkPolyData* polyData, const MeshData& mesh, const std::string& what,
  const std::string& name, int& components)
{
  std::vector<double> values;
  if (what == "geometry")
  {
    components = 3;
    for (std::int64_t t = 0; t < mesh.NumberOfTriangles(); ++t)
    {
      const Vec3 n = shocktest::TriangleNormal(mesh, t);
      values.insert(values.end(), n.begin(), n.end());
    }
  }
  else
  {
    vtkDataArray* array = what == "cell" ? polyData->GetCellData()->GetArray(name.c_str())
                                         : polyData->GetPointData()->GetArray(name.c_str());
    if (!array)
    {
      std::cerr << "no " << what << " array '" << name << "'\n";
      return {};
    }
    components = array->GetNumberOfComponents();
    for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < components; ++c)
      {
        values.push_back(array->GetComponent(i, c));
      }
    }
  }
  for (const double v : values)
  {
    if (!std::isfinite(v))
    {
      std::cerr << "non-finite value\n";
      return {};
    }
  }
  return values;
}

int Sharper(const std::string& beforePath, const std::string& afterPath, const std::string& what,
  const std::string& name)
{
  std::string error;
  vtkSmartPointer<vtkPolyData> before = shockio::ReadMesh(beforePath, error);
  vtkSmartPointer<vtkPolyData> after = before ? shockio::ReadMesh(afterPath, error) : nullptr;
  if (!before || !after)
  {
    std::cerr << error << "\n";
    return 1;
  }
  const MeshData beforeMesh = shocktest::FromPolyData(before);
  const MeshData afterMesh = shocktest::FromPolyData(after);
  if (beforeMesh.triangles != afterMesh.triangles || beforeMesh.NumberOfPoints() != afterMesh.NumberOfPoints())
  {
    std::cerr << "the meshes differ in points or triangles\n";
    return 1;
  }
  int components = 0;
  const std::vector<double> beforeValues = Signal(before, beforeMesh, what, name, components);
  const std::vector<double> afterValues = Signal(after, afterMesh, what, name, components);
  if (beforeValues.empty() || afterValues.size() != beforeValues.size())
  {
    return 1;
  }
  const bool perTriangle = what != "point";
  const double contrastBefore = EdgeContrast(beforeMesh, beforeValues, components, perTriangle);
  const double contrastAfter = EdgeContrast(afterMesh, afterValues, components, perTriangle);
  std::cout << "edge contrast of " << what << (name.empty() ? "" : " '" + name + "'") << ": "
            << contrastBefore << " -> " << contrastAfter << "\n";
  // 5 %: well above rounding (8-bit colours), well below what sharpening does here.
  return contrastAfter > 1.05 * contrastBefore ? 0 : 1;
}
} // namespace

int main(int argc, char* argv[])
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 2 && args[0] == "make")
  {
    return Make(args[1]);
  }
  if (args.size() == 4 && args[0] == "sharper" && args[3] == "geometry")
  {
    return Sharper(args[1], args[2], args[3], "");
  }
  if (args.size() == 5 && args[0] == "sharper" && (args[3] == "point" || args[3] == "cell"))
  {
    return Sharper(args[1], args[2], args[3], args[4]);
  }
  std::cerr << "usage: ShockCliTestMeshes make DIR\n"
               "       ShockCliTestMeshes sharper BEFORE AFTER point|cell NAME\n"
               "       ShockCliTestMeshes sharper BEFORE AFTER geometry\n";
  return 2;
}
