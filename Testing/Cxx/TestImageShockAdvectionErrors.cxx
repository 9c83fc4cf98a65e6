// Tests of vtkImageShockAdvectionFilter in real VTK pipelines: NaN values, bad
// inputs with a clear error, progress and abort, PrintSelf and the clamps of the
// parameters (the other tests: TestImageShockAdvectionFilter.cxx,
// TestImageShockAdvectionPDE.cxx).
#include "TestImageShockAdvection.h"

namespace
{

TEST(ImageShockAdvectionFilter, NaNStaysWhereItWas)
{
  vtkNew<vtkFloatArray> values;
  auto image = MakeImage(values);
  double range[2];
  values->GetRange(range);
  values->SetValue(100, std::numeric_limits<float>::quiet_NaN());
  values->SetValue(777, std::numeric_limits<float>::quiet_NaN());
  const auto out = Values(FilterImage(image, 2000.0)->GetPointData()->GetScalars());
  for (size_t i = 0; i < out.size(); ++i)
  {
    if (i == 100 || i == 777)
    {
      EXPECT_TRUE(std::isnan(out[i]));
    }
    else
    {
      ASSERT_TRUE(std::isfinite(out[i])) << i;
      ASSERT_GE(out[i], range[0] - 1e-6);
      ASSERT_LE(out[i], range[1] + 1e-6);
    }
  }
}

TEST(ImageShockAdvectionFilter, BadInputsFailWithAClearError)
{
  vtkNew<vtkFloatArray> values;
  auto image = MakeImage(values);
  vtkNew<vtkStringArray> labels;
  labels->SetName("Labels");
  labels->SetNumberOfValues(image->GetNumberOfPoints());
  image->GetPointData()->AddArray(labels);
  vtkNew<vtkDoubleArray> fieldArray;
  fieldArray->SetName("FieldValues");
  fieldArray->SetNumberOfTuples(image->GetNumberOfPoints());
  image->GetFieldData()->AddArray(fieldArray);

  struct Case
  {
    const char* what;
    std::function<void(vtkImageShockAdvectionFilter*)> setup;
    const char* message;
  };
  const std::vector<Case> cases = {
    { "negative time", [](vtkImageShockAdvectionFilter* f) { f->SetFlowTime(-1.0); }, "FlowTime" },
    { "NaN time",
      [](vtkImageShockAdvectionFilter* f) { f->SetFlowTime(std::numeric_limits<double>::quiet_NaN()); },
      "FlowTime" },
    { "infinite time",
      [](vtkImageShockAdvectionFilter* f) { f->SetFlowTime(std::numeric_limits<double>::infinity()); },
      "FlowTime" },
    { "missing array",
      [](vtkImageShockAdvectionFilter* f) {
        f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "NoSuchArray");
      },
      "No array to process" },
    { "string array",
      [](vtkImageShockAdvectionFilter* f) {
        f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Labels");
      },
      "not a numeric array" },
    { "field data",
      [](vtkImageShockAdvectionFilter* f) {
        f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_NONE, "FieldValues");
      },
      "point or cell data" },
  };
  for (const Case& c : cases)
  {
    vtkNew<vtkImageShockAdvectionFilter> filter;
    MessageLog log(filter);
    filter->SetInputData(image);
    c.setup(filter);
    EXPECT_FALSE(UpdateSucceeds(filter)) << c.what;
    EXPECT_NE(log.Errors.find(c.message), std::string::npos) << c.what << ": " << log.Errors;
  }

  // No scalars at all: the default array selection finds nothing.
  auto bare = vtkSmartPointer<vtkImageData>::New();
  bare->SetDimensions(4, 4, 1);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  MessageLog log(filter);
  filter->SetInputData(bare);
  EXPECT_FALSE(UpdateSucceeds(filter));
  EXPECT_NE(log.Errors.find("No array to process"), std::string::npos);

  // Zero spacing.
  auto flat = vtkSmartPointer<vtkImageData>::New();
  flat->DeepCopy(image);
  flat->SetSpacing(0.5, 0.0, 1.0);
  vtkNew<vtkImageShockAdvectionFilter> spacingFilter;
  MessageLog spacingLog(spacingFilter);
  spacingFilter->SetInputData(flat);
  EXPECT_FALSE(UpdateSucceeds(spacingFilter));
  EXPECT_NE(spacingLog.Errors.find("spacing"), std::string::npos);
}

TEST(ImageShockAdvectionFilter, ReportsProgressAndHonoursAbort)
{
  vtkNew<vtkFloatArray> values;
  auto image = MakeImage(values, 400, 300);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(image);
  filter->SetFlowTime(1000.0);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&progress);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* data) {
    static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(data));
    (void)caller;
  });
  filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
  filter->Update();
  ASSERT_GT(progress.size(), 3u);
  EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));

  // Abort at the first progress report: the run stops and the data is unfiltered.
  vtkNew<vtkImageShockAdvectionFilter> aborting;
  aborting->SetInputData(image);
  aborting->SetFlowTime(1000.0);
  int calls = 0;
  vtkNew<vtkCallbackCommand> onAbort;
  onAbort->SetClientData(&calls);
  onAbort->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    ++*static_cast<int*>(client);
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  aborting->AddObserver(vtkCommand::ProgressEvent, onAbort);
  aborting->Update();
  EXPECT_LE(calls, 3); // the executive's own reports and the filter's first one
  EXPECT_EQ(aborting->GetLastTraceSteps(), 0u);
  EXPECT_EQ(Values(aborting->GetOutput()->GetPointData()->GetScalars()), Values(values));
}

TEST(ImageShockAdvectionFilter, PrintSelfListsTheParameters)
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetFlowModeToComposed();
  filter->SetSamplingToNearest();
  filter->SetTracingModeToStepped();
  std::ostringstream os;
  filter->Print(os);
  for (const char* key : { "FlowTime", "SmoothingPasses", "StepFraction", "FlowMode: Composed",
         "NumberOfFlowUpdates", "Sampling: Nearest", "TracingMode: Stepped", "GenerateFlowArrays",
         "NumberOfThreads", "Method: Advection", "CourantNumber", "MaximumIterations", "LastGhostLevels: 0",
         "LastHaloAttempts: 0", "LastHaloFromSource: false", "LastHaloInLayers: false" })
  {
    EXPECT_NE(os.str().find(key), std::string::npos) << key;
  }
  filter->SetSmoothingPasses(-3);
  EXPECT_EQ(filter->GetSmoothingPasses(), 0);
  filter->SetStepFraction(5.0);
  EXPECT_EQ(filter->GetStepFraction(), 1.0);
  filter->SetCourantNumber(3.0);
  EXPECT_EQ(filter->GetCourantNumber(), 1.0);
  filter->SetCourantNumber(0.0);
  EXPECT_EQ(filter->GetCourantNumber(), 0.01);
  filter->SetMaximumIterations(0);
  EXPECT_EQ(filter->GetMaximumIterations(), 1);
  filter->SetMethod(7);
  EXPECT_EQ(filter->GetMethod(), vtkImageShockAdvectionFilter::PDE);
  filter->SetMethodToAdvection();
  std::ostringstream pdeText;
  filter->SetMethodToPDE();
  filter->Print(pdeText);
  EXPECT_NE(pdeText.str().find("Method: PDE"), std::string::npos);
}

} // namespace
