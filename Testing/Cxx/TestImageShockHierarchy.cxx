// vtkImageShockAdvectionFilter's HierarchyLevels (coarse-to-fine tracing,
// docs/hierarchy.md) in real VTK pipelines.
#include "vtkImageShockAdvectionFilter.h"

#include "TestFilterHelpers.h"

#include "vtkImageData.h"
#include "vtkImageEllipsoidSource.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkImageMathematics.h"
#include "vtkImageNoiseSource.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace
{

using shock_test::Values;

/// A large disc (0 outside, 1 inside), blurred with sigma = 6 pixels, plus uniform noise.
struct NoisyDisc
{
  vtkNew<vtkImageEllipsoidSource> disc;
  vtkNew<vtkImageGaussianSmooth> blur;
  vtkNew<vtkImageNoiseSource> noise;
  vtkNew<vtkImageMathematics> sum;

  NoisyDisc()
  {
    disc->SetWholeExtent(0, 127, 0, 95, 0, 0);
    disc->SetCenter(62, 47, 0);
    disc->SetRadius(36, 30, 1);
    disc->SetInValue(1.0);
    disc->SetOutValue(0.0);
    disc->SetOutputScalarTypeToDouble();
    blur->SetInputConnection(disc->GetOutputPort());
    blur->SetDimensionality(2);
    blur->SetStandardDeviations(6.0, 6.0, 0.0);
    blur->SetRadiusFactors(4.0, 4.0, 0.0);
    noise->SetWholeExtent(0, 127, 0, 95, 0, 0);
    noise->SetMinimum(-0.1);
    noise->SetMaximum(0.1);
    sum->SetOperationToAdd();
    sum->SetInputConnection(0, blur->GetOutputPort());
    sum->SetInputConnection(1, noise->GetOutputPort());
  }

  /// Root-mean-square difference of the filter's output to the sharp disc.
  double Error(vtkImageData* image)
  {
    disc->Update();
    const auto sharp = Values(disc->GetOutput()->GetPointData()->GetScalars());
    const auto values = Values(image->GetPointData()->GetScalars());
    double total = 0.0;
    for (size_t s = 0; s < sharp.size(); ++s)
    {
      total += (values[s] - sharp[s]) * (values[s] - sharp[s]);
    }
    return std::sqrt(total / static_cast<double>(sharp.size()));
  }
};

TEST(ImageShockHierarchy, DefaultIsOneLevelClampedToItsRangeAndPrinted)
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  EXPECT_EQ(filter->GetHierarchyLevels(), 1);
  filter->SetHierarchyLevels(0);
  EXPECT_EQ(filter->GetHierarchyLevels(), 1);
  filter->SetHierarchyLevels(100);
  EXPECT_EQ(filter->GetHierarchyLevels(), 16);
  filter->SetHierarchyLevels(3);
  std::ostringstream printed;
  filter->Print(printed);
  EXPECT_NE(printed.str().find("HierarchyLevels: 3"), std::string::npos);
}

TEST(ImageShockHierarchy, OneLevelIsTheDefaultResultAndMoreLevelsSharpenTheNoisyDiscMore)
{
  NoisyDisc data;
  vtkNew<vtkImageShockAdvectionFilter> single;
  single->SetInputConnection(data.sum->GetOutputPort());
  single->SetFlowTime(1e5);
  single->Update();
  vtkNew<vtkImageShockAdvectionFilter> one;
  one->SetInputConnection(data.sum->GetOutputPort());
  one->SetFlowTime(1e5);
  one->SetHierarchyLevels(1);
  one->Update();
  vtkNew<vtkImageShockAdvectionFilter> two;
  two->SetInputConnection(data.sum->GetOutputPort());
  two->SetFlowTime(1e5);
  two->SetHierarchyLevels(2);
  two->Update();

  const auto in = Values(data.sum->GetOutput()->GetPointData()->GetScalars());
  const auto out = Values(two->GetOutput()->GetPointData()->GetScalars());
  EXPECT_EQ(Values(one->GetOutput()->GetPointData()->GetScalars()),
    Values(single->GetOutput()->GetPointData()->GetScalars()));
  const auto [low, high] = std::minmax_element(in.begin(), in.end());
  const auto [outLow, outHigh] = std::minmax_element(out.begin(), out.end());
  EXPECT_GE(*outLow, *low);
  EXPECT_LE(*outHigh, *high);

  const double before = data.Error(data.sum->GetOutput());
  const double withOne = data.Error(single->GetOutput());
  const double withTwo = data.Error(two->GetOutput());
  EXPECT_LT(withOne, 0.97 * before); // one level sharpens too
  EXPECT_LT(withTwo, 0.85 * withOne) << before << " " << withOne << " " << withTwo;
}

TEST(ImageShockHierarchy, ResultDoesNotDependOnTheThreadCount)
{
  NoisyDisc data;
  std::vector<double> results[2];
  for (int threads : { 1, 2 })
  {
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputConnection(data.sum->GetOutputPort());
    filter->SetFlowTime(1e4);
    filter->SetHierarchyLevels(3);
    filter->SetNumberOfThreads(threads);
    filter->Update();
    results[threads - 1] = Values(filter->GetOutput()->GetPointData()->GetScalars());
  }
  EXPECT_EQ(results[0], results[1]);
}

} // namespace
