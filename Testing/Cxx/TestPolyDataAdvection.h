// Meshes, signals and measurements shared by the tests of
// vtkPolyDataShockAdvectionFilter (TestPolyDataShockAdvectionFilter.cxx,
// TestPolyDataShockAdvectionModes.cxx). Each test file gets its own copy (an
// unnamed namespace).
#ifndef TestPolyDataAdvection_h
#define TestPolyDataAdvection_h

#include "vtkPolyDataShockAdvectionFilter.h"

#include "TestFilterHelpers.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkElevationFilter.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIntArray.h"
#include "vtkLineSource.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPointSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkStripper.h"
#include "vtkTransform.h"
#include "vtkTransformFilter.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using shock_test::MaxDifferenceThrough;
using shock_test::MessageLog;
using shock_test::Renumbered;
using shock_test::UpdateSucceeds;
using shock_test::Values;

using Filter = vtkPolyDataShockAdvectionFilter;
using Configure = std::function<void(Filter*)>;

// ---------------------------------------------------------------------------
// Geometry and signals

/// Unit direction across which the blurred step changes (not aligned with the sphere's rings).
const double* StepDirection()
{
  static const double d[3] = { 1.0 / std::sqrt(5.25), 0.5 / std::sqrt(5.25), 2.0 / std::sqrt(5.25) };
  return d;
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Smooth step from 0 to 1 over [-halfWidth, halfWidth] (C1, like a blurred edge).
double SmoothStep(double x, double halfWidth)
{
  const double s = std::min(1.0, std::max(0.0, (x + halfWidth) / (2.0 * halfWidth)));
  return s * s * (3.0 - 2.0 * s);
}

/// The blurred step used throughout, at position x (sphere of radius 0.5: band about 10 edges wide).
double BlurredStep(const double x[3])
{
  return SmoothStep(Dot(x, StepDirection()), 0.08);
}

/// A vtkSphereSource (radius 0.5, centred at the origin, triangles) with double coordinates.
vtkSmartPointer<vtkPolyData> Sphere(int resolution = 96)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(resolution);
  source->SetPhiResolution(resolution);
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(source->GetOutput());
  return mesh;
}

using Field = std::function<double(const double x[3], int component)>;

/// Fill `array` (given type) with field(x, c) at the points of `mesh`; named `name`.
template <typename ArrayT = vtkDoubleArray>
vtkSmartPointer<ArrayT> PointArray(vtkPolyData* mesh, const char* name, const Field& field, int components = 1)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    for (int c = 0; c < components; ++c)
    {
      array->SetComponent(p, c, field(x, c));
    }
  }
  return array;
}

/// Centroid of a cell's points.
void CellCentre(vtkPolyData* mesh, vtkIdType cell, double centre[3])
{
  vtkNew<vtkIdList> ids;
  mesh->GetCellPoints(cell, ids);
  centre[0] = centre[1] = centre[2] = 0.0;
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
  {
    double x[3];
    mesh->GetPoint(ids->GetId(k), x);
    for (int a = 0; a < 3; ++a)
    {
      centre[a] += x[a] / static_cast<double>(ids->GetNumberOfIds());
    }
  }
}

template <typename ArrayT = vtkDoubleArray>
vtkSmartPointer<ArrayT> CellArray(vtkPolyData* mesh, const char* name, const Field& field, int components = 1)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(mesh->GetNumberOfCells());
  for (vtkIdType cell = 0; cell < mesh->GetNumberOfCells(); ++cell)
  {
    double x[3];
    CellCentre(mesh, cell, x);
    for (int c = 0; c < components; ++c)
    {
      array->SetComponent(cell, c, field(x, c));
    }
  }
  return array;
}

/// The sphere with the blurred step as active point scalars "Step".
vtkSmartPointer<vtkPolyData> StepSphere(int resolution = 96)
{
  auto mesh = Sphere(resolution);
  mesh->GetPointData()->SetScalars(
    PointArray(mesh, "Step", [](const double x[3], int) { return BlurredStep(x); }));
  return mesh;
}

// ---------------------------------------------------------------------------
// Measurements

struct Range
{
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  double Width() const { return this->high - this->low; }
};

/// Range of the finite values of component `c` (all components when c < 0).
Range RangeOf(vtkDataArray* array, int c = -1)
{
  Range r;
  const int nc = array->GetNumberOfComponents();
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int k = 0; k < nc; ++k)
    {
      if (c >= 0 && k != c)
      {
        continue;
      }
      const double v = array->GetComponent(i, k);
      if (std::isfinite(v))
      {
        r.low = std::min(r.low, v);
        r.high = std::max(r.high, v);
      }
    }
  }
  return r;
}

/// Tuples whose component 0 lies in the transition band (10% .. 90% of `range`).
vtkIdType BandCount(vtkDataArray* array, const Range& range)
{
  vtkIdType count = 0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    const double s = (array->GetComponent(i, 0) - range.low) / range.Width();
    count += (s > 0.1 && s < 0.9) ? 1 : 0;
  }
  return count;
}

/// Every value of every component finite and within the same component's input range.
::testing::AssertionResult FiniteAndInRange(vtkDataArray* out, vtkDataArray* in, double slack = 0.0)
{
  if (!out)
  {
    return ::testing::AssertionFailure() << "no output array";
  }
  if (out->GetNumberOfTuples() != in->GetNumberOfTuples() ||
    out->GetNumberOfComponents() != in->GetNumberOfComponents())
  {
    return ::testing::AssertionFailure() << "output array shape differs";
  }
  for (int c = 0; c < in->GetNumberOfComponents(); ++c)
  {
    const Range r = RangeOf(in, c);
    const double tolerance = slack * r.Width() + 1e-12 * std::max(std::abs(r.low), std::abs(r.high));
    for (vtkIdType i = 0; i < out->GetNumberOfTuples(); ++i)
    {
      const double v = out->GetComponent(i, c);
      if (!std::isfinite(v) || v < r.low - tolerance || v > r.high + tolerance)
      {
        return ::testing::AssertionFailure() << "tuple " << i << " component " << c << " = " << v
                                             << " outside [" << r.low << ", " << r.high << "]";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double m = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
  {
    m = std::max(m, std::abs(a[i] - b[i]));
  }
  return m;
}

// ---------------------------------------------------------------------------
// Running the filter

/// Filter `input` with FlowTime `time` after `setup`; the output (kept alive after the filter).
vtkSmartPointer<vtkPolyData> FilterMesh(vtkPolyData* input, double time, const Configure& setup = Configure())
{
  vtkNew<Filter> filter;
  filter->SetInputData(input);
  filter->SetFlowTime(time);
  if (setup)
  {
    setup(filter);
  }
  filter->Update();
  return filter->GetOutput();
}

Configure PointArrayNamed(const char* name)
{
  return [name](Filter* f) {
    f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name);
  };
}

Configure CellArrayNamed(const char* name)
{
  return [name](Filter* f) {
    f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, name);
  };
}

/// The flow time that visibly sharpens the step of StepSphere().
constexpr double SharpeningTime = 4000.0;

/// The flow time that sharpens vtkElevationFilter's ramp on a sphere along the equator:
/// the ramp spreads over the whole sphere, so its flow is much slower.
constexpr double RampSharpeningTime = 1e6;

} // namespace

#endif
