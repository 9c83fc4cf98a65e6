// The prepared mesh that vtkPolyDataShockAdvectionFilter keeps between executions:
// kept when only a parameter changes (ParaView's Apply after a new FlowTime),
// prepared again when the input's points or cells change, and the results
// always equal those of a fresh filter; and the triangles read from either
// storage of a cell array (64- or 32-bit ids) give the same result.
#include "vtkPolyDataShockAdvectionFilter.h"

#include "TestFilterHelpers.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkElevationFilter.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace
{

using shock_test::Values;
using Filter = vtkPolyDataShockAdvectionFilter;

/// A sphere whose point scalars are a blurred step across an oblique plane.
vtkSmartPointer<vtkPolyData> StepSphere(int resolution)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(resolution);
  source->SetPhiResolution(resolution);
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(source->GetOutput());
  vtkNew<vtkDoubleArray> values;
  values->SetName("step");
  values->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    values->SetValue(p, std::tanh(12.0 * (0.3 * x[0] + 0.5 * x[1] + 0.8 * x[2])));
  }
  mesh->GetPointData()->SetScalars(values);
  return mesh;
}

/// The filtered scalars of a fresh filter on `input` with FlowTime `time`.
std::vector<double> FreshResult(vtkPolyData* input, double time)
{
  vtkNew<Filter> fresh;
  fresh->SetInputData(input);
  fresh->SetFlowTime(time);
  fresh->Update();
  EXPECT_EQ(fresh->GetNumberOfMeshPreparations(), 1);
  return Values(fresh->GetOutput()->GetPointData()->GetScalars());
}

std::vector<double> Result(Filter* filter)
{
  return Values(filter->GetOutput()->GetPointData()->GetScalars());
}

TEST(PolyDataMeshCache, ChangingOnlyParametersKeepsThePreparedMesh)
{
  // As in ParaView: a source, an elevation, the filter; FlowTime changed, Apply again.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(sphere->GetOutputPort());
  elevation->SetLowPoint(-0.3, -0.2, -0.4);
  elevation->SetHighPoint(0.3, 0.2, 0.4);
  vtkNew<Filter> filter;
  filter->SetInputConnection(elevation->GetOutputPort());
  filter->SetFlowTime(16);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  const std::vector<double> first = Result(filter);

  filter->SetFlowTime(256);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  const std::vector<double> second = Result(filter);
  EXPECT_NE(first, second); // the new time was used
  EXPECT_EQ(second, FreshResult(vtkPolyData::SafeDownCast(elevation->GetOutput()), 256));

  filter->SetSmoothingPasses(3);
  filter->SetNumberOfThreads(1);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  EXPECT_NE(Result(filter), second);

  // Upstream runs again with the same points and cells (only its scalars
  // change): the prepared mesh is kept, the result is a fresh filter's.
  filter->SetSmoothingPasses(1); // as FreshResult's filter
  elevation->SetHighPoint(0.5, 0.2, 0.4);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  EXPECT_EQ(Result(filter), FreshResult(vtkPolyData::SafeDownCast(elevation->GetOutput()), 256));

  // An upstream change gives a new mesh: prepared again, equal to a fresh filter.
  sphere->SetThetaResolution(40);
  filter->SetSmoothingPasses(1);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 2);
  EXPECT_EQ(elevation->GetOutput()->GetNumberOfPoints(), filter->GetOutput()->GetNumberOfPoints());
  EXPECT_EQ(Result(filter), FreshResult(vtkPolyData::SafeDownCast(elevation->GetOutput()), 256));
}

TEST(PolyDataMeshCache, MovedPointsArePreparedAgain)
{
  vtkSmartPointer<vtkPolyData> mesh = StepSphere(40);
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->SetFlowTime(64);
  filter->Update();
  const std::vector<double> before = Result(filter);

  // Stretch the sphere along z in place (the points' Modified, as VTK asks).
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    double x[3];
    points->GetPoint(p, x);
    points->SetPoint(p, x[0], x[1], 3.0 * x[2]);
  }
  points->Modified();
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 2);
  EXPECT_NE(Result(filter), before);
  EXPECT_EQ(Result(filter), FreshResult(mesh, 64));

  // The same coordinates as float: another data type, prepared again.
  vtkNew<vtkPoints> floats;
  floats->SetDataTypeToFloat();
  floats->DeepCopy(points);
  ASSERT_EQ(floats->GetDataType(), VTK_FLOAT);
  mesh->SetPoints(floats);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 3);
  EXPECT_EQ(Result(filter), FreshResult(mesh, 64));
}

TEST(PolyDataMeshCache, ChangedCellsArePreparedAgain)
{
  vtkSmartPointer<vtkPolyData> mesh = StepSphere(40);
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->SetFlowTime(64);
  filter->Update();
  const std::vector<double> before = Result(filter);
  filter->SetFlowTime(64.0); // unchanged parameter: nothing runs again
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);

  // Replace the corners of every other triangle by those of its successor,
  // in place (the cell array's Modified): other connectivity, same counts.
  vtkCellArray* polys = mesh->GetPolys();
  vtkNew<vtkIdList> a, b;
  for (vtkIdType c = 0; c + 1 < polys->GetNumberOfCells(); c += 2)
  {
    polys->GetCellAtId(c + 1, a);
    polys->ReplaceCellAtId(c, a);
  }
  polys->Modified();
  mesh->Modified();
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 2);
  EXPECT_NE(Result(filter), before);
  EXPECT_EQ(Result(filter), FreshResult(mesh, 64));

  // New polygons: half the triangles removed.
  vtkNew<vtkCellArray> half;
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); c += 2)
  {
    polys->GetCellAtId(c, b);
    half->InsertNextCell(b);
  }
  mesh->SetPolys(half);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 3);
  EXPECT_EQ(Result(filter), FreshResult(mesh, 64));
}

TEST(PolyDataMeshCache, AnUnusableInputKeepsNothing)
{
  vtkSmartPointer<vtkPolyData> mesh = StepSphere(24);
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->SetFlowTime(16);
  filter->Update();
  const std::vector<double> good = Result(filter);
  double saved[3];
  mesh->GetPoint(5, saved);
  mesh->GetPoints()->SetPoint(5, std::nan(""), saved[1], saved[2]);
  mesh->GetPoints()->Modified();
  shock_test::MessageLog log(filter);
  EXPECT_FALSE(shock_test::UpdateSucceeds(filter));
  EXPECT_NE(log.Errors.find("not finite"), std::string::npos) << log.Errors;
  mesh->GetPoints()->SetPoint(5, saved);
  mesh->GetPoints()->Modified();
  filter->Update();
  // The NaN is refused before any mesh is prepared (the input checks come
  // first); the edited points are prepared again, not taken from the cache.
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 2);
  EXPECT_EQ(Result(filter), good);
}

TEST(PolyDataMeshCache, TrianglesIn32BitCellArraysGiveTheSameResult)
{
  vtkSmartPointer<vtkPolyData> mesh = StepSphere(40);
  const std::vector<double> reference = FreshResult(mesh, 64);
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(mesh->GetPolys());
  ASSERT_TRUE(polys->ConvertTo32BitStorage());
  ASSERT_FALSE(polys->IsStorage64Bit());
  mesh->SetPolys(polys);
  EXPECT_EQ(FreshResult(mesh, 64), reference);
  // An id out of range in 32-bit storage: the same clear error as in 64-bit storage.
  vtkNew<vtkIdList> ids;
  polys->GetCellAtId(7, ids);
  ids->SetId(1, mesh->GetNumberOfPoints());
  polys->ReplaceCellAtId(7, ids);
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  shock_test::MessageLog log(filter);
  EXPECT_FALSE(shock_test::UpdateSucceeds(filter));
  EXPECT_NE(log.Errors.find("refers to point"), std::string::npos) << log.Errors;
}

} // namespace
