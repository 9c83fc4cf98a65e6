// Tests of the mesh file input and output of shockfilter (ShockMeshIO.h): round
// trips through every format, colours, the OFF reader's syntax and the errors
// of malformed, missing and unsupported files (never a crash or printed text).
#include "IOTestSupport.h"
#include "ShockMeshIO.h"
#include "TestMeshesVTK.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStructuredPointsWriter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkUnstructuredGridWriter.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace
{
using shocktest::FromPolyData;
using shocktest::Icosphere;
using shocktest::TempPath;
using shocktest::TextFile;
using shocktest::ToPolyData;

const char* const Formats[] = { "ply", "obj", "stl", "vtp", "vtk", "off" };

/// The corner coordinates of every polygon, in order: compares meshes whose point ids differ.
std::vector<std::vector<std::array<double, 3>>> PolygonCorners(vtkPolyData* mesh)
{
  std::vector<std::vector<std::array<double, 3>>> polygons;
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    auto& corners = polygons.emplace_back();
    for (vtkIdType k = 0; k < size; ++k)
    {
      mesh->GetPoint(ids[k], corners.emplace_back().data());
    }
  }
  return polygons;
}

/// Expects the same polygons with the same corners, within `tolerance`.
void ExpectSamePolygons(vtkPolyData* expected, vtkPolyData* actual, double tolerance)
{
  const auto a = PolygonCorners(expected), b = PolygonCorners(actual);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
  {
    ASSERT_EQ(a[i].size(), b[i].size()) << "polygon " << i;
    for (size_t k = 0; k < a[i].size(); ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_NEAR(a[i][k][c], b[i][k][c], tolerance) << "polygon " << i << " corner " << k;
      }
    }
  }
}

/// Expects the same points in the same order, within `tolerance`.
void ExpectSamePoints(vtkPolyData* expected, vtkPolyData* actual, double tolerance)
{
  ASSERT_EQ(expected->GetNumberOfPoints(), actual->GetNumberOfPoints());
  for (vtkIdType p = 0; p < expected->GetNumberOfPoints(); ++p)
  {
    double a[3], b[3];
    expected->GetPoint(p, a);
    actual->GetPoint(p, b);
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_NEAR(a[c], b[c], tolerance) << "point " << p;
    }
  }
}

/// Writes then reads `mesh` as `path`, expecting both to succeed.
vtkSmartPointer<vtkPolyData> RoundTrip(vtkPolyData* mesh, const std::string& path)
{
  std::string error;
  EXPECT_TRUE(shockio::WriteMesh(mesh, path, error)) << error;
  EXPECT_EQ(error, "");
  vtkSmartPointer<vtkPolyData> read = shockio::ReadMesh(path, error);
  EXPECT_TRUE(read) << error;
  EXPECT_EQ(error, "");
  return read;
}

/// Points and cells of the positions stored as floats (PLY, STL) match within this.
constexpr double FloatTolerance = 1e-6;

/// A flat mesh of 2 quads, 2 triangles and a convex pentagon on 11 points, counter-clockwise.
vtkSmartPointer<vtkPolyData> MixedPolygons()
{
  vtkNew<vtkPoints> points;
  for (double y : { 0.0, 1.0 })
  {
    for (double x : { 0.0, 1.0, 2.0, 3.0, 4.0 })
    {
      points->InsertNextPoint(x, y, 0.0);
    }
  }
  points->InsertNextPoint(3.5, 1.5, 0.0);
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell({ 0, 1, 6, 5 });
  polys->InsertNextCell({ 1, 2, 7, 6 });
  polys->InsertNextCell({ 2, 3, 8 });
  polys->InsertNextCell({ 2, 8, 7 });
  polys->InsertNextCell({ 3, 4, 9, 10, 8 });
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

/// An unsigned-char colour array of `count` tuples of `components`, its values made from `seed`.
vtkSmartPointer<vtkUnsignedCharArray> Colors(
  const char* name, vtkIdType count, int components, int seed)
{
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetName(name);
  colors->SetNumberOfComponents(components);
  colors->SetNumberOfTuples(count);
  for (vtkIdType i = 0; i < count * components; ++i)
  {
    colors->SetValue(i, static_cast<unsigned char>((seed + 37 * i) % 256));
  }
  return colors;
}

/// Expects an unsigned-char array `name` in `data` equal to `expected`.
void ExpectColors(vtkDataSetAttributes* data, const char* name, vtkUnsignedCharArray* expected)
{
  auto* colors = vtkUnsignedCharArray::SafeDownCast(data->GetArray(name));
  ASSERT_NE(colors, nullptr) << name;
  ASSERT_EQ(colors->GetNumberOfComponents(), expected->GetNumberOfComponents());
  ASSERT_EQ(colors->GetNumberOfTuples(), expected->GetNumberOfTuples());
  for (vtkIdType i = 0; i < expected->GetNumberOfValues(); ++i)
  {
    ASSERT_EQ(colors->GetValue(i), expected->GetValue(i)) << "value " << i;
  }
}

/// Records what VTK would print, to show that nothing is.
class RecordingOutputWindow : public vtkOutputWindow
{
public:
  static RecordingOutputWindow* New();
  vtkTypeMacro(RecordingOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override { this->Text += text; }

  std::string Text;
};
vtkStandardNewMacro(RecordingOutputWindow);

/// Installs a RecordingOutputWindow for its lifetime.
class OutputWindowScope
{
public:
  OutputWindowScope()
    : Previous(vtkOutputWindow::GetInstance())
  {
    vtkOutputWindow::SetInstance(this->Window);
  }
  ~OutputWindowScope() { vtkOutputWindow::SetInstance(this->Previous); }
  const std::string& Text() const { return this->Window->Text; }

private:
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkNew<RecordingOutputWindow> Window;
};

/// Expects ReadMesh(path) to fail with a one-line error naming the file and containing `expected`.
void ExpectReadError(const std::string& path, const std::string& expected)
{
  std::string error;
  EXPECT_EQ(shockio::ReadMesh(path, error), nullptr) << path;
  EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
  EXPECT_NE(error.find(expected), std::string::npos)
    << "error: " << error << "\nexpected: " << expected;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

// --- Round trips -------------------------------------------------------------------

TEST(ShockMeshIO, TrianglesRoundTripThroughEveryFormat)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(2, 1.5));
  for (const char* format : Formats)
  {
    SCOPED_TRACE(format);
    const std::string extension = format;
    const vtkSmartPointer<vtkPolyData> read = RoundTrip(sphere, TempPath("sphere." + extension));
    ASSERT_TRUE(read);
    const bool floats = extension == "ply" || extension == "stl";
    ExpectSamePolygons(sphere, read, floats ? FloatTolerance : 0.0);
    EXPECT_EQ(
      read->GetNumberOfPoints(), sphere->GetNumberOfPoints()); // STL's points are merged again
    if (extension != "stl")
    {
      ExpectSamePoints(sphere, read, floats ? FloatTolerance : 0.0);
    }
  }
}

TEST(ShockMeshIO, ExtensionsAreCaseInsensitive)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(1));
  for (const char* name : { "a.PLY", "b.Obj", "c.STL", "d.VTP", "e.Vtk", "f.OFF" })
  {
    const vtkSmartPointer<vtkPolyData> read = RoundTrip(sphere, TempPath(name));
    ASSERT_TRUE(read) << name;
    ExpectSamePolygons(sphere, read, FloatTolerance);
  }
}

TEST(ShockMeshIO, PolygonsKeepTheirSizeWhereTheFormatAllows)
{
  const vtkSmartPointer<vtkPolyData> mesh = MixedPolygons();
  const double area = shocktest::SurfaceArea(FromPolyData(mesh));
  for (const char* format : Formats)
  {
    SCOPED_TRACE(format);
    const std::string extension = format;
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("mixed.") + format));
    ASSERT_TRUE(read);
    if (extension == "stl")
    {
      // STL holds triangles: 2 per quad, 3 for the pentagon, same area.
      EXPECT_EQ(read->GetNumberOfPolys(), 2 * 2 + 2 + 3);
      EXPECT_NEAR(shocktest::SurfaceArea(FromPolyData(read)), area, 1e-12);
    }
    else
    {
      ExpectSamePolygons(mesh, read, FloatTolerance);
    }
  }
}

TEST(ShockMeshIO, PointColorsRoundTripThroughPlyOffAndVtp)
{
  for (int components : { 3, 4 })
  {
    const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
    const auto colors = Colors(shockio::PointColorsName, mesh->GetNumberOfPoints(), components, 5);
    mesh->GetPointData()->AddArray(colors); // found by name: not the active scalars
    for (const char* format : { "ply", "off", "vtp" })
    {
      SCOPED_TRACE(std::string(format) + " " + std::to_string(components));
      const vtkSmartPointer<vtkPolyData> read =
        RoundTrip(mesh, TempPath(std::to_string(components) + "." + format));
      ASSERT_TRUE(read);
      ExpectColors(read->GetPointData(), shockio::PointColorsName, colors);
    }
  }
}

TEST(ShockMeshIO, ReadColorsAreTheActiveScalars)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  mesh->GetPointData()->AddArray(Colors(shockio::PointColorsName, mesh->GetNumberOfPoints(), 3, 1));
  for (const char* format : { "ply", "off" })
  {
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("colors.") + format));
    ASSERT_TRUE(read);
    ASSERT_NE(read->GetPointData()->GetScalars(), nullptr) << format;
    EXPECT_STREQ(read->GetPointData()->GetScalars()->GetName(), shockio::PointColorsName);
  }
}

TEST(ShockMeshIO, ActiveColorScalarsAreWrittenUnderAnyName)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  const auto colors = Colors("paint", mesh->GetNumberOfPoints(), 3, 9);
  mesh->GetPointData()->SetScalars(colors);
  for (const char* format : { "ply", "off" })
  {
    SCOPED_TRACE(format);
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("paint.") + format));
    ASSERT_TRUE(read);
    ExpectColors(read->GetPointData(), shockio::PointColorsName, colors);
  }
  // The caller's arrays keep their names.
  EXPECT_STREQ(mesh->GetPointData()->GetScalars()->GetName(), "paint");
}

TEST(ShockMeshIO, NonColorArraysAreNotColors)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  vtkNew<vtkFloatArray> scalars; // not unsigned char
  scalars->SetName(shockio::PointColorsName);
  scalars->SetNumberOfComponents(3);
  scalars->SetNumberOfTuples(mesh->GetNumberOfPoints());
  scalars->Fill(0.5);
  mesh->GetPointData()->SetScalars(scalars);
  const std::string path = TempPath("plain.off");
  std::string error;
  ASSERT_TRUE(shockio::WriteMesh(mesh, path, error)) << error;
  std::ifstream file(path);
  std::string header;
  file >> header;
  EXPECT_EQ(header, "OFF");
  const vtkSmartPointer<vtkPolyData> read = shockio::ReadMesh(path, error);
  ASSERT_TRUE(read) << error;
  EXPECT_EQ(read->GetPointData()->GetNumberOfArrays(), 0);
}

TEST(ShockMeshIO, FaceColorsRoundTripThroughPlyAndOff)
{
  for (int components : { 3, 4 })
  {
    const vtkSmartPointer<vtkPolyData> mesh = MixedPolygons();
    const auto colors = Colors(shockio::FaceColorsName, mesh->GetNumberOfPolys(), components, 77);
    mesh->GetCellData()->AddArray(colors);
    for (const char* format : { "ply", "off" })
    {
      SCOPED_TRACE(std::string(format) + " " + std::to_string(components));
      const vtkSmartPointer<vtkPolyData> read =
        RoundTrip(mesh, TempPath(std::to_string(components) + "." + format));
      ASSERT_TRUE(read);
      ExpectColors(read->GetCellData(), shockio::FaceColorsName, colors);
    }
  }
}

TEST(ShockMeshIO, PlyKeepsNormals)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  vtkNew<vtkDoubleArray> normals; // the PLY writer takes floats only: converted
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    normals->InsertNextTuple(mesh->GetPoint(p));
  }
  mesh->GetPointData()->SetNormals(normals);
  const vtkSmartPointer<vtkPolyData> read = RoundTrip(mesh, TempPath("normals.ply"));
  ASSERT_TRUE(read);
  vtkDataArray* readNormals = read->GetPointData()->GetNormals();
  ASSERT_NE(readNormals, nullptr);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(readNormals->GetComponent(p, c), normals->GetComponent(p, c), FloatTolerance);
    }
  }
}

TEST(ShockMeshIO, VtkFormatsKeepEveryArray)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  vtkNew<vtkDoubleArray> height;
  height->SetName("height");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    height->InsertNextValue(mesh->GetPoint(p)[2]);
  }
  mesh->GetPointData()->AddArray(height);
  mesh->GetCellData()->AddArray(Colors("labels", mesh->GetNumberOfPolys(), 1, 3));
  for (const char* format : { "vtp", "vtk" })
  {
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("arrays.") + format));
    ASSERT_TRUE(read);
    vtkDataArray* readHeight = read->GetPointData()->GetArray("height");
    ASSERT_NE(readHeight, nullptr) << format;
    EXPECT_EQ(readHeight->GetTuple1(7), height->GetValue(7));
    EXPECT_NE(read->GetCellData()->GetArray("labels"), nullptr) << format;
  }
}

TEST(ShockMeshIO, FaceFormatsWriteStripsAsTrianglesAndDropOtherCells)
{
  // A vertex cell, a line, a triangle and a 5-point strip (3 triangles), each with a face colour.
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 6; ++k)
  {
    points->InsertNextPoint(k / 2, k % 2, 0.0);
  }
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  verts->InsertNextCell({ 0 });
  lines->InsertNextCell({ 0, 5 });
  polys->InsertNextCell({ 0, 2, 1 });
  strips->InsertNextCell({ 1, 2, 3, 4, 5 });
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  mesh->SetPolys(polys);
  mesh->SetStrips(strips);
  const auto colors = Colors(shockio::FaceColorsName, 4, 3, 0); // vertex, line, triangle, strip
  mesh->GetCellData()->AddArray(colors);
  for (const char* format : { "ply", "off", "stl" })
  {
    SCOPED_TRACE(format);
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("strip.") + format));
    ASSERT_TRUE(read);
    EXPECT_EQ(read->GetNumberOfVerts() + read->GetNumberOfLines() + read->GetNumberOfStrips(), 0);
    ASSERT_EQ(read->GetNumberOfPolys(), 4);
    // The strip's triangles alternate in orientation to face the same way.
    const shocktest::MeshData triangles = FromPolyData(read);
    for (std::int64_t t = 0; t < 4; ++t)
    {
      EXPECT_GT(shocktest::TriangleNormal(triangles, t)[2], 0.0) << "triangle " << t;
    }
    if (std::string(format) != "stl")
    {
      auto* readColors =
        vtkUnsignedCharArray::SafeDownCast(read->GetCellData()->GetArray(shockio::FaceColorsName));
      ASSERT_NE(readColors, nullptr);
      for (vtkIdType t = 0; t < 4; ++t)
      {
        EXPECT_EQ(readColors->GetValue(3 * t), colors->GetValue(3 * (t == 0 ? 2 : 3)))
          << "triangle " << t;
      }
    }
  }
}

TEST(ShockMeshIO, OffCoordinatesRoundTripExactly)
{
  auto mesh = ToPolyData(shocktest::Noisy(Icosphere(2), 1e-3, 11));
  mesh->GetPoints()->SetPoint(0, 0.1, -1e-300, 12345678.901234567);
  const vtkSmartPointer<vtkPolyData> read = RoundTrip(mesh, TempPath("exact.off"));
  ASSERT_TRUE(read);
  ExpectSamePoints(mesh, read, 0.0);
}

// --- The OFF syntax -------------------------------------------------------------------

TEST(ShockMeshIO, OffReadsCommentsBlankLinesAndPolygonsOfAnySize)
{
  const std::string path = TextFile("syntax.off",
    "# a comment before the header\n"
    "\n"
    "OFF 5 3 0   # counts on the header line\r\n"
    "0 0 0\n"
    "\t1 0 0\n"
    "# a comment between the vertices\n"
    "1 1 0\n"
    "0 1 0\n"
    "+0.5 1.5e0 -0\n"
    "\n"
    "4 0 1 2 3\n"
    "3 3 2 4 # a comment after a face\n"
    "5  0 1 2 4 3\n");
  std::string error;
  const vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(path, error);
  ASSERT_TRUE(mesh) << error;
  EXPECT_EQ(mesh->GetNumberOfPoints(), 5);
  EXPECT_EQ(mesh->GetPoint(4)[1], 1.5);
  const auto polygons = PolygonCorners(mesh);
  ASSERT_EQ(polygons.size(), 3u);
  EXPECT_EQ(polygons[0].size(), 4u);
  EXPECT_EQ(polygons[1].size(), 3u);
  EXPECT_EQ(polygons[2].size(), 5u);
  EXPECT_EQ(
    mesh->GetPointData()->GetNumberOfArrays() + mesh->GetCellData()->GetNumberOfArrays(), 0);
}

TEST(ShockMeshIO, OffReadsCountsOnTheirOwnLineWithoutEdgeCount)
{
  const std::string path =
    TextFile("counts.off", "OFF\n# comment\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  std::string error;
  const vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(path, error);
  ASSERT_TRUE(mesh) << error;
  EXPECT_EQ(mesh->GetNumberOfPolys(), 1);
}

TEST(ShockMeshIO, CoffReadsIntegerAndRealColors)
{
  const std::string integers = TextFile("integers.off",
    "COFF\n3 1 3\n0 0 0 255 0 0\n1 0 0 0 128 0\n0 1 0 0 0 1\n3 0 1 2 10 20 30 40\n");
  const std::string reals = TextFile("reals.off",
    "COFF\n3 1 3\n0 0 0 1.0 0 0 1\n1 0 0 0 0.5 0 1\n0 1 0 0 0 1 0.0\n3 0 1 2 1 0.2e0 0\n");
  std::string error;
  const vtkSmartPointer<vtkPolyData> a = shockio::ReadMesh(integers, error);
  ASSERT_TRUE(a) << error;
  const auto* pointColors = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  ASSERT_NE(pointColors, nullptr);
  EXPECT_EQ(pointColors->GetNumberOfComponents(), 3);
  EXPECT_EQ(pointColors->GetValue(0), 255);
  EXPECT_EQ(pointColors->GetValue(4), 128);
  EXPECT_EQ(pointColors->GetValue(8), 1); // integers are 0..255 values
  const auto* faceColors =
    vtkUnsignedCharArray::SafeDownCast(a->GetCellData()->GetArray(shockio::FaceColorsName));
  ASSERT_NE(faceColors, nullptr);
  EXPECT_EQ(faceColors->GetNumberOfComponents(), 4);
  EXPECT_EQ(faceColors->GetValue(3), 40);

  // One real makes every colour value of the file a 0..1 real.
  const vtkSmartPointer<vtkPolyData> b = shockio::ReadMesh(reals, error);
  ASSERT_TRUE(b) << error;
  const auto* realColors =
    vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetArray(shockio::PointColorsName));
  ASSERT_NE(realColors, nullptr);
  EXPECT_EQ(realColors->GetNumberOfComponents(), 4);
  EXPECT_EQ(realColors->GetValue(0), 255);
  EXPECT_EQ(realColors->GetValue(5), 128); // 0.5 * 255 rounded
  EXPECT_EQ(realColors->GetValue(10), 255);
  EXPECT_EQ(realColors->GetValue(11), 0);
  const auto* realFaces =
    vtkUnsignedCharArray::SafeDownCast(b->GetCellData()->GetArray(shockio::FaceColorsName));
  ASSERT_NE(realFaces, nullptr);
  EXPECT_EQ(realFaces->GetValue(0), 255);
  EXPECT_EQ(realFaces->GetValue(1), 51);
}

TEST(ShockMeshIO, MalformedOffFilesGiveErrors)
{
  const std::string triangle = "0 0 0\n1 0 0\n0 1 0\n";
  const std::pair<std::string, std::string> cases[] = {
    { "# only a comment\n\n", "no OFF header" },
    { "PLY\n3 1 0\n" + triangle + "3 0 1 2\n", "not an OFF file" },
    { "NOFF\n3 1 0\n", "unsupported OFF variant 'NOFF'" },
    { "OFF BINARY\n", "binary OFF files are not supported" },
    { "OFF\n", "the file ends before the counts" },
    { "OFF\n3\n" + triangle, "line 2: expected the counts" },
    { "OFF\n3 1 0 7\n" + triangle, "line 2: expected the counts" },
    { "OFF\n-3 1 0\n", "expected the counts" }, { "OFF\nthree 1 0\n", "expected the counts" },
    { "OFF\n4 1 0\n" + triangle, "ends after 3 of its 4 vertices" },
    { "OFF\n3 2 0\n" + triangle + "3 0 1 2\n", "ends after 1 of its 2 faces" },
    { "OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 3: vertex 0: 2 values" },
    { "OFF\n3 1 0\n0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "vertex 0: 4 values" },
    { "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n",
      "line 4: vertex 1: coordinate 'x' is not a finite number" },
    { "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "coordinate 'nan' is not a finite number" },
    { "OFF\n3 1 0\n0 0 0\n1 1e999 0\n0 1 0\n3 0 1 2\n",
      "coordinate '1e999' is not a finite number" },
    { "OFF\n3 1 0\n" + triangle + "2 0 1\n", "face 0: 2 vertices; a face has at least 3" },
    { "OFF\n3 1 0\n" + triangle + "4 0 1 2\n", "face 0: announces 4 vertex ids but lists 3" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 3\n", "vertex id '3' is not an integer in 0..2" },
    { "OFF\n3 1 0\n" + triangle + "3 0 -1 2\n", "vertex id '-1' is not an integer in 0..2" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1.0 2\n", "vertex id '1.0' is not an integer" },
    { "OFF\n3 1 0\n" + triangle + "x 0 1 2\n",
      "the vertex count 'x' is not a non-negative integer" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 5\n", "colour-map indices are not supported" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 5 5\n", "2 colour values" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 1 2 3 4 5\n", "5 colour values" },
    { "OFF\n3 2 0\n" + triangle + "3 0 1 2 1 2 3\n3 0 1 2\n",
      "face 1: 0 colour values, but the first one has 3" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 1 2 red\n", "colour value 'red' is not a number" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2\n3 0 1 2\n",
      "line 7: more data after the last of the 1 faces" },
    { "COFF\n3 1 0\n" + triangle + "3 0 1 2\n",
      "line 3: vertex 0: no colour, but the file is COFF" },
    { "COFF\n3 1 0\n0 0 0 1 2 3\n1 0 0 1 2 3 4\n0 1 0 1 2 3\n3 0 1 2\n",
      "vertex 1: 4 colour values, but the first one has 3" },
    { "COFF\n3 1 0\n0 0 0 1 2 3\n1 0 0 1 2 300\n0 1 0 1 2 3\n3 0 1 2\n",
      "line 4: colour value 300 is not an integer in 0..255" },
    { "COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1.5\n3 0 1 2\n",
      "line 5: colour value 1.5 is not in 0..1" },
    { "COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 0.5\n3 0 1 2 2 0 0\n",
      "line 6: colour value 2 is not in 0..1" },
    { "OFF\n0 0 0\n", "no points could be read" },
    { "OFF\n1000000000000 1 0\n0 0 0\n", "ends after 1 of its 1000000000000 vertices" },
    { "OFF\n3 1 0\n0 0 0\n1 " + std::string(1, '\0') + "\x01 0\n0 1 0\n3 0 1 2\n",
      "coordinate '?"
      "?' is not a finite number" }, // two unprintable bytes
  };
  OutputWindowScope output;
  int index = 0;
  for (const auto& [text, expected] : cases)
  {
    SCOPED_TRACE(text);
    ExpectReadError(TextFile("malformed" + std::to_string(index++) + ".off", text), expected);
  }
  EXPECT_EQ(output.Text(), "");
}

// --- Errors of the VTK formats ----------------------------------------------------------

TEST(ShockMeshIO, MalformedFilesOfTheVtkFormatsGiveErrorsWithoutPrinting)
{
  const std::string plyHeader = "ply\nformat ascii 1.0\n"
                                "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                "element face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n";
  const std::string plyVertices = "0 0 0\n1 0 0\n0 1 0\n";
  struct Case
  {
    const char* extension;
    std::string text;
    const char* expected;
  };
  const Case cases[] = {
    { "ply", "garbage\n", "not a PLY file" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no end_header line" },
    { "ply", "ply\nelement vertex 1\nproperty float x\nend_header\n", "no format line" },
    { "ply", "ply\nformat nonsense 1.0\nend_header\n", "line 2: unknown PLY format" },
    { "ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
      "line 3: expected 'property" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n",
      "line 4: expected 'property" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n",
      "line 3: expected 'element" },
    { "ply", "ply\nformat ascii 1.0\n\nelement vertex 1\nend_header\n",
      "line 3: a blank line in the header" },
    { "ply",
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n3 0 1 2\n",
      "has no 'vertex' element" },
    { "ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 "
      "0\n",
      "no x, y and z values" },
    { "ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\nelement extra 2\nend_header\n0 0 0\n1 0 0\n0 1 0\n\n\n",
      "the PLY element 'extra' has no properties" }, // vtkPLY crashed on it (fuzzing)
    { "ply",
      "ply\nformat ascii 1.0\nelement edge 0\nproperty int a\nelement vertex 0\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n",
      "needs the 'vertex' element first" },
    { "ply",
      "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "element face 0\nproperty list uchar float vertex_indices\nend_header\n",
      "no 'vertex_indices' list of integers" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
      "property list uchar uchar red\nend_header\n",
      "the PLY property 'red' is declared a list" },
    { "ply", plyHeader.substr(0, plyHeader.size() - 11) + "property float texcoord\nend_header\n" + plyVertices +
      "3 0 1 2 5\n",
      "the PLY property 'texcoord' is declared a single value" },
    { "ply", plyHeader + "0 0 0\n1 0 0\n", "vertex 2: the file ends before the data" },
    { "ply", plyHeader + plyVertices + "3 0 1 2", "line 13: face 0: the last line has no line break" },
    { "ply", plyHeader + "0 0 0\n1\v0 0\n0 1 0\n3 0 1 2\n", "vertex 1: '1?0' is not a finite number" },
    { "ply", plyHeader + plyVertices, "face 0: the file ends before the data" },
    { "ply", plyHeader + "0 0 0\n\n1 0 0\n0 1 0\n3 0 1 2\n",
      "line 11: vertex 1: a blank line in the data" },
    { "ply", plyHeader + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
      "line 11: vertex 1: 'zero' is not a finite number" },
    { "ply", plyHeader + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n",
      "vertex 1: fewer values than the header announces" },
    { "ply", plyHeader + "0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
      "vertex 0: more values than the header announces" },
    { "ply", plyHeader + plyVertices + "3 0 1 3\n", "line 13: face 0: vertex id 3 is not in 0..2" },
    { "ply", plyHeader + plyVertices + "3 0 1.5 2\n", "'1.5' is not an integer" },
    { "ply", plyHeader + plyVertices + "3 0 1\n", "fewer values" },
    { "stl", "solid broken\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n",
      "Parse error reading STL vertex" },
    { "stl", "not an stl file at all\n", "Expecting 'solid'" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "line 4: vertex id '9' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: vertex id '0' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "vertex id '-4' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n",
      "texture coordinate id '1' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/ 3/1\n",
      "texture coordinate id '' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n",
      "normal id '2' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 \\\n 4\n", "line 4: vertex id '4' refers to nothing" },
    { "obj", "v 0 0 0\nusemtl " + std::string(100, 'm') + "\n",
      "a material name of 100 characters or more" },
    { "obj", "just some words\n", "no points could be read" },
    { "vtp", "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"><PolyData><Piece",
      "Error parsing XML" },
    { "vtp", "this is not XML\n", "Error parsing XML" },
    { "vtk", "# vtk DataFile Version 3.0\nbroken\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0\n",
      "Error reading ascii data" }, // a generic VTK warning, caught through the output window
    { "vtk", "not a vtk file\n", "Unrecognized file type" },
    { "vtk",
      "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
      "POLYGONS 1 4\n3 0 1 5\n",
      "a cell refers to a point the file does not have" },
  };
  OutputWindowScope output;
  for (size_t i = 0; i < std::size(cases); ++i)
  {
    SCOPED_TRACE(cases[i].text);
    ExpectReadError(
      TextFile("malformed" + std::to_string(i) + "." + cases[i].extension, cases[i].text),
      cases[i].expected);
  }
  EXPECT_EQ(output.Text(), "");
}

TEST(ShockMeshIO, TruncatedAndCorruptBinaryFilesGiveErrors)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(1));
  OutputWindowScope output;
  const std::pair<const char*, const char*> formats[] = { { "ply",
                                                            "the file ends before the data" },
    { "stl", "announces 80 triangles, but the file holds 78" }, { "vtp", "Cannot read" },
    { "vtk", "Error reading binary data" } };
  for (const auto& [format, expected] : formats)
  {
    SCOPED_TRACE(format);
    const std::string path = TempPath(std::string("whole.") + format);
    std::string error;
    ASSERT_TRUE(shockio::WriteMesh(sphere, path, error)) << error;
    std::ifstream file(path, std::ios::binary);
    const std::string bytes(
      (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    // The last 100 bytes cut off.
    const std::string truncated =
      TextFile(std::string("truncated.") + format, bytes.substr(0, bytes.size() - 100));
    ExpectReadError(truncated, expected);
  }
  // A binary PLY file whose face refers to a vertex it does not have.
  {
    const std::string path = TempPath("badindex.ply");
    std::string error;
    ASSERT_TRUE(shockio::WriteMesh(sphere, path, error)) << error;
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    const std::string bytes(
      (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const size_t faces =
      bytes.find("end_header\n") + 11 + 12 * static_cast<size_t>(sphere->GetNumberOfPoints());
    const char wrong[4] = { '\xE8', '\x03', 0,
      0 }; // 1000 as a little-endian int32: the second id of face 0
    file.seekp(static_cast<std::streamoff>(faces + 1 + 4));
    file.write(wrong, sizeof(wrong));
    file.close();
    ExpectReadError(path, "face 0: vertex id 1000 is not in 0..41");
  }
  // A binary STL file announcing more triangles than it holds.
  {
    std::string bytes(84 + 50, '\0');
    bytes[80] = 2;
    ExpectReadError(TextFile("short.stl", bytes), "announces 2 triangles, but the file holds 1");
  }
  EXPECT_EQ(output.Text(), "");
}

// What VTK's mesh readers would silently change or drop is refused, naming it:
// a face vtkOBJReader skips (vertex references in another form than the faces
// before it), PLY colours that are not 8-bit (vtkPLYReader stores them as
// 8-bit: 0..1 floats would turn black, 60000 would become 96), triangle strips
// vtkPLYReader skips. The same faces in one form are read whole.
// A truncated ASCII PLY says so; a complete one whose last line lacks its line
// break is told that.
TEST(ShockMeshIO, ATruncatedPlySaysTruncated)
{
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n";
  std::string error;
  const std::string cut = TextFile("cut.ply", header + "3 0 1");
  EXPECT_FALSE(shockio::ReadMesh(cut, error));
  EXPECT_EQ(error, cut + ": line 13: face 0: the file ends inside the data (truncated?)");
  const std::string open = TextFile("open.ply", header + "3 0 1 2");
  EXPECT_FALSE(shockio::ReadMesh(open, error));
  EXPECT_EQ(error, open + ": line 13: face 0: the last line has no line break, which VTK's PLY reader needs");
}

TEST(ShockMeshIO, WhatTheReadersWouldDropOrChangeIsRefused)
{
  std::string error;
  const std::string mixed = TextFile(
    "skipped.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n");
  EXPECT_FALSE(shockio::ReadMesh(mixed, error));
  EXPECT_EQ(error, mixed + ": face 2 (counting from 1) writes its vertex references in another form (v, v/vt, "
                           "v//vn or v/vt/vn) than the faces before it, and VTK's OBJ reader drops such faces; "
                           "write every face in one form");
  const std::string oneForm = TextFile(
    "one_form.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2//1 4//1 3//1\n");
  const vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(oneForm, error);
  ASSERT_TRUE(mesh) << error;
  EXPECT_EQ(mesh->GetNumberOfPolys(), 2);

  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (const std::string type : { "float", "ushort", "double" })
  {
    const std::string path = TextFile("colours_" + type + ".ply",
      header + "property " + type + " red\nproperty " + type + " green\nproperty " + type + " blue\n" + faces +
        "0 0 0 0 0 1\n1 0 0 1 0 0\n0 1 0 0 1 0\n3 0 1 2\n");
    EXPECT_FALSE(shockio::ReadMesh(path, error)) << type;
    EXPECT_NE(error.find("the PLY colour 'red' of the vertex element is"), std::string::npos) << error;
    EXPECT_NE(error.find("store them as uchar"), std::string::npos) << error;
  }
  const std::string bytes = TextFile("colours_uchar.ply",
    header + "property uchar red\nproperty uchar green\nproperty uchar blue\n" + faces +
      "0 0 0 0 0 255\n1 0 0 255 0 0\n0 1 0 0 255 0\n3 0 1 2\n");
  EXPECT_TRUE(shockio::ReadMesh(bytes, error)) << error;

  const std::string strips = TextFile("strips.ply",
    header + "element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
             "3 0 1 2\n");
  EXPECT_FALSE(shockio::ReadMesh(strips, error));
  EXPECT_NE(error.find("'tristrips', which VTK's PLY reader skips"), std::string::npos) << error;
}

TEST(ShockMeshIO, LegacyUnstructuredGridIsReadAsItsSurface)
{
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(0, 0, 1);
  grid->SetPoints(points);
  const vtkIdType tetra[4] = { 0, 1, 2, 3 };
  grid->InsertNextCell(VTK_TETRA, 4, tetra);
  const std::string path = TempPath("tetra.vtk");
  vtkNew<vtkUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  std::string error;
  const vtkSmartPointer<vtkPolyData> surface = shockio::ReadMesh(path, error);
  ASSERT_TRUE(surface) << error;
  EXPECT_EQ(surface->GetNumberOfPolys(), 4);
  EXPECT_NEAR(shocktest::SurfaceArea(FromPolyData(surface)), 1.5 + std::sqrt(3.0) / 2, 1e-12);
}

TEST(ShockMeshIO, LegacyFilesOfOtherDatasetsGiveErrors)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 2);
  const std::string path = TempPath("image.vtk");
  vtkNew<vtkStructuredPointsWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  OutputWindowScope output;
  ExpectReadError(path, "holds neither polydata nor an unstructured grid");
  EXPECT_EQ(output.Text(), "");
}

// --- File and argument errors ------------------------------------------------------------

TEST(ShockMeshIO, UnsupportedOrMissingFilesGiveErrors)
{
  const std::string mesh = TextFile("mesh.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string renamed = TextFile("mesh.xyz", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string folder = TempPath("folder");
  std::filesystem::create_directories(folder);
  const std::string bare = folder + "/mesh";
  std::ofstream(bare) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  ExpectReadError(renamed, "unknown extension '.xyz'");
  ExpectReadError(bare, "no file extension");
  ExpectReadError(TempPath("missing.ply"), "no such file");
  ExpectReadError(TextFile("empty.stl", ""), "the file is empty");
  const std::string directory = TempPath("folder.obj");
  std::filesystem::create_directories(directory);
  ExpectReadError(directory, "is a directory");
  std::string error;
  EXPECT_TRUE(shockio::ReadMesh(mesh, error)) << error;
}

TEST(ShockMeshIO, WritingErrors)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(1));
  OutputWindowScope output;
  std::string error;
  EXPECT_FALSE(shockio::WriteMesh(sphere, TempPath("mesh.xyz"), error));
  EXPECT_NE(error.find("unknown extension '.xyz'"), std::string::npos) << error;
  EXPECT_FALSE(shockio::WriteMesh(nullptr, TempPath("null.ply"), error));
  EXPECT_NE(error.find("no points"), std::string::npos) << error;
  vtkNew<vtkPolyData> empty;
  EXPECT_FALSE(shockio::WriteMesh(empty, TempPath("empty.vtp"), error));
  EXPECT_NE(error.find("no points"), std::string::npos) << error;

  // A point cloud has no triangles for STL.
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(sphere->GetPoints());
  EXPECT_FALSE(shockio::WriteMesh(cloud, TempPath("cloud.stl"), error));
  EXPECT_NE(error.find("no polygons"), std::string::npos) << error;

  // PLY stores at most 255 corners per polygon.
  vtkNew<vtkPolyData> disk;
  vtkNew<vtkPoints> points;
  std::vector<vtkIdType> ring;
  for (int k = 0; k < 300; ++k)
  {
    ring.push_back(points->InsertNextPoint(std::cos(k / 47.0), std::sin(k / 47.0), 0.0));
  }
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell(static_cast<vtkIdType>(ring.size()), ring.data());
  disk->SetPoints(points);
  disk->SetPolys(polys);
  EXPECT_FALSE(shockio::WriteMesh(disk, TempPath("disk.ply"), error));
  EXPECT_NE(error.find("at most 255"), std::string::npos) << error;
  EXPECT_TRUE(RoundTrip(disk, TempPath("disk.off"))); // OFF has no limit

  // Every format reports a directory that does not exist.
  for (const char* format : Formats)
  {
    const std::string path = TempPath("no-such-directory") + "/mesh." + format;
    EXPECT_FALSE(shockio::WriteMesh(sphere, path, error)) << format;
    EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  EXPECT_EQ(output.Text(), "");
}

// --- The converters of the test meshes -----------------------------------------------------

TEST(TestMeshesVTK, ConvertersRoundTrip)
{
  const shocktest::MeshData sphere = Icosphere(2);
  const vtkSmartPointer<vtkPolyData> polyData = ToPolyData(sphere);
  EXPECT_EQ(polyData->GetNumberOfPoints(), sphere.NumberOfPoints());
  EXPECT_EQ(polyData->GetNumberOfPolys(), sphere.NumberOfTriangles());
  const shocktest::MeshData back = FromPolyData(polyData);
  EXPECT_EQ(back.points, sphere.points);
  EXPECT_EQ(back.triangles, sphere.triangles);
}

TEST(TestMeshesVTK, FromPolyDataFansPolygonsAndSkipsOtherCells)
{
  const vtkSmartPointer<vtkPolyData> mesh = MixedPolygons();
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell({ 0, 9 });
  mesh->SetLines(lines);
  const shocktest::MeshData triangles = FromPolyData(mesh);
  EXPECT_EQ(triangles.NumberOfPoints(), 11);
  const std::vector<std::int64_t> expected = { 0, 1, 6, 0, 6, 5, 1, 2, 7, 1, 7, 6, 2, 3, 8, 2, 8, 7,
    3, 4, 9, 3, 9, 10, 3, 10, 8 };
  EXPECT_EQ(triangles.triangles, expected);
}

} // namespace
