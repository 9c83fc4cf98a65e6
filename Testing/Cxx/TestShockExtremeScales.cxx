// The VTK filters on data at extreme scales (issue #15): a mesh scaled by
// 1e80, 1e-100, 1e100 or 1e150, an image of spacing 1e-100 or 1e100. The
// algorithm is scale-covariant (the paper normalises lengths by the mean edge
// length or the grid spacing), so the result must be the unit-scale result
// scaled: never NaN, never the input silently unchanged, never a false
// "flipped triangles" report.
#include "TestFilterHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkImageShockAdvectionFilter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataShockAdvectionFilter.h"
#include "vtkPolyDataShockSharpenFilter.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
using shock_test::MessageLog;
using shock_test::UpdateSucceeds;
using shock_test::Values;

const double Scales[] = { 1e80, 1e-100, 1e100, 1e150 };

/// A flattened sphere (an ellipsoid of semi-axes 0.5, 0.5, 0.2) times `scale`,
/// double points, with a blurred step of values along x.
vtkSmartPointer<vtkPolyData> Ellipsoid(double scale)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(sphere->GetOutput());
  vtkNew<vtkDoubleArray> step;
  step->SetName("Step");
  step->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    step->SetValue(p, std::tanh(8.0 * x[0]));
    mesh->GetPoints()->SetPoint(p, scale * x[0], scale * x[1], scale * 0.4 * x[2]);
  }
  mesh->GetPointData()->SetScalars(step);
  return mesh;
}

std::vector<double> Coordinates(vtkPolyData* mesh)
{
  std::vector<double> xyz(static_cast<size_t>(3 * mesh->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    mesh->GetPoint(p, &xyz[static_cast<size_t>(3 * p)]);
  }
  return xyz;
}

bool AllFinite(const std::vector<double>& values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b, double bScale = 1.0)
{
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - bScale * b[i]));
  }
  return worst;
}

double FieldValue(vtkPolyData* mesh, const char* name)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, 0) : std::nan("");
}

TEST(ShockExtremeScales, SharpeningAMeshAtAnyScaleIsTheUnitResultScaled)
{
  vtkNew<vtkPolyDataShockSharpenFilter> unit;
  unit->SetInputData(Ellipsoid(1.0));
  ASSERT_TRUE(UpdateSucceeds(unit));
  const std::vector<double> reference = Coordinates(unit->GetOutput());
  const std::vector<double> input = Coordinates(Ellipsoid(1.0));
  ASSERT_GT(MaxDifference(reference, input), 1e-3); // sharpening moves the points
  ASSERT_EQ(unit->GetLastFlippedTriangles(), 0);
  for (const double scale : Scales)
  {
    vtkNew<vtkPolyDataShockSharpenFilter> filter;
    filter->SetInputData(Ellipsoid(scale));
    MessageLog log(filter);
    ASSERT_TRUE(UpdateSucceeds(filter)) << scale << ": " << log.Errors;
    const std::vector<double> result = Coordinates(filter->GetOutput());
    ASSERT_TRUE(AllFinite(result)) << scale;
    // The unit ellipsoid has size 1: differences relative to its size.
    EXPECT_LT(MaxDifference(result, reference, scale) / scale, 1e-7) << scale;
    EXPECT_EQ(filter->GetLastFlippedTriangles(), 0) << scale;
    // A fraction of the bounding-box diagonal: the same at every scale.
    EXPECT_NEAR(filter->GetLastMaxDisplacement(), unit->GetLastMaxDisplacement(), 1e-8) << scale;
    EXPECT_NEAR(FieldValue(filter->GetOutput(), "ShockMaxDisplacement"),
      FieldValue(unit->GetOutput(), "ShockMaxDisplacement"), 1e-8)
      << scale;
  }
}

TEST(ShockExtremeScales, AdvectionOnAMeshAtAnyScaleIsTheUnitResult)
{
  vtkNew<vtkPolyDataShockAdvectionFilter> unit;
  unit->SetInputData(Ellipsoid(1.0));
  ASSERT_TRUE(UpdateSucceeds(unit));
  const std::vector<double> reference = Values(unit->GetOutput()->GetPointData()->GetArray("Step"));
  ASSERT_GT(MaxDifference(reference, Values(Ellipsoid(1.0)->GetPointData()->GetArray("Step"))), 0.05);
  for (const double scale : Scales)
  {
    vtkNew<vtkPolyDataShockAdvectionFilter> filter;
    filter->SetInputData(Ellipsoid(scale));
    MessageLog log(filter);
    ASSERT_TRUE(UpdateSucceeds(filter)) << scale << ": " << log.Errors;
    const std::vector<double> result = Values(filter->GetOutput()->GetPointData()->GetArray("Step"));
    ASSERT_TRUE(AllFinite(result)) << scale;
    EXPECT_LT(MaxDifference(result, reference), 1e-9) << scale; // values in [-1, 1]
    // The points pass through.
    EXPECT_EQ(MaxDifference(Coordinates(filter->GetOutput()), Coordinates(Ellipsoid(scale))), 0.0) << scale;
  }
}

/// A 32 x 24 image of spacing `spacing` (all axes) holding a blurred disc.
vtkSmartPointer<vtkImageData> Disc(double spacing)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(32, 24, 1);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkDoubleArray> values;
  values->SetName("Disc");
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  for (int j = 0; j < 24; ++j)
  {
    for (int i = 0; i < 32; ++i)
    {
      const double r = std::hypot(i - 15.5, j - 11.0);
      values->SetValue(j * 32 + i, 1.0 / (1.0 + std::exp((r - 7.0) / 2.0)));
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

TEST(ShockExtremeScales, AnImageOfAnySpacingGivesTheUnitResult)
{
  vtkNew<vtkImageShockAdvectionFilter> unit;
  unit->SetInputData(Disc(1.0));
  ASSERT_TRUE(UpdateSucceeds(unit));
  const std::vector<double> reference = Values(unit->GetOutput()->GetPointData()->GetArray("Disc"));
  ASSERT_GT(MaxDifference(reference, Values(Disc(1.0)->GetPointData()->GetArray("Disc"))), 0.01);
  for (const double spacing : { 1e-100, 1e100, 1e-300, 1e300 })
  {
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputData(Disc(spacing));
    MessageLog log(filter);
    ASSERT_TRUE(UpdateSucceeds(filter)) << spacing << ": " << log.Errors;
    const std::vector<double> result = Values(filter->GetOutput()->GetPointData()->GetArray("Disc"));
    ASSERT_TRUE(AllFinite(result)) << spacing;
    EXPECT_LT(MaxDifference(result, reference), 1e-9) << spacing;
    EXPECT_EQ(filter->GetOutput()->GetSpacing()[0], spacing);
  }
}

} // namespace
