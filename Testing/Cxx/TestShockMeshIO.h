// Formats, test meshes, comparisons and an output-window recorder shared by the
// tests of the mesh file input and output of shockfilter (ShockMeshIO.h):
// TestShockMeshIO.cxx (round trips), TestShockMeshIOOffSyntax.cxx (the OFF
// syntax) and TestShockMeshIOErrors.cxx (errors of the VTK formats, files and
// arguments). Each test file gets its own copy (an unnamed namespace).
#ifndef TestShockMeshIO_h
#define TestShockMeshIO_h

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

} // namespace

#endif
