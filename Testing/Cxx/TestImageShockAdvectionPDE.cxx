// Tests of vtkImageShockAdvectionFilter's Method PDE (the Osher-Rudin baseline)
// in real VTK pipelines: it sharpens like the advection, equals the kernel for
// point and cell data, warns at the iteration limit, fails cleanly and honours
// abort (the other tests: TestImageShockAdvectionFilter.cxx,
// TestImageShockAdvectionErrors.cxx).
#include "TestImageShockAdvection.h"

namespace
{

// --- Method PDE: the Osher-Rudin baseline through the same filter -------------

TEST(ImageShockAdvectionFilter, PDEMethodSharpensLikeTheAdvection)
{
  // The same blurred ellipse as WorksInAPipelineAndKeepsTheImageStructure
  // (TestImageShockAdvectionFilter.cxx), through a real pipeline, by both methods
  // with the same parameters: the PDE sharpens too, stays in range, keeps the
  // array's type and the image structure, and the two steady states are close.
  vtkNew<vtkImageEllipsoidSource> source;
  source->SetWholeExtent(0, 63, 0, 47, 0, 0);
  source->SetCenter(30, 22, 0);
  source->SetRadius(14, 9, 1);
  source->SetInValue(220);
  source->SetOutValue(30);
  source->SetOutputScalarTypeToUnsignedChar();
  vtkNew<vtkImageGaussianSmooth> blur;
  blur->SetInputConnection(source->GetOutputPort());
  blur->SetStandardDeviations(1.5, 1.5, 0.0);
  blur->SetDimensionality(2);
  vtkNew<vtkImageShockAdvectionFilter> pde;
  pde->SetInputConnection(blur->GetOutputPort());
  pde->SetMethodToPDE();
  pde->SetFlowTime(4096.0);
  MessageLog log(pde);
  ASSERT_TRUE(UpdateSucceeds(pde));
  EXPECT_TRUE(log.Warnings.empty()) << log.Warnings;
  vtkNew<vtkImageShockAdvectionFilter> advection;
  advection->SetInputConnection(blur->GetOutputPort());
  advection->SetFlowTime(4096.0);
  advection->Update();

  vtkImageData* in = blur->GetOutput();
  vtkImageData* out = pde->GetOutput();
  EXPECT_EQ(out->GetNumberOfPoints(), in->GetNumberOfPoints());
  vtkDataArray* scalars = out->GetPointData()->GetScalars();
  ASSERT_NE(scalars, nullptr);
  EXPECT_EQ(scalars->GetDataType(), VTK_UNSIGNED_CHAR);
  double inRange[2], outRange[2];
  in->GetPointData()->GetScalars()->GetRange(inRange);
  scalars->GetRange(outRange);
  EXPECT_GE(outRange[0], inRange[0]);
  EXPECT_LE(outRange[1], inRange[1]);
  const char* name = scalars->GetName();
  EXPECT_GT(GradientEnergy(out, name), 1.5 * GradientEnergy(in, name));
  EXPECT_GT(pde->GetLastIterations(), 1);
  EXPECT_DOUBLE_EQ(pde->GetLastReachedTime(), 4096.0);
  EXPECT_EQ(pde->GetLastTraceSteps(), 0u);
  EXPECT_GT(pde->GetLastFlowSeconds(), 0.0);
  // The advection run reports no PDE steps.
  EXPECT_EQ(advection->GetLastIterations(), 0);

  const auto a = Values(scalars);
  const auto b = Values(advection->GetOutput()->GetPointData()->GetScalars());
  double difference = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    difference += std::abs(a[i] - b[i]);
  }
  EXPECT_LT(difference / static_cast<double>(a.size()), 0.03 * (inRange[1] - inRange[0]));
}

TEST(ImageShockAdvectionFilter, PDEMethodEqualsTheKernelAndHandlesEveryAssociation)
{
  // The filter is a thin layer: its double output equals the kernel's on the
  // same samples, for point data and for cell data on the grid of cell centres.
  for (bool cells : { false, true })
  {
    vtkNew<vtkDoubleArray> values;
    auto image = MakeImage(values, 30, 24, 1, 2);
    if (cells)
    {
      image->GetPointData()->RemoveArray("Intensity");
      vtkNew<vtkDoubleArray> cellValues;
      auto grid = MakeImage(cellValues, 29, 23, 1, 2);
      image->GetCellData()->SetScalars(cellValues);
    }
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputData(image);
    filter->SetInputArrayToProcess(0, 0, 0,
      cells ? vtkDataObject::FIELD_ASSOCIATION_CELLS : vtkDataObject::FIELD_ASSOCIATION_POINTS,
      "Intensity");
    filter->SetMethod(vtkImageShockAdvectionFilter::PDE);
    filter->SetFlowTime(48.0);
    filter->SetCourantNumber(0.3);
    filter->SetSmoothingPasses(2);
    ASSERT_TRUE(UpdateSucceeds(filter));

    vtkDataArray* input = cells ? image->GetCellData()->GetArray("Intensity")
                                : image->GetPointData()->GetArray("Intensity");
    shock::GridShape shape;
    shape.dimensions = { cells ? 29 : 30, cells ? 23 : 24, 1 };
    shape.spacing = { 0.5, 0.5, 0.5 };
    shock::PDEParameters p;
    p.time = 48.0;
    p.courantNumber = 0.3;
    p.smoothingPasses = 2;
    const auto samples = Values(input);
    std::vector<double> expected(samples.size());
    ASSERT_TRUE(shock::SolveGridShockPDE(shape, 2, samples.data(), expected.data(), p).Ok());
    vtkDataArray* output = cells ? filter->GetOutput()->GetCellData()->GetArray("Intensity")
                                 : filter->GetOutput()->GetPointData()->GetArray("Intensity");
    EXPECT_EQ(Values(output), expected) << (cells ? "cells" : "points");
    EXPECT_NE(expected, samples);
    // The input is untouched.
    EXPECT_EQ(Values(input), samples);
  }
}

TEST(ImageShockAdvectionFilter, PDEMethodWarnsAtTheIterationLimit)
{
  vtkNew<vtkFloatArray> values;
  auto image = MakeImage(values);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  MessageLog log(filter);
  filter->SetInputData(image);
  filter->SetMethodToPDE();
  filter->SetFlowTime(5000.0);
  filter->SetMaximumIterations(2);
  ASSERT_TRUE(UpdateSucceeds(filter));
  EXPECT_NE(log.Warnings.find("MaximumIterations"), std::string::npos) << log.Warnings;
  EXPECT_EQ(filter->GetLastIterations(), 2);
  EXPECT_GT(filter->GetLastReachedTime(), 0.0);
  EXPECT_LT(filter->GetLastReachedTime(), 5000.0);
  EXPECT_NE(Values(filter->GetOutput()->GetPointData()->GetScalars()), Values(values));
}

TEST(ImageShockAdvectionFilter, PDEMethodFailsCleanlyAndHonoursAbort)
{
  vtkNew<vtkFloatArray> values;
  auto image = MakeImage(values, 200, 150);
  // Bad time: an error and no output, as for the advection.
  for (double bad : { -1.0, std::numeric_limits<double>::quiet_NaN() })
  {
    vtkNew<vtkImageShockAdvectionFilter> filter;
    MessageLog log(filter);
    filter->SetInputData(image);
    filter->SetMethodToPDE();
    filter->SetFlowTime(bad);
    EXPECT_FALSE(UpdateSucceeds(filter));
    EXPECT_NE(log.Errors.find("FlowTime"), std::string::npos) << log.Errors;
    EXPECT_EQ(filter->GetLastIterations(), 0);
  }
  // A NaN sample stays where it is and does not spread.
  {
    vtkNew<vtkFloatArray> withNaN;
    auto nanImage = MakeImage(withNaN);
    withNaN->SetValue(300, std::numeric_limits<float>::quiet_NaN());
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputData(nanImage);
    filter->SetMethodToPDE();
    filter->SetFlowTime(256.0);
    ASSERT_TRUE(UpdateSucceeds(filter));
    const auto out = Values(filter->GetOutput()->GetPointData()->GetScalars());
    for (size_t i = 0; i < out.size(); ++i)
    {
      EXPECT_EQ(std::isnan(out[i]), i == 300) << i;
    }
  }
  // Abort at the first progress report: the data comes out unfiltered.
  vtkNew<vtkImageShockAdvectionFilter> aborting;
  aborting->SetInputData(image);
  aborting->SetMethodToPDE();
  aborting->SetFlowTime(100000.0);
  vtkNew<vtkCallbackCommand> onAbort;
  onAbort->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  aborting->AddObserver(vtkCommand::ProgressEvent, onAbort);
  aborting->Update();
  EXPECT_LE(aborting->GetLastIterations(), 1);
  EXPECT_EQ(Values(aborting->GetOutput()->GetPointData()->GetScalars()), Values(values));
}

} // namespace
