// Meshes, runs and measurements shared by the tests of
// vtkPolyDataShockSharpenFilter (TestPolyDataShockSharpenFilter.cxx and
// TestPolyDataShockSharpenInputs.cxx). Each test file gets its own copy (an
// unnamed namespace).
#ifndef TestPolyDataSharpen_h
#define TestPolyDataSharpen_h

#include "vtkPolyDataShockSharpenFilter.h"

#include "ShockTypes.h"
#include "TestFilterHelpers.h"
#include "TestMeshesVTK.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIntArray.h"
#include "vtkLineSource.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkPolygon.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkStripper.h"
#include "vtkTransform.h"
#include "vtkTransformFilter.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <numeric>
#include <random>
#include <vector>

namespace
{


using shock_test::MessageLog;
using shock_test::UpdateSucceeds;
using shock_test::Values;

using Filter = vtkPolyDataShockSharpenFilter;
using Configure = std::function<void(Filter*)>;
using Vector = std::array<double, 3>;

// ---------------------------------------------------------------------------
// Meshes

/// The rounded cube of side 2 (rounding radius 0.35, n x n squares per face) as polydata.
vtkSmartPointer<vtkPolyData> RoundedCube(int n = 24)
{
  return shocktest::ToPolyData(shocktest::RoundedBox(n, 2.0, 0.35));
}

/**
 * The same rounded cube made of quads: BoxSurface emits each square as the two
 * triangles (a, b, c), (a, c, d) in a row, which become the quad (a, b, c, d).
 */
vtkSmartPointer<vtkPolyData> RoundedCubeOfQuads(int n = 16)
{
  const shocktest::MeshData box = shocktest::RoundedBox(n, 2.0, 0.35);
  auto mesh = shocktest::ToPolyData(box);
  vtkNew<vtkCellArray> quads;
  for (std::int64_t t = 0; t + 1 < box.NumberOfTriangles(); t += 2)
  {
    const std::int64_t* first = &box.triangles[static_cast<size_t>(3 * t)];
    const std::int64_t* second = &box.triangles[static_cast<size_t>(3 * t + 3)];
    EXPECT_EQ(first[0], second[0]);
    EXPECT_EQ(first[2], second[1]);
    const vtkIdType ids[4] = { first[0], first[1], first[2], second[2] };
    quads->InsertNextCell(4, ids);
  }
  mesh->SetPolys(quads);
  return mesh;
}

/// A vtkSphereSource (radius 0.5) with the given resolution and double coordinates.
vtkSmartPointer<vtkPolyData> SphereSource(int resolution)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(resolution);
  source->SetPhiResolution(resolution);
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(source->GetOutput());
  return mesh;
}

vtkSmartPointer<vtkPolyData> DeepCopy(vtkPolyData* mesh)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(mesh);
  return copy;
}

// ---------------------------------------------------------------------------
// Running the filter

/// Run a filter on `input` (FlowTime `time`, then `configure`); expect success without errors.
vtkSmartPointer<vtkPolyData> Sharpen(vtkPolyData* input, double time, const Configure& configure = {},
  std::string* warnings = nullptr)
{
  vtkNew<Filter> filter;
  MessageLog log(filter);
  filter->SetInputData(input);
  filter->SetFlowTime(time);
  if (configure)
  {
    configure(filter);
  }
  EXPECT_TRUE(UpdateSucceeds(filter)) << log.Errors;
  EXPECT_TRUE(log.Errors.empty()) << log.Errors;
  if (warnings)
  {
    *warnings = log.Warnings;
  }
  return DeepCopy(filter->GetOutput());
}

void Exact(Filter* f)
{
  f->SetSolverToExact();
}

// ---------------------------------------------------------------------------
// Measurements

std::vector<double> Coordinates(vtkPolyData* mesh)
{
  return mesh->GetPoints() ? Values(mesh->GetPoints()->GetData()) : std::vector<double>();
}

bool AllFinite(const std::vector<double>& values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

/// Largest |a_i - b_i| over all coordinates (infinity when the sizes differ).
double MaxDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  if (a.size() != b.size())
  {
    return std::numeric_limits<double>::infinity();
  }
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst;
}

double Distance(vtkPolyData* a, vtkIdType p, vtkPolyData* b, vtkIdType q)
{
  double x[3], y[3];
  a->GetPoint(p, x);
  b->GetPoint(q, y);
  return std::sqrt(vtkMath::Distance2BetweenPoints(x, y));
}

double Dot(const Vector& a, const Vector& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double Length(const Vector& a)
{
  return std::sqrt(Dot(a, a));
}

double Angle(const Vector& a, const Vector& b)
{
  return std::acos(std::clamp(Dot(a, b) / (Length(a) * Length(b)), -1.0, 1.0));
}

/// The (Newell) unit normal of every polygon of `mesh`, in cell order of the polygons.
std::vector<Vector> PolygonNormals(vtkPolyData* mesh)
{
  std::vector<Vector> normals;
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    Vector n;
    vtkPolygon::ComputeNormal(mesh->GetPoints(), static_cast<int>(size), ids, n.data());
    normals.push_back(n);
  }
  return normals;
}

/// The centroid of every polygon of `mesh`.
std::vector<Vector> PolygonCentroids(vtkPolyData* mesh)
{
  std::vector<Vector> centroids;
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    Vector c{ 0.0, 0.0, 0.0 };
    for (vtkIdType k = 0; k < size; ++k)
    {
      double x[3];
      mesh->GetPoint(ids[k], x);
      for (int d = 0; d < 3; ++d)
      {
        c[d] += x[d] / static_cast<double>(size);
      }
    }
    centroids.push_back(c);
  }
  return centroids;
}

/// The true cube normal of a face of a box centred at the origin: the dominant axis of its centroid.
Vector CubeNormal(const Vector& centroid)
{
  const int axis = static_cast<int>(std::max_element(centroid.begin(), centroid.end(),
                                      [](double a, double b) { return std::abs(a) < std::abs(b); }) -
    centroid.begin());
  Vector n{ 0.0, 0.0, 0.0 };
  n[axis] = centroid[axis] > 0.0 ? 1.0 : -1.0;
  return n;
}

/// Mean angle between the polygons' normals in `mesh` and the cube normals of `reference`'s polygons.
double MeanCubeNormalError(vtkPolyData* mesh, vtkPolyData* reference)
{
  const std::vector<Vector> normals = PolygonNormals(mesh);
  const std::vector<Vector> centroids = PolygonCentroids(reference);
  EXPECT_EQ(normals.size(), centroids.size());
  double sum = 0.0;
  for (size_t f = 0; f < normals.size(); ++f)
  {
    sum += Angle(normals[f], CubeNormal(centroids[f]));
  }
  return sum / static_cast<double>(normals.size());
}

/// Mean angle between the polygons' normals and the radial direction at their centroid (sphere about c).
double MeanRadialNormalError(vtkPolyData* mesh, const Vector& c = { 0.0, 0.0, 0.0 })
{
  const std::vector<Vector> normals = PolygonNormals(mesh);
  const std::vector<Vector> centroids = PolygonCentroids(mesh);
  double sum = 0.0;
  for (size_t f = 0; f < normals.size(); ++f)
  {
    const Vector r{ centroids[f][0] - c[0], centroids[f][1] - c[1], centroids[f][2] - c[2] };
    sum += Angle(normals[f], r);
  }
  return sum / static_cast<double>(normals.size());
}

/// Same vertex, line, polygon and strip cells (connectivity and offsets).
void ExpectSameCells(vtkPolyData* a, vtkPolyData* b, const std::string& what = "")
{
  const std::array<std::pair<const char*, std::function<vtkCellArray*(vtkPolyData*)>>, 4> kinds = { {
    { "verts", [](vtkPolyData* m) { return m->GetVerts(); } },
    { "lines", [](vtkPolyData* m) { return m->GetLines(); } },
    { "polys", [](vtkPolyData* m) { return m->GetPolys(); } },
    { "strips", [](vtkPolyData* m) { return m->GetStrips(); } },
  } };
  for (const auto& [name, get] : kinds)
  {
    EXPECT_EQ(Values(get(a)->GetConnectivityArray()), Values(get(b)->GetConnectivityArray())) << what << " " << name;
    EXPECT_EQ(Values(get(a)->GetOffsetsArray()), Values(get(b)->GetOffsetsArray())) << what << " " << name;
  }
}

/// The single value of field-data array `name` (NaN when missing or not a single value).
double FieldValue(vtkPolyData* mesh, const char* name)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array && array->GetNumberOfValues() == 1 ? array->GetComponent(0, 0)
                                                  : std::numeric_limits<double>::quiet_NaN();
}

/// Largest point displacement from `before` to `after`, divided by the bounding-box diagonal of `before`.
double RelativeMaxDisplacement(vtkPolyData* before, vtkPolyData* after)
{
  double largest = 0.0;
  for (vtkIdType p = 0; p < before->GetNumberOfPoints(); ++p)
  {
    largest = std::max(largest, Distance(before, p, after, p));
  }
  return largest / before->GetLength();
}

/// Min and max distance of the points from c.
std::pair<double, double> RadiusRange(vtkPolyData* mesh, const Vector& c = { 0.0, 0.0, 0.0 })
{
  double low = std::numeric_limits<double>::infinity(), high = 0.0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    const double r = std::sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) + (x[2] - c[2]) * (x[2] - c[2]));
    low = std::min(low, r);
    high = std::max(high, r);
  }
  return { low, high };
}

} // namespace

#endif
