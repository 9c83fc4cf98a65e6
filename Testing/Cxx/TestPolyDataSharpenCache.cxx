// What vtkPolyDataShockSharpenFilter keeps between executions: the prepared
// mesh (and the kernels' clean mesh, smoothed normals and feature split) until
// the input's points or cells change, the fit's matrix until they or the
// screening weight change. Pressing Apply again after changing only a flow
// parameter rebuilds neither, and every result equals a fresh filter's.
#include "vtkPolyDataShockSharpenFilter.h"

#include "TestFilterHelpers.h"

#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkLoopSubdivisionFilter.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"

#include <gtest/gtest.h>

#include <functional>
#include <vector>

namespace
{
using Filter = vtkPolyDataShockSharpenFilter;
using shock_test::Values;

/// A cube rounded by Loop subdivision: creases to sharpen.
struct RoundedCube
{
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkTriangleFilter> triangles;
  vtkNew<vtkCleanPolyData> clean;
  vtkNew<vtkLoopSubdivisionFilter> loop;
  vtkNew<vtkTransform> transform;
  vtkNew<vtkTransformPolyDataFilter> moved;

  RoundedCube()
  {
    this->triangles->SetInputConnection(this->cube->GetOutputPort());
    this->clean->SetInputConnection(this->triangles->GetOutputPort());
    this->loop->SetInputConnection(this->clean->GetOutputPort());
    this->loop->SetNumberOfSubdivisions(4);
    this->moved->SetInputConnection(this->loop->GetOutputPort());
    this->moved->SetTransform(this->transform);
  }
};

std::vector<double> Points(Filter* filter)
{
  return Values(filter->GetOutput()->GetPoints()->GetData());
}

/// The points of a fresh filter set up by `setup` on the output of `source`.
std::vector<double> FreshPoints(vtkAlgorithm* source, const std::function<void(Filter*)>& setup)
{
  vtkNew<Filter> fresh;
  fresh->SetInputConnection(source->GetOutputPort());
  setup(fresh);
  fresh->Update();
  EXPECT_EQ(fresh->GetNumberOfMeshPreparations(), 1);
  EXPECT_EQ(fresh->GetNumberOfFitAssemblies(), 1);
  return Points(fresh);
}

TEST(PolyDataSharpenCache, ChangingOnlyFlowParametersRebuildsNothing)
{
  RoundedCube input;
  vtkNew<Filter> filter;
  filter->SetInputConnection(input.moved->GetOutputPort());
  filter->SetFlowTime(64);
  filter->Update();
  const std::vector<double> first = Points(filter);
  filter->SetFlowTime(1024); // Apply again with a new flow time
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  EXPECT_EQ(filter->GetNumberOfFitAssemblies(), 1);
  const std::vector<double> second = Points(filter);
  EXPECT_NE(second, first);
  EXPECT_EQ(second, FreshPoints(input.moved, [](Filter* f) { f->SetFlowTime(1024); }));
  filter->SetSampling(vtkShockAdvectionFilter::NEAREST);
  filter->SetSolverIterations(40);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  EXPECT_EQ(filter->GetNumberOfFitAssemblies(), 1);
  EXPECT_NE(Points(filter), second);
  EXPECT_EQ(Points(filter), FreshPoints(input.moved, [](Filter* f) {
    f->SetFlowTime(1024);
    f->SetSampling(vtkShockAdvectionFilter::NEAREST);
    f->SetSolverIterations(40);
  }));
}

TEST(PolyDataSharpenCache, TheScreeningWeightReassemblesTheFitOnly)
{
  RoundedCube input;
  vtkNew<Filter> filter;
  filter->SetInputConnection(input.moved->GetOutputPort());
  filter->Update();
  const std::vector<double> first = Points(filter);
  filter->SetScreeningWeight(10.0);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  EXPECT_EQ(filter->GetNumberOfFitAssemblies(), 2);
  EXPECT_NE(Points(filter), first);
  EXPECT_EQ(Points(filter), FreshPoints(input.moved, [](Filter* f) { f->SetScreeningWeight(10.0); }));
  // The feature angle and the smoothing change the normals, not the matrix.
  filter->SetFeatureAngle(5.0);
  filter->SetNormalSmoothingPasses(2);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 1);
  EXPECT_EQ(filter->GetNumberOfFitAssemblies(), 2);
  EXPECT_EQ(Points(filter), FreshPoints(input.moved, [](Filter* f) {
    f->SetScreeningWeight(10.0);
    f->SetFeatureAngle(5.0);
    f->SetNormalSmoothingPasses(2);
  }));
}

TEST(PolyDataSharpenCache, ANewInputIsPreparedAgain)
{
  RoundedCube input;
  vtkNew<Filter> filter;
  filter->SetInputConnection(input.moved->GetOutputPort());
  filter->Update();
  const std::vector<double> first = Points(filter);
  // Moved points: prepared and assembled again, the result follows them.
  input.transform->Scale(2.0, 1.0, 1.0);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 2);
  EXPECT_EQ(filter->GetNumberOfFitAssemblies(), 2);
  EXPECT_NE(Points(filter), first);
  EXPECT_EQ(Points(filter), FreshPoints(input.moved, [](Filter*) {}));
  // Other triangles (one subdivision level less).
  input.loop->SetNumberOfSubdivisions(3);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 3);
  EXPECT_EQ(filter->GetNumberOfFitAssemblies(), 3);
  EXPECT_EQ(Points(filter), FreshPoints(input.moved, [](Filter*) {}));
  // The same input without merging coincident points is prepared again too.
  filter->MergeCoincidentPointsOff();
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 4);
  EXPECT_EQ(Points(filter), FreshPoints(input.moved, [](Filter* f) { f->MergeCoincidentPointsOff(); }));
}

TEST(PolyDataSharpenCache, AFailedExecutionKeepsNothingWrong)
{
  // A mesh with a NaN point fails; the repaired mesh afterwards gives the fresh result.
  RoundedCube input;
  input.moved->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(input.moved->GetOutput());
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->Update();
  double saved[3];
  mesh->GetPoints()->GetPoint(0, saved);
  mesh->GetPoints()->SetPoint(0, std::nan(""), 0.0, 0.0);
  mesh->GetPoints()->Modified();
  EXPECT_FALSE(shock_test::UpdateSucceeds(filter));
  mesh->GetPoints()->SetPoint(0, saved);
  mesh->GetPoints()->Modified();
  filter->Update();
  vtkNew<Filter> fresh;
  fresh->SetInputData(mesh);
  fresh->Update();
  EXPECT_EQ(Points(filter), Points(fresh));
}
} // namespace

// VTK's idiom for data edited in place: write the coordinates (here through the
// array's memory, as numpy does), then Modified() on the data set only. The
// filter must see the new shape, not the one it prepared before.
TEST(PolyDataSharpenCache, CoordinatesEditedInPlaceAndTheDataSetModified)
{
  RoundedCube shape;
  shape.moved->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(shape.moved->GetOutput());
  vtkNew<vtkPoints> doubles;
  doubles->SetDataTypeToDouble();
  doubles->DeepCopy(mesh->GetPoints());
  mesh->SetPoints(doubles);
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->SetFlowTime(256);
  filter->Update();
  const std::vector<double> before = Points(filter);

  auto* coordinates = static_cast<double*>(mesh->GetPoints()->GetData()->GetVoidPointer(0));
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    coordinates[3 * p + 2] *= 2.0; // stretched along z, the arrays' times untouched
  }
  mesh->Modified();
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfMeshPreparations(), 2);
  const std::vector<double> after = Points(filter);
  EXPECT_NE(after, before);
  vtkNew<Filter> fresh;
  fresh->SetInputData(mesh);
  fresh->SetFlowTime(256);
  fresh->Update();
  EXPECT_EQ(after, Points(fresh)) << "the edited mesh sharpened, not the old one";
}
