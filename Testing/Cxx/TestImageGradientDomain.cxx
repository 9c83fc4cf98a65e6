// vtkImageShockAdvectionFilter's Domain GRADIENTS (GridGradientDomain.h) in
// real VTK pipelines: equal to the kernel on every storage and association,
// parameters, refusals, abort.
#include "vtkImageShockAdvectionFilter.h"

#include "GridGradientDomain.h"
#include "TestFilterHelpers.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using shock_test::MessageLog;
using shock_test::UpdateSucceeds;
using shock_test::Values;

/// A blurred disc and square on a ramp, in [0, 1], per component a variant.
double Pattern(int i, int j, int k, int c)
{
  double v = 0.0;
  for (int dj = -2; dj <= 2; ++dj)
  {
    for (int di = -2; di <= 2; ++di)
    {
      const double x = i + di, y = j + dj + 0.7 * k;
      const double disc = std::hypot(x - 17.0 - 2 * c, y - 14.0) < 8.0 ? 0.55 : 0.0;
      const double square = (x > 26 && x < 37 && y > 6 && y < 24) ? -0.2 : 0.0;
      v += (0.3 + disc + square + 0.004 * x) / 25.0;
    }
  }
  return v;
}

/// An image of the pattern in `array` (scaled by `scale`), point or cell data.
vtkSmartPointer<vtkImageData> MakeImage(vtkDataArray* array, int nx, int ny, int nz, int components,
  double scale, bool cells = false)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx + (cells ? 1 : 0), ny + (cells ? 1 : 0), nz + (cells && nz > 1 ? 1 : 0));
  image->SetSpacing(0.5, 0.8, 1.1);
  image->SetOrigin(-3.0, 2.0, 1.0);
  array->SetName("Intensity");
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        for (int c = 0; c < components; ++c)
        {
          array->SetComponent((static_cast<vtkIdType>(k) * ny + j) * nx + i, c, std::round(scale * Pattern(i, j, k, c) * 1e6) / 1e6);
        }
      }
    }
  }
  (cells ? static_cast<vtkDataSetAttributes*>(image->GetCellData()) : image->GetPointData())->SetScalars(array);
  return image;
}

/// The kernel on the same samples (as doubles), the shape in the filter's own units.
std::vector<double> Kernel(const std::vector<double>& values, int nx, int ny, int nz, int C, double time,
  double screening)
{
  shock::GridShape shape;
  shape.dimensions = { nx, ny, nz };
  shape.spacing = { 0.5, 0.8, 1.1 };
  shock::AdvectionParameters p;
  p.time = time;
  shock::GradientDomainParameters domain;
  domain.screening = screening;
  std::vector<double> out(values.size());
  const shock::SampleWriter writer = [&out, C](std::int64_t first, std::int64_t count, const double* v) {
    std::copy(v, v + count * C, out.begin() + first * C);
  };
  const shock::Status status = shock::AdvectGridGradients(shape, C, values.data(), writer, p, domain);
  EXPECT_TRUE(status.Ok()) << status.error;
  return out;
}

vtkSmartPointer<vtkImageShockAdvectionFilter> GradientFilter(vtkImageData* input, double time)
{
  auto filter = vtkSmartPointer<vtkImageShockAdvectionFilter>::New();
  filter->SetInputData(input);
  filter->SetFlowTime(time);
  filter->SetDomainToGradients();
  return filter;
}

TEST(ImageGradientDomain, EqualsTheKernelOnAnRGBImageAndAVolume)
{
  // 8-bit RGB: the kernel's result rounded and clamped to 0..255.
  vtkNew<vtkUnsignedCharArray> bytes;
  auto photo = MakeImage(bytes, 48, 36, 1, 3, 255.0);
  const std::vector<double> before = Values(bytes);
  auto filter = GradientFilter(photo, 900.0);
  filter->SetGradientScreening(0.03);
  ASSERT_TRUE(UpdateSucceeds(filter));
  const std::vector<double> got = Values(filter->GetOutput()->GetPointData()->GetScalars());
  std::vector<double> expected = Kernel(before, 48, 36, 1, 3, 900.0, 0.03);
  double changed = 0.0;
  for (size_t s = 0; s < got.size(); ++s)
  {
    EXPECT_EQ(got[s], std::min(255.0, std::max(0.0, std::round(expected[s])))) << "value " << s;
    changed = std::max(changed, std::abs(got[s] - before[s]));
  }
  EXPECT_GE(changed, 10.0) << "the filter should change the photo";
  EXPECT_EQ(Values(bytes), before) << "the input is not modified";
  EXPECT_EQ(filter->GetOutput()->GetPointData()->GetScalars()->GetDataType(), VTK_UNSIGNED_CHAR);

  // A float volume.
  vtkNew<vtkFloatArray> floats;
  auto volume = MakeImage(floats, 20, 16, 9, 1, 3.0);
  auto volumeFilter = GradientFilter(volume, 300.0);
  ASSERT_TRUE(UpdateSucceeds(volumeFilter));
  const std::vector<double> volumeOut = Values(volumeFilter->GetOutput()->GetPointData()->GetScalars());
  const std::vector<double> volumeExpected = Kernel(Values(floats), 20, 16, 9, 1, 300.0, 0.01);
  for (size_t s = 0; s < volumeOut.size(); ++s)
  {
    EXPECT_NEAR(volumeOut[s], volumeExpected[s], 1e-5 * (1.0 + std::abs(volumeExpected[s])));
  }
}

TEST(ImageGradientDomain, CellDataIsFilteredOnTheGridOfCellCentres)
{
  vtkNew<vtkDoubleArray> pointValues;
  auto pointImage = MakeImage(pointValues, 30, 24, 1, 1, 1.0);
  vtkNew<vtkDoubleArray> cellValues;
  auto cellImage = MakeImage(cellValues, 30, 24, 1, 1, 1.0, true);
  auto viaPoints = GradientFilter(pointImage, 500.0);
  auto viaCells = GradientFilter(cellImage, 500.0);
  ASSERT_TRUE(UpdateSucceeds(viaPoints));
  ASSERT_TRUE(UpdateSucceeds(viaCells));
  const auto p = Values(viaPoints->GetOutput()->GetPointData()->GetScalars());
  const auto c = Values(viaCells->GetOutput()->GetCellData()->GetScalars());
  ASSERT_EQ(p.size(), c.size());
  for (size_t s = 0; s < p.size(); ++s)
  {
    EXPECT_NEAR(p[s], c[s], 1e-9);
  }
  const auto input = Values(pointValues);
  double changed = 0.0;
  for (size_t s = 0; s < p.size(); ++s)
  {
    changed = std::max(changed, std::abs(p[s] - input[s]));
  }
  EXPECT_GT(changed, 0.01);
}

TEST(ImageGradientDomain, ParametersDefaultsAndPrintSelf)
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  EXPECT_EQ(filter->GetDomain(), vtkImageShockAdvectionFilter::VALUES);
  EXPECT_EQ(filter->GetGradientScreening(), 0.01);
  filter->SetGradientScreening(0.0);
  EXPECT_EQ(filter->GetGradientScreening(), 1e-6);
  filter->SetGradientScreening(1e9);
  EXPECT_EQ(filter->GetGradientScreening(), 1e6);
  filter->SetDomain(7);
  EXPECT_EQ(filter->GetDomain(), vtkImageShockAdvectionFilter::GRADIENTS);
  std::ostringstream text;
  filter->Print(text);
  EXPECT_NE(text.str().find("Domain: Gradients"), std::string::npos);
  EXPECT_NE(text.str().find("GradientScreening: 1e+06"), std::string::npos);
}

/// Runs `filter`, expecting a failure whose one error says `about`, and an empty output.
void ExpectRefusal(vtkImageShockAdvectionFilter* filter, const std::string& about, int piece = -1)
{
  MessageLog log(filter);
  const int ok = piece < 0 ? filter->GetExecutive()->Update() : filter->UpdatePiece(piece, 2, 0);
  EXPECT_EQ(ok, 0);
  EXPECT_NE(log.Errors.find(about), std::string::npos) << log.Errors;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(ImageGradientDomain, RefusesWhatItCannotDoWithAClearError)
{
  vtkNew<vtkDoubleArray> values;
  auto image = MakeImage(values, 30, 24, 1, 1, 1.0);
  {
    auto filter = GradientFilter(image, 100.0);
    filter->SetMethodToPDE();
    ExpectRefusal(filter, "Domain Gradients works with Method Advection only");
  }
  {
    auto filter = GradientFilter(image, 100.0);
    filter->SetFlowMode(vtkShockAdvectionFilter::COMPOSED);
    ExpectRefusal(filter, "fixed flow only");
  }
  {
    vtkNew<vtkDoubleArray> withNaN;
    auto bad = MakeImage(withNaN, 30, 24, 1, 1, 1.0);
    withNaN->SetValue(100, std::numeric_limits<double>::quiet_NaN());
    ExpectRefusal(GradientFilter(bad, 100.0), "finite value at every sample");
  }
  {
    // A blanked sample (HIDDENPOINT) has no value to integrate.
    vtkNew<vtkDoubleArray> hiddenValues;
    auto hidden = MakeImage(hiddenValues, 30, 24, 1, 1, 1.0);
    hidden->AllocatePointGhostArray();
    hidden->GetPointGhostArray()->SetValue(50, vtkDataSetAttributes::HIDDENPOINT);
    ExpectRefusal(GradientFilter(hidden, 100.0), "blanked");
  }
  {
    // Serial streaming: a piece of the source's image, without a controller.
    vtkNew<vtkRTAnalyticSource> source;
    source->SetWholeExtent(0, 39, 0, 29, 0, 0);
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputConnection(source->GetOutputPort());
    filter->SetFlowTime(64.0);
    filter->SetDomainToGradients();
    ExpectRefusal(filter, "does not run on pieces", 0);
    // The whole image is filtered.
    vtkNew<vtkImageShockAdvectionFilter> whole;
    whole->SetInputConnection(source->GetOutputPort());
    whole->SetFlowTime(64.0);
    whole->SetDomainToGradients();
    EXPECT_TRUE(UpdateSucceeds(whole));
  }
}

TEST(ImageGradientDomain, HonoursAbortDuringTheAdvectionAndTheSolve)
{
  vtkNew<vtkFloatArray> values;
  auto image = MakeImage(values, 300, 200, 1, 3, 1.0);
  // Abort at the first report at or past `at`: 0 (the advection) and 0.8 (the solve).
  for (const double at : { 0.0, 0.8 })
  {
    auto filter = GradientFilter(image, 1000.0);
    struct Abort
    {
      double at;
      double abortedAt = -1.0;
    } abort{ at };
    vtkNew<vtkCallbackCommand> onAbort;
    onAbort->SetClientData(&abort);
    onAbort->SetCallback([](vtkObject* caller, unsigned long, void* client, void* data) {
      auto* a = static_cast<Abort*>(client);
      const double progress = *static_cast<double*>(data);
      if (a->abortedAt < 0.0 && progress > 0.0 && progress >= a->at)
      {
        a->abortedAt = progress;
        static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      }
    });
    filter->AddObserver(vtkCommand::ProgressEvent, onAbort);
    filter->Update();
    EXPECT_GE(abort.abortedAt, at) << "no progress report to abort at from " << at;
    EXPECT_EQ(Values(filter->GetOutput()->GetPointData()->GetScalars()), Values(values)) << "aborted at " << abort.abortedAt;
  }
}

} // namespace
