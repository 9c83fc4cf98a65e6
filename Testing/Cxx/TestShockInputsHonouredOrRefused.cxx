// Inputs the filters once turned into a plausible wrong result with success:
// each is now honoured exactly or refused with a message naming the problem.
// - values whose difference overflows a double (near +-1e308): refused;
// - one isolated point (no cell uses it) far away, 1e80 or 1e200: the
//   surface is filtered exactly as without it, and the point passes through;
// - a block of a composite that fails: empty, nothing of another block;
// - blanked samples (HIDDENPOINT): they neither feed nor receive values.
#include "vtkImageShockAdvectionFilter.h"
#include "vtkPolyDataShockAdvectionFilter.h"
#include "vtkPolyDataShockSharpenFilter.h"

#include "TestFilterHelpers.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkDataSetAttributes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace
{
using shock_test::MessageLog;
using shock_test::UpdateSucceeds;
using shock_test::Values;

/// A sphere (double points) with a blurred step "Heat" across z, times `scale`;
/// with an extra point at (far, 0, 0) that no cell uses when far != 0.
vtkSmartPointer<vtkPolyData> Sphere(double scale, double far = 0.0)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(32);
  source->SetPhiResolution(24);
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(source->GetOutput());
  if (far != 0.0)
  {
    mesh->GetPoints()->InsertNextPoint(far, 0.0, 0.0);
  }
  vtkNew<vtkDoubleArray> heat;
  heat->SetName("Heat");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    heat->InsertNextValue(scale * std::tanh(8.0 * mesh->GetPoint(p)[2]));
  }
  mesh->GetPointData()->SetScalars(heat);
  return mesh;
}

template <typename Filter>
std::vector<double> Filtered(vtkPolyData* input, bool points)
{
  vtkNew<Filter> filter;
  filter->SetInputData(input);
  filter->SetFlowTime(512.0);
  EXPECT_TRUE(UpdateSucceeds(filter));
  return points ? Values(filter->GetOutput()->GetPoints()->GetData())
                : Values(filter->GetOutput()->GetPointData()->GetArray("Heat"));
}
}

TEST(ShockInputsHonouredOrRefused, ValuesWhoseRangeOverflowsAreRefused)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(32, 24, 1);
  vtkNew<vtkDoubleArray> values;
  values->SetName("v");
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    values->InsertNextValue(1.5e308 * std::tanh(0.5 * (static_cast<double>(i % 32) - 15.5)));
  }
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkImageShockAdvectionFilter> imageFilter;
  imageFilter->SetInputData(image);
  MessageLog imageLog(imageFilter);
  EXPECT_FALSE(UpdateSucceeds(imageFilter));
  EXPECT_NE(imageLog.Errors.find("more than a double can hold as their difference"), std::string::npos)
    << imageLog.Errors;

  vtkNew<vtkPolyDataShockAdvectionFilter> surfaceFilter;
  surfaceFilter->SetInputData(Sphere(1.5e308));
  MessageLog surfaceLog(surfaceFilter);
  EXPECT_FALSE(UpdateSucceeds(surfaceFilter));
  EXPECT_NE(surfaceLog.Errors.find("rescale the array"), std::string::npos) << surfaceLog.Errors;

  // 1e300 wide is still a double's difference: filtered like the unit range, scaled.
  const std::vector<double> unit = Filtered<vtkPolyDataShockAdvectionFilter>(Sphere(1.0), false);
  const std::vector<double> wide = Filtered<vtkPolyDataShockAdvectionFilter>(Sphere(5e299), false);
  ASSERT_EQ(unit.size(), wide.size());
  double largest = 0.0, change = 0.0;
  const std::vector<double> input = Values(Sphere(1.0)->GetPointData()->GetArray("Heat"));
  for (size_t i = 0; i < unit.size(); ++i)
  {
    largest = std::max(largest, std::abs(wide[i] / 5e299 - unit[i]));
    change = std::max(change, std::abs(unit[i] - input[i]));
  }
  EXPECT_LT(largest, 1e-9);
  EXPECT_GT(change, 0.05);
}

TEST(ShockInputsHonouredOrRefused, AnIsolatedFarPointChangesNothing)
{
  for (double far : { 1e80, 1e200 })
  {
    for (bool sharpen : { false, true })
    {
      const std::vector<double> alone = sharpen ? Filtered<vtkPolyDataShockSharpenFilter>(Sphere(1.0), true)
                                                : Filtered<vtkPolyDataShockAdvectionFilter>(Sphere(1.0), false);
      vtkSmartPointer<vtkPolyData> withFar = Sphere(1.0, far);
      const std::vector<double> with = sharpen ? Filtered<vtkPolyDataShockSharpenFilter>(withFar, true)
                                               : Filtered<vtkPolyDataShockAdvectionFilter>(withFar, false);
      const std::vector<double> before = sharpen ? Values(Sphere(1.0)->GetPoints()->GetData())
                                                 : Values(Sphere(1.0)->GetPointData()->GetArray("Heat"));
      ASSERT_EQ(with.size(), alone.size() + (sharpen ? 3 : 1)) << far;
      EXPECT_EQ(std::vector<double>(with.begin(), with.begin() + static_cast<long>(alone.size())), alone)
        << "far point at " << far << (sharpen ? ", sharpen" : ", advection");
      EXPECT_NE(alone, before) << "the filter changed the surface";
      if (sharpen)
      {
        EXPECT_EQ(with[alone.size()], far) << "the isolated point stays where it is";
      }
    }
  }
}

// A block that fails (no array to filter) comes out empty, not with the
// arrays of the block filtered before it; the other blocks are filtered.
TEST(ShockInputsHonouredOrRefused, AFailedBlockCarriesNothing)
{
  auto good = vtkSmartPointer<vtkImageData>::New();
  good->SetDimensions(24, 16, 1);
  vtkNew<vtkDoubleArray> values;
  values->SetName("Step");
  for (vtkIdType i = 0; i < good->GetNumberOfPoints(); ++i)
  {
    values->InsertNextValue(std::tanh(0.5 * (static_cast<double>(i % 24) - 11.5)));
  }
  good->GetPointData()->SetScalars(values);
  auto bad = vtkSmartPointer<vtkImageData>::New();
  bad->SetDimensions(5, 5, 1); // no array at all
  vtkNew<vtkMultiBlockDataSet> group;
  group->SetNumberOfBlocks(2);
  group->SetBlock(0, good);
  group->SetBlock(1, bad);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(group);
  filter->SetFlowTime(256.0);
  MessageLog log(filter);
  filter->Update();
  EXPECT_NE(log.Errors.find("No array to process"), std::string::npos) << log.Errors;
  auto* out = vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  auto* first = vtkImageData::SafeDownCast(out->GetBlock(0));
  ASSERT_NE(first, nullptr);
  EXPECT_NE(Values(first->GetPointData()->GetArray("Step")), Values(values)) << "the good block is filtered";
  auto* second = vtkImageData::SafeDownCast(out->GetBlock(1));
  if (second)
  {
    EXPECT_EQ(second->GetPointData()->GetNumberOfArrays(), 0) << "nothing of the block before";
    EXPECT_EQ(second->GetNumberOfPoints(), 0);
  }
}

namespace
{
/// A 48 x 40 blurred step; columns 28..33 blanked (HIDDENPOINT) and holding `underneath`.
vtkSmartPointer<vtkImageData> BlankedStep(double underneath)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(48, 40, 1);
  vtkNew<vtkDoubleArray> values;
  values->SetName("v");
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    const int x = static_cast<int>(i % 48);
    const bool hidden = x >= 28 && x <= 33;
    values->InsertNextValue(hidden ? underneath : 0.5 + 0.49 * std::tanh((x - 20.0) / 3.0));
    ghosts->InsertNextValue(hidden ? vtkDataSetAttributes::HIDDENPOINT : 0);
  }
  image->GetPointData()->SetScalars(values);
  image->GetPointData()->AddArray(ghosts);
  return image;
}
}

// Blanked samples (vtkGhostType HIDDENPOINT) neither feed nor receive values:
// whatever lies under the blanking, the visible samples come out the same, and
// the blanked ones keep their own.
TEST(ShockInputsHonouredOrRefused, BlankedSamplesNeitherFeedNorReceive)
{
  std::vector<std::vector<double>> results;
  for (double underneath : { 5.0, -3.0 })
  {
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputData(BlankedStep(underneath));
    filter->SetFlowTime(512.0);
    ASSERT_TRUE(UpdateSucceeds(filter));
    results.push_back(Values(filter->GetOutput()->GetPointData()->GetArray("v")));
  }
  const std::vector<double> input = Values(BlankedStep(5.0)->GetPointData()->GetArray("v"));
  double changed = 0.0;
  for (size_t i = 0; i < input.size(); ++i)
  {
    const int x = static_cast<int>(i % 48);
    if (x >= 28 && x <= 33)
    {
      EXPECT_EQ(results[0][i], 5.0);
      EXPECT_EQ(results[1][i], -3.0);
      continue;
    }
    ASSERT_EQ(results[0][i], results[1][i]) << "sample " << i << " depends on the blanked values";
    EXPECT_LE(results[0][i], 0.99 + 1e-12);
    changed = std::max(changed, std::abs(results[0][i] - input[i]));
  }
  EXPECT_GT(changed, 0.05);

  // The same on a surface: blanked points of a sphere.
  std::vector<std::vector<double>> surfaces;
  for (double underneath : { 7.0, -7.0 })
  {
    vtkSmartPointer<vtkPolyData> mesh = Sphere(1.0);
    vtkNew<vtkUnsignedCharArray> ghosts;
    ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
    auto* heat = mesh->GetPointData()->GetArray("Heat");
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      const bool hidden = mesh->GetPoint(p)[0] > 0.3;
      ghosts->InsertNextValue(hidden ? vtkDataSetAttributes::HIDDENPOINT : 0);
      if (hidden)
      {
        heat->SetTuple1(p, underneath);
      }
    }
    mesh->GetPointData()->AddArray(ghosts);
    surfaces.push_back(Filtered<vtkPolyDataShockAdvectionFilter>(mesh, false));
  }
  vtkSmartPointer<vtkPolyData> plain = Sphere(1.0);
  const std::vector<double> before = Values(plain->GetPointData()->GetArray("Heat"));
  double surfaceChange = 0.0;
  for (vtkIdType p = 0; p < plain->GetNumberOfPoints(); ++p)
  {
    if (plain->GetPoint(p)[0] > 0.3)
    {
      EXPECT_EQ(surfaces[0][static_cast<size_t>(p)], 7.0);
      continue;
    }
    ASSERT_EQ(surfaces[0][static_cast<size_t>(p)], surfaces[1][static_cast<size_t>(p)]) << "point " << p;
    surfaceChange = std::max(surfaceChange, std::abs(surfaces[0][static_cast<size_t>(p)] - before[static_cast<size_t>(p)]));
  }
  EXPECT_GT(surfaceChange, 0.05);
}

// A line or vertex cell holding a point id out of range: refused by both
// surface filters with the cell named, never a crash (polygons were checked
// before; lines and vertices crashed the sharpening).
TEST(ShockInputsHonouredOrRefused, OutOfRangeIdsInLinesAndVerticesAreRefused)
{
  for (bool line : { true, false })
  {
    vtkSmartPointer<vtkPolyData> mesh = Sphere(1.0);
    vtkNew<vtkCellArray> cells;
    const vtkIdType ids[2] = { 0, 99999 };
    cells->InsertNextCell(line ? 2 : 1, line ? ids : ids + 1);
    if (line)
    {
      mesh->SetLines(cells);
    }
    else
    {
      mesh->SetVerts(cells);
    }
    vtkNew<vtkPolyDataShockSharpenFilter> sharpen;
    sharpen->SetInputData(mesh);
    MessageLog sharpenLog(sharpen);
    EXPECT_FALSE(UpdateSucceeds(sharpen));
    EXPECT_NE(sharpenLog.Errors.find(line ? "line cell" : "vertex cell"), std::string::npos) << sharpenLog.Errors;
    vtkNew<vtkPolyDataShockAdvectionFilter> advection;
    advection->SetInputData(mesh);
    MessageLog advectionLog(advection);
    EXPECT_FALSE(UpdateSucceeds(advection));
    EXPECT_NE(advectionLog.Errors.find(line ? "line cell" : "vertex cell"), std::string::npos) << advectionLog.Errors;
  }
}
