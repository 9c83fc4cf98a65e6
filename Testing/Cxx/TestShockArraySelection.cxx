// Which array the advection filters process when none is named: the active
// point scalars, else the active cell scalars (also for the empty name that
// ParaView sends when the input had no arrays yet), said at verbosity 1; and mixed composites.
#include "vtkImageShockAdvectionFilter.h"
#include "vtkPolyDataShockAdvectionFilter.h"

#include "TestFilterHelpers.h"

#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{
using shock_test::MessageLog;
using shock_test::UpdateSucceeds;

// A soft step along x, nx by ny samples (points) or cells.
vtkSmartPointer<vtkDoubleArray> Step(const char* name, int nx, int ny)
{
  auto values = vtkSmartPointer<vtkDoubleArray>::New();
  values->SetName(name);
  for (int y = 0; y < ny; ++y)
  {
    for (int x = 0; x < nx; ++x)
    {
      values->InsertNextValue(std::tanh((x - 0.5 * (nx - 1)) / 3.0));
    }
  }
  return values;
}

// The messages of vtkLogger at verbosity 1 (the filters' details: quiet at the
// default INFO), and those at INFO or more urgent, while it lives.
class InfoLog
{
public:
  InfoLog()
  {
    vtkLogger::AddCallback("shock-test-details", &InfoLog::Collect, &this->Text, vtkLogger::VERBOSITY_1);
    vtkLogger::AddCallback("shock-test-info", &InfoLog::Collect, &this->Info, vtkLogger::VERBOSITY_INFO);
  }
  ~InfoLog()
  {
    vtkLogger::RemoveCallback("shock-test-details");
    vtkLogger::RemoveCallback("shock-test-info");
  }
  std::string Text; ///< verbosity 1 and below
  std::string Info; ///< INFO and below: what a user sees by default

private:
  static void Collect(void* text, const vtkLogger::Message& message)
  {
    *static_cast<std::string*>(text) += std::string(message.message) + "\n";
  }
};

bool Changed(vtkDataArray* before, vtkDataArray* after)
{
  double largest = 0.0;
  for (vtkIdType i = 0; i < before->GetNumberOfTuples(); ++i)
  {
    largest = std::fmax(largest, std::fabs(after->GetTuple1(i) - before->GetTuple1(i)));
  }
  return largest > 0.05;
}
}

TEST(ShockArraySelection, EmptyNameMeansTheActivePointScalars)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(40, 8, 1);
  image->GetPointData()->AddArray(Step("Other", 40, 8));
  image->GetPointData()->SetScalars(Step("Active", 40, 8));
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(image);
  filter->SetFlowTime(512.0);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "");
  InfoLog log;
  ASSERT_TRUE(UpdateSucceeds(filter));
  vtkPointData* out = filter->GetOutput()->GetPointData();
  EXPECT_TRUE(Changed(image->GetPointData()->GetArray("Active"), out->GetArray("Active")));
  EXPECT_FALSE(Changed(image->GetPointData()->GetArray("Other"), out->GetArray("Other")));
  EXPECT_NE(log.Text.find("active point scalars 'Active'"), std::string::npos) << log.Text;
  EXPECT_EQ(log.Info, "") << "a successful run says nothing at the default verbosity";
}

TEST(ShockArraySelection, WithoutPointScalarsTheActiveCellScalars)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(41, 9, 1);
  image->GetPointData()->AddArray(Step("NotScalars", 41, 9));
  image->GetCellData()->SetScalars(Step("CellStep", 40, 8));
  vtkNew<vtkImageShockAdvectionFilter> filter; // the default selection: no name
  filter->SetInputData(image);
  filter->SetFlowTime(512.0);
  InfoLog log;
  ASSERT_TRUE(UpdateSucceeds(filter));
  EXPECT_TRUE(Changed(image->GetCellData()->GetScalars(), filter->GetOutput()->GetCellData()->GetArray("CellStep")));
  EXPECT_NE(log.Text.find("active cell scalars 'CellStep'"), std::string::npos) << log.Text;
}

TEST(ShockArraySelection, SurfacesFallBackToo)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(sphere->GetOutput());
  mesh->GetPointData()->SetScalars(nullptr);
  auto band = vtkSmartPointer<vtkDoubleArray>::New();
  band->SetName("Band");
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    double center[3] = { 0, 0, 0 };
    double point[3];
    for (vtkIdType k = 0; k < 3; ++k)
    {
      mesh->GetPoint(mesh->GetCell(c)->GetPointId(k), point);
      center[2] += point[2] / 3.0;
    }
    band->InsertNextValue(std::tanh(8.0 * center[2]));
  }
  mesh->GetCellData()->SetScalars(band);
  vtkNew<vtkPolyDataShockAdvectionFilter> filter;
  filter->SetInputData(mesh);
  filter->SetFlowTime(4096.0);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "");
  InfoLog log;
  ASSERT_TRUE(UpdateSucceeds(filter));
  EXPECT_TRUE(Changed(band, filter->GetOutput()->GetCellData()->GetArray("Band")));
  EXPECT_NE(log.Text.find("active cell scalars 'Band'"), std::string::npos) << log.Text;
}

TEST(ShockArraySelection, NoScalarsAtAllIsAClearError)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(10, 10, 1);
  image->GetPointData()->AddArray(Step("NotScalars", 10, 10));
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(image);
  MessageLog log(filter);
  EXPECT_FALSE(UpdateSucceeds(filter));
  EXPECT_NE(log.Errors.find("no active point or cell scalars"), std::string::npos) << log.Errors;
}

// The reason is said once: a serial run does not repeat it as "no array to filter".
TEST(ShockArraySelection, NoScalarsOnAMeshIsOneClearError)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  vtkNew<vtkPolyDataShockAdvectionFilter> filter;
  filter->SetInputData(sphere->GetOutput()); // normals only, no scalars
  MessageLog log(filter);
  EXPECT_FALSE(UpdateSucceeds(filter));
  EXPECT_NE(log.Errors.find("no active point or cell scalars"), std::string::npos) << log.Errors;
  EXPECT_EQ(log.Errors.find("ERROR"), log.Errors.rfind("ERROR")) << "one error only:\n" << log.Errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(ShockArraySelection, ANamedArrayThatIsMissingIsStillAnError)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(10, 10, 1);
  image->GetPointData()->SetScalars(Step("Active", 10, 10));
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(image);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Missing");
  MessageLog log(filter);
  EXPECT_FALSE(UpdateSucceeds(filter));
  EXPECT_NE(log.Errors.find("no point or cell array named 'Missing'"), std::string::npos) << log.Errors;
}

// A composite of an image and a mesh (ParaView's GroupDatasets): each filter
// filters the blocks of its type, as if alone, the others pass through; the one
// array ParaView names for all blocks falls back to a block's active scalars
// where the block lacks it (only inside a composite: alone, it is an error above).
TEST(ShockArraySelection, MixedCompositeBlocks)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(40, 8, 1);
  image->GetPointData()->SetScalars(Step("ImageStep", 40, 8));
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(sphere->GetOutput());
  auto heat = vtkSmartPointer<vtkDoubleArray>::New();
  heat->SetName("Heat");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    heat->InsertNextValue(std::tanh(8.0 * mesh->GetPoint(p)[2]));
  }
  mesh->GetPointData()->SetScalars(heat);
  vtkNew<vtkMultiBlockDataSet> group;
  group->SetNumberOfBlocks(2);
  group->SetBlock(0, image);
  group->SetBlock(1, mesh);

  // The image filter, with the mesh's array named (what ParaView's default gave).
  vtkNew<vtkImageShockAdvectionFilter> imageFilter;
  imageFilter->SetInputData(group);
  imageFilter->SetFlowTime(512.0);
  imageFilter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Heat");
  InfoLog log;
  MessageLog messages(imageFilter);
  ASSERT_TRUE(UpdateSucceeds(imageFilter)) << messages.Errors;
  EXPECT_EQ(messages.Errors, "");
  auto* out = vtkMultiBlockDataSet::SafeDownCast(imageFilter->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  auto* imageOut = vtkImageData::SafeDownCast(out->GetBlock(0));
  auto* meshOut = vtkPolyData::SafeDownCast(out->GetBlock(1));
  ASSERT_NE(imageOut, nullptr);
  ASSERT_NE(meshOut, nullptr);
  vtkNew<vtkImageShockAdvectionFilter> imageAlone;
  imageAlone->SetInputData(image);
  imageAlone->SetFlowTime(512.0);
  ASSERT_TRUE(UpdateSucceeds(imageAlone));
  vtkDataArray* filtered = imageOut->GetPointData()->GetArray("ImageStep");
  vtkDataArray* alone = imageAlone->GetOutput()->GetPointData()->GetArray("ImageStep");
  ASSERT_NE(filtered, nullptr);
  EXPECT_TRUE(Changed(image->GetPointData()->GetScalars(), filtered));
  ASSERT_NE(alone, nullptr);
  ASSERT_EQ(alone->GetNumberOfTuples(), filtered->GetNumberOfTuples());
  for (vtkIdType i = 0; i < alone->GetNumberOfTuples(); ++i)
  {
    ASSERT_EQ(alone->GetTuple1(i), filtered->GetTuple1(i)) << "the image block equals the image filtered alone";
  }
  EXPECT_EQ(meshOut->GetNumberOfPoints(), mesh->GetNumberOfPoints());
  EXPECT_EQ(meshOut->GetPointData()->GetArray("Heat"), heat.GetPointer()) << "the mesh block passes through";
  EXPECT_NE(messages.Warnings.find("has no array 'Heat': its active scalars 'ImageStep' are filtered instead"),
    std::string::npos)
    << messages.Warnings;

  // The surface filter on the same composite: the mesh filtered, the image passed through.
  vtkNew<vtkPolyDataShockAdvectionFilter> surfaceFilter;
  surfaceFilter->SetInputData(group);
  surfaceFilter->SetFlowTime(4096.0);
  ASSERT_TRUE(UpdateSucceeds(surfaceFilter));
  out = vtkMultiBlockDataSet::SafeDownCast(surfaceFilter->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  ASSERT_NE(vtkImageData::SafeDownCast(out->GetBlock(0)), nullptr);
  EXPECT_EQ(vtkImageData::SafeDownCast(out->GetBlock(0))->GetPointData()->GetArray("ImageStep"),
    image->GetPointData()->GetScalars()) << "the image block passes through";
  ASSERT_NE(vtkPolyData::SafeDownCast(out->GetBlock(1)), nullptr);
  EXPECT_TRUE(Changed(heat, vtkPolyData::SafeDownCast(out->GetBlock(1))->GetPointData()->GetArray("Heat")));
}
