// Tests of vtkImageShockAdvectionFilter in real VTK pipelines: data handling,
// array types, pass-through, flow arrays, errors, progress and abort.
#include "vtkImageShockAdvectionFilter.h"

#include "vtkExtractVOI.h"
#include "vtkRTAnalyticSource.h"

#include "GridShockAdvection.h"
#include "GridShockPDE.h"
#include "TestFilterHelpers.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkImageEllipsoidSource.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using shock_test::MessageLog;
using shock_test::UpdateSucceeds;
using shock_test::Values;

/// A blurred multi-feature image: a bright disc, a dark square and a ramp.
double Feature(double x, double y)
{
  const double disc = std::hypot(x - 20.0, y - 18.0) < 9.0 ? 1.0 : 0.0;
  const double square = (x > 32 && x < 46 && y > 8 && y < 30) ? -0.25 : 0.0;
  return 0.3 + 0.5 * disc + square + 0.004 * x;
}

/// An image of nx x ny (x nz) samples with a blurred feature pattern in `array`.
vtkSmartPointer<vtkImageData> MakeImage(vtkDataArray* array, int nx = 56, int ny = 40, int nz = 1,
  int components = 1, double scale = 1.0, double offset = 0.0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(0.5, 0.5, 0.5);
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
        // Box-blur the pattern so edges are ramps a few samples wide.
        double v = 0.0;
        for (int dj = -2; dj <= 2; ++dj)
        {
          for (int di = -2; di <= 2; ++di)
          {
            v += Feature(i + di, j + dj + 0.5 * k) / 25.0;
          }
        }
        for (int c = 0; c < components; ++c)
        {
          array->SetComponent((k * ny + j) * nx + i, c, offset + scale * (c == 1 ? 1.0 - v : v));
        }
      }
    }
  }
  image->GetPointData()->SetScalars(array);
  return image;
}

/// Mean squared forward difference along x: a sharpness measure.
double GradientEnergy(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  int dims[3];
  image->GetDimensions(dims);
  double sum = 0.0;
  for (vtkIdType s = 0; s + 1 < a->GetNumberOfTuples(); ++s)
  {
    if ((s + 1) % dims[0] != 0)
    {
      const double d = a->GetComponent(s + 1, 0) - a->GetComponent(s, 0);
      sum += d * d;
    }
  }
  return sum / static_cast<double>(a->GetNumberOfTuples());
}

vtkSmartPointer<vtkImageData> FilterImage(vtkImageData* input, double time, int threads = 0)
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(input);
  filter->SetFlowTime(time);
  filter->SetNumberOfThreads(threads);
  filter->Update();
  return filter->GetOutput();
}

TEST(ImageShockAdvectionFilter, WorksInAPipelineAndKeepsTheImageStructure)
{
  vtkNew<vtkImageEllipsoidSource> source;
  source->SetWholeExtent(0, 63, 0, 47, 0, 0);
  source->SetCenter(30, 22, 0);
  source->SetRadius(14, 9, 1);
  source->SetInValue(220);
  source->SetOutValue(30);
  source->SetOutputScalarTypeToUnsignedChar();
  vtkNew<vtkImageGaussianSmooth> blur;
  blur->SetInputConnection(source->GetOutputPort());
  blur->SetStandardDeviations(2.0, 2.0, 0.0);
  blur->SetDimensionality(2);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputConnection(blur->GetOutputPort());
  filter->SetFlowTime(2000.0);
  filter->Update();

  vtkImageData* in = blur->GetOutput();
  vtkImageData* out = filter->GetOutput();
  int inExtent[6], outExtent[6];
  in->GetExtent(inExtent);
  out->GetExtent(outExtent);
  for (int a = 0; a < 6; ++a)
  {
    EXPECT_EQ(inExtent[a], outExtent[a]);
  }
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_EQ(in->GetSpacing()[a], out->GetSpacing()[a]);
    EXPECT_EQ(in->GetOrigin()[a], out->GetOrigin()[a]);
  }
  vtkDataArray* scalars = out->GetPointData()->GetScalars();
  ASSERT_NE(scalars, nullptr);
  EXPECT_STREQ(scalars->GetName(), in->GetPointData()->GetScalars()->GetName());
  EXPECT_EQ(scalars->GetDataType(), VTK_UNSIGNED_CHAR);
  double inRange[2], outRange[2];
  in->GetPointData()->GetScalars()->GetRange(inRange);
  scalars->GetRange(outRange);
  EXPECT_GE(outRange[0], inRange[0]);
  EXPECT_LE(outRange[1], inRange[1]);
  const char* name = scalars->GetName();
  EXPECT_GT(GradientEnergy(out, name), 1.5 * GradientEnergy(in, name));
  EXPECT_GT(filter->GetLastTraceSteps(), 0u);
}

TEST(ImageShockAdvectionFilter, PngRoundTrip)
{
  const std::string path = ::testing::TempDir() + "shock_roundtrip.png";
  vtkNew<vtkUnsignedCharArray> rgb;
  auto image = MakeImage(rgb, 56, 40, 1, 3, 255.0 * 0.8, 20.0);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->Write();
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputConnection(reader->GetOutputPort());
  filter->SetFlowTime(500.0);
  filter->Update();
  vtkDataArray* out = filter->GetOutput()->GetPointData()->GetScalars();
  ASSERT_NE(out, nullptr);
  EXPECT_EQ(out->GetNumberOfComponents(), 3);
  EXPECT_EQ(out->GetDataType(), VTK_UNSIGNED_CHAR);
  EXPECT_GT(GradientEnergy(filter->GetOutput(), out->GetName()),
    GradientEnergy(reader->GetOutput(), out->GetName()));
  std::remove(path.c_str());
}

TEST(ImageShockAdvectionFilter, EveryNumericTypeKeepsItsTypeAndMatchesDouble)
{
  vtkNew<vtkDoubleArray> reference;
  auto referenceOut = FilterImage(MakeImage(reference, 56, 40, 1, 1, 200.0, 10.0), 300.0);
  const auto expected = Values(referenceOut->GetPointData()->GetArray("Intensity"));
  std::vector<vtkSmartPointer<vtkDataArray>> arrays = { vtkSmartPointer<vtkUnsignedCharArray>::New(),
    vtkSmartPointer<vtkShortArray>::New(), vtkSmartPointer<vtkUnsignedShortArray>::New(),
    vtkSmartPointer<vtkIntArray>::New(), vtkSmartPointer<vtkFloatArray>::New() };
  for (auto& array : arrays)
  {
    // Integer inputs are the rounded reference input; outputs are rounded again.
    auto image = MakeImage(array, 56, 40, 1, 1, 200.0, 10.0);
    auto out = FilterImage(image, 300.0);
    vtkDataArray* result = out->GetPointData()->GetArray("Intensity");
    ASSERT_NE(result, nullptr);
    EXPECT_EQ(result->GetDataType(), array->GetDataType());
    const auto values = Values(result);
    double mean = 0.0;
    for (size_t i = 0; i < values.size(); ++i)
    {
      if (array->GetDataType() != VTK_FLOAT)
      {
        ASSERT_EQ(values[i], std::round(values[i]));
      }
      mean += std::abs(values[i] - expected[i]);
    }
    EXPECT_LT(mean / static_cast<double>(values.size()), 1.0) << array->GetClassName();
  }
}

TEST(ImageShockAdvectionFilter, EveryStorageIsReadAndWrittenAsTheKernelComputesIt)
{
  // The filter reads float, double and unsigned char arrays in place and other
  // types through a copy, and writes the results straight into an array of the input's type:
  // for every storage and flow mode, the output is the kernel's double result on
  // the same values, rounded and clamped for integers, and the input is untouched.
  std::vector<vtkSmartPointer<vtkDataArray>> arrays = { vtkSmartPointer<vtkUnsignedCharArray>::New(),
    vtkSmartPointer<vtkShortArray>::New(), vtkSmartPointer<vtkIntArray>::New(),
    vtkSmartPointer<vtkFloatArray>::New(), vtkSmartPointer<vtkDoubleArray>::New(),
    vtkSmartPointer<vtkSOADataArrayTemplate<float>>::New(),
    vtkSmartPointer<vtkSOADataArrayTemplate<unsigned char>>::New() };
  for (int mode : { vtkShockAdvectionFilter::FIXED, vtkShockAdvectionFilter::COMPOSED,
         vtkShockAdvectionFilter::NAIVE })
  {
    for (auto& array : arrays)
    {
      auto image = MakeImage(array, 33, 27, 1, 2, 180.0, 20.0);
      const auto samples = Values(array);
      vtkNew<vtkImageShockAdvectionFilter> filter;
      filter->SetInputData(image);
      filter->SetFlowTime(500.0);
      filter->SetFlowMode(mode);
      filter->SetNumberOfFlowUpdates(3);
      ASSERT_TRUE(UpdateSucceeds(filter));

      shock::GridShape shape;
      shape.dimensions = { 33, 27, 1 };
      shape.spacing = { 0.5, 0.5, 0.5 };
      shock::AdvectionParameters p;
      p.time = 500.0;
      p.flowMode = static_cast<shock::FlowMode>(mode);
      p.flowUpdates = 3;
      std::vector<double> expected(samples.size());
      ASSERT_TRUE(shock::AdvectGridSignal(shape, 2, samples.data(), expected.data(), p).Ok());
      const bool integral = array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
      for (double& v : expected)
      {
        v = integral ? std::round(v) : (array->GetDataType() == VTK_FLOAT ? static_cast<float>(v) : v);
      }
      vtkDataArray* output = filter->GetOutput()->GetPointData()->GetArray("Intensity");
      ASSERT_NE(output, nullptr);
      EXPECT_STREQ(output->GetClassName(), array->GetClassName());
      EXPECT_EQ(output->GetNumberOfComponents(), 2);
      EXPECT_EQ(Values(output), expected) << array->GetClassName() << " mode " << mode;
      EXPECT_NE(Values(output), samples) << array->GetClassName(); // something changed
      EXPECT_EQ(Values(array), samples); // the input is untouched
    }
  }
}

TEST(ImageShockAdvectionFilter, EightBitAndUnitFloatGiveTheSameResult)
{
  // The invariance: uchar 0-255 and float 0-1 versions of one picture.
  vtkNew<vtkFloatArray> unit;
  auto floatImage = MakeImage(unit, 56, 40, 1, 1, 1.0, 0.0);
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetName("Intensity");
  bytes->SetNumberOfTuples(unit->GetNumberOfTuples());
  for (vtkIdType i = 0; i < unit->GetNumberOfTuples(); ++i)
  {
    const double v = std::round(255.0 * unit->GetValue(i));
    bytes->SetValue(i, static_cast<unsigned char>(v));
    unit->SetValue(i, static_cast<float>(v / 255.0)); // the same quantised picture
  }
  auto byteImage = vtkSmartPointer<vtkImageData>::New();
  byteImage->CopyStructure(floatImage);
  byteImage->GetPointData()->SetScalars(bytes);
  const auto f = Values(FilterImage(floatImage, 400.0)->GetPointData()->GetScalars());
  const auto b = Values(FilterImage(byteImage, 400.0)->GetPointData()->GetScalars());
  // Equal up to the final rounding, except where float32 storage of the unit
  // image flips a discrete tracing decision (a handful of samples).
  size_t beyondRounding = 0;
  for (size_t i = 0; i < f.size(); ++i)
  {
    beyondRounding += std::abs(b[i] - 255.0 * f[i]) > 0.5 + 1e-3 ? 1 : 0;
    ASSERT_NEAR(b[i], 255.0 * f[i], 3.0);
  }
  EXPECT_LT(beyondRounding, f.size() / 200) << beyondRounding << " of " << f.size();
}

TEST(ImageShockAdvectionFilter, OtherArraysPassThroughAndTheInputIsUntouched)
{
  vtkNew<vtkFloatArray> intensity;
  auto image = MakeImage(intensity);
  vtkNew<vtkDoubleArray> other;
  other->SetName("Other");
  other->SetNumberOfTuples(image->GetNumberOfPoints());
  other->Fill(7.0);
  image->GetPointData()->AddArray(other);
  vtkNew<vtkIntArray> cellIds;
  cellIds->SetName("CellIds");
  cellIds->SetNumberOfTuples(image->GetNumberOfCells());
  cellIds->Fill(3);
  image->GetCellData()->AddArray(cellIds);
  const auto before = Values(intensity);
  const vtkMTimeType mtime = intensity->GetMTime();

  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(image);
  filter->SetFlowTime(300.0);
  filter->Update();
  vtkImageData* out = filter->GetOutput();
  EXPECT_EQ(Values(intensity), before);
  EXPECT_EQ(intensity->GetMTime(), mtime);
  EXPECT_EQ(out->GetPointData()->GetArray("Other"), other.GetPointer());
  EXPECT_EQ(out->GetCellData()->GetArray("CellIds"), cellIds.GetPointer());
  EXPECT_NE(out->GetPointData()->GetScalars(), intensity.GetPointer());
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "Intensity");
  EXPECT_NE(Values(out->GetPointData()->GetScalars()), before);
}

TEST(ImageShockAdvectionFilter, SelectedNonScalarArrayIsFiltered)
{
  vtkNew<vtkFloatArray> intensity;
  auto image = MakeImage(intensity);
  vtkNew<vtkFloatArray> second;
  MakeImage(second);
  second->SetName("Second");
  image->GetPointData()->AddArray(second);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(image);
  filter->SetFlowTime(300.0);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Second");
  filter->Update();
  vtkImageData* out = filter->GetOutput();
  EXPECT_EQ(out->GetPointData()->GetScalars(), intensity.GetPointer());
  EXPECT_NE(out->GetPointData()->GetArray("Second"), second.GetPointer());
  EXPECT_EQ(out->GetPointData()->GetArray("Second")->GetNumberOfTuples(), second->GetNumberOfTuples());
}

TEST(ImageShockAdvectionFilter, CellDataIsFilteredOnTheGridOfCellCentres)
{
  // Cell data of an (n+1) x (m+1) image equals point data of an n x m image.
  vtkNew<vtkDoubleArray> pointValues;
  auto pointImage = MakeImage(pointValues, 40, 30);
  auto cellImage = vtkSmartPointer<vtkImageData>::New();
  cellImage->SetDimensions(41, 31, 1);
  cellImage->SetSpacing(0.5, 0.5, 0.5);
  vtkNew<vtkDoubleArray> cellValues;
  cellValues->DeepCopy(pointValues);
  cellValues->SetName("CellIntensity");
  cellImage->GetCellData()->SetScalars(cellValues);

  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(cellImage);
  filter->SetFlowTime(300.0);
  filter->SetGenerateFlowArrays(true);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "CellIntensity");
  filter->Update();
  const auto viaCells = Values(filter->GetOutput()->GetCellData()->GetArray("CellIntensity"));
  const auto viaPoints = Values(FilterImage(pointImage, 300.0)->GetPointData()->GetScalars());
  ASSERT_EQ(viaCells.size(), viaPoints.size());
  for (size_t i = 0; i < viaCells.size(); ++i)
  {
    ASSERT_NEAR(viaCells[i], viaPoints[i], 1e-9);
  }
  EXPECT_NE(filter->GetOutput()->GetCellData()->GetArray("ShockPotential"), nullptr);
  vtkDataArray* flow = filter->GetOutput()->GetPointData()->GetArray("ShockFlow");
  ASSERT_NE(flow, nullptr);
  EXPECT_EQ(flow->GetNumberOfTuples(), cellImage->GetNumberOfPoints());
}

TEST(ImageShockAdvectionFilter, FlowArraysAreInWorldAxes)
{
  vtkNew<vtkDoubleArray> values;
  auto image = MakeImage(values);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(image);
  filter->SetGenerateFlowArrays(true);
  filter->SetFlowTime(10.0);
  filter->Update();
  vtkSmartPointer<vtkDataArray> potential = filter->GetOutput()->GetPointData()->GetArray("ShockPotential");
  vtkSmartPointer<vtkDataArray> flow = filter->GetOutput()->GetCellData()->GetArray("ShockFlow");
  ASSERT_NE(potential, nullptr);
  ASSERT_NE(flow, nullptr);
  EXPECT_EQ(potential->GetNumberOfTuples(), image->GetNumberOfPoints());
  EXPECT_EQ(flow->GetNumberOfTuples(), image->GetNumberOfCells());
  EXPECT_EQ(flow->GetNumberOfComponents(), 3);
  EXPECT_GE(potential->GetRange()[0], 0.0);

  // Rotate the image by 90 degrees about z: the flow rotates with it.
  auto rotated = vtkSmartPointer<vtkImageData>::New();
  rotated->DeepCopy(image);
  const double direction[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
  rotated->SetDirectionMatrix(direction);
  filter->SetInputData(rotated);
  filter->Update();
  vtkDataArray* rotatedFlow = filter->GetOutput()->GetCellData()->GetArray("ShockFlow");
  double maxDiff = 0.0, maxNorm = 0.0;
  for (vtkIdType c = 0; c < flow->GetNumberOfTuples(); ++c)
  {
    const double* u = flow->GetTuple3(c);
    const double expected[2] = { -u[1], u[0] };
    const double* r = rotatedFlow->GetTuple3(c);
    maxDiff = std::max({ maxDiff, std::abs(r[0] - expected[0]), std::abs(r[1] - expected[1]), std::abs(r[2]) });
    maxNorm = std::max(maxNorm, std::hypot(u[0], u[1]));
  }
  EXPECT_GT(maxNorm, 0.0);
  EXPECT_LT(maxDiff, 1e-12 * std::max(1.0, maxNorm));
}

TEST(ImageShockAdvectionFilter, ThreadCountDoesNotChangeTheResult)
{
  vtkNew<vtkFloatArray> rgb;
  auto image = MakeImage(rgb, 80, 64, 1, 3);
  EXPECT_EQ(Values(FilterImage(image, 500.0, 1)->GetPointData()->GetScalars()),
    Values(FilterImage(image, 500.0, 2)->GetPointData()->GetScalars()));
}

TEST(ImageShockAdvectionFilter, VolumesAndRowsAreFiltered)
{
  vtkNew<vtkFloatArray> volume;
  auto image = MakeImage(volume, 24, 20, 12);
  auto out = FilterImage(image, 1000.0);
  EXPECT_GT(GradientEnergy(out, "Intensity"), GradientEnergy(image, "Intensity"));

  vtkNew<vtkFloatArray> row;
  auto line = MakeImage(row, 1, 60);
  auto filteredLine = FilterImage(line, 1000.0);
  EXPECT_EQ(filteredLine->GetNumberOfPoints(), 60);
  double range[2];
  filteredLine->GetPointData()->GetScalars()->GetRange(range);
  EXPECT_GE(range[0], row->GetRange()[0]);
  EXPECT_LE(range[1], row->GetRange()[1]);
}

TEST(ImageShockAdvectionFilter, SingleSampleAndEmptyImage)
{
  auto single = vtkSmartPointer<vtkImageData>::New();
  single->SetDimensions(1, 1, 1);
  vtkNew<vtkDoubleArray> one;
  one->SetName("v");
  one->InsertNextValue(4.25);
  single->GetPointData()->SetScalars(one);
  EXPECT_EQ(FilterImage(single, 10.0)->GetPointData()->GetScalars()->GetComponent(0, 0), 4.25);

  auto empty = vtkSmartPointer<vtkImageData>::New();
  vtkNew<vtkImageShockAdvectionFilter> filter;
  MessageLog log(filter);
  filter->SetInputData(empty);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(log.Warnings.find("empty"), std::string::npos);
  EXPECT_TRUE(log.Errors.empty());
}

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

// --- Method PDE: the Osher-Rudin baseline through the same filter -------------

TEST(ImageShockAdvectionFilter, PDEMethodSharpensLikeTheAdvection)
{
  // The same blurred ellipse as above, through a real pipeline, by both methods
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
         "NumberOfThreads", "Method: Advection", "CourantNumber", "MaximumIterations" })
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

// A direction matrix that scales an axis is that axis's spacing: diag(4,1,1)
// gives what spacing (4,1,1) gives, and a rotated-and-scaled image what the
// same scaled image gives (the flow arrays rotate). A singular, non-finite or
// shearing matrix is refused with a message naming it.
TEST(ImageShockAdvectionFilter, DirectionMatricesScaleAndRotate)
{
  vtkNew<vtkDoubleArray> values;
  auto image = MakeImage(values, 48, 36);
  auto asSpacing = vtkSmartPointer<vtkImageData>::New();
  asSpacing->DeepCopy(image);
  asSpacing->SetSpacing(4.0, 1.0, 1.0);
  const auto expected = Values(FilterImage(asSpacing, 300.0)->GetPointData()->GetScalars());
  const auto identity = Values(FilterImage(image, 300.0)->GetPointData()->GetScalars());

  auto scaled = vtkSmartPointer<vtkImageData>::New();
  scaled->DeepCopy(image);
  const double diag[9] = { 4, 0, 0, 0, 1, 0, 0, 0, 1 };
  scaled->SetDirectionMatrix(diag);
  const auto viaDirection = Values(FilterImage(scaled, 300.0)->GetPointData()->GetScalars());
  EXPECT_EQ(viaDirection, expected);
  EXPECT_NE(viaDirection, identity) << "the scale changed the result";

  auto rotated = vtkSmartPointer<vtkImageData>::New();
  rotated->DeepCopy(image);
  const double rotatedAndScaled[9] = { 0, -1, 0, 4, 0, 0, 0, 0, 1 }; // x axis: 4 along world y
  rotated->SetDirectionMatrix(rotatedAndScaled);
  EXPECT_EQ(Values(FilterImage(rotated, 300.0)->GetPointData()->GetScalars()), expected);

  const double singular[9] = { 1, 0, 0, 0, 0, 0, 0, 0, 1 };
  const double notFinite[9] = { 1, 0, 0, 0, std::nan(""), 0, 0, 0, 1 };
  const double shear[9] = { 1, 0.5, 0, 0, 1, 0, 0, 0, 1 };
  const std::pair<const double*, const char*> refused[] = { { singular, "singular" },
    { notFinite, "non-finite" }, { shear, "shears the axes" } };
  for (const auto& matrix : refused)
  {
    auto bad = vtkSmartPointer<vtkImageData>::New();
    bad->DeepCopy(image);
    bad->SetDirectionMatrix(matrix.first);
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputData(bad);
    MessageLog log(filter);
    EXPECT_FALSE(UpdateSucceeds(filter)) << matrix.second;
    EXPECT_NE(log.Errors.find(matrix.second), std::string::npos) << log.Errors;
  }
}

// A sub-extent request downstream (vtkExtractVOI) gets the whole image's
// result there: the same data range normalises it, and flow lines start
// outside the sub-extent too.
TEST(ImageShockAdvectionFilter, ASubExtentRequestGetsTheWholeImagesResult)
{
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, 63, 0, 47, 0, 0);
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputConnection(source->GetOutputPort());
  filter->SetFlowTime(256.0);
  vtkNew<vtkExtractVOI> voi;
  voi->SetInputConnection(filter->GetOutputPort());
  voi->SetVOI(10, 20, 30, 45, 0, 0);
  voi->Update();
  vtkNew<vtkImageShockAdvectionFilter> whole;
  whole->SetInputConnection(source->GetOutputPort());
  whole->SetFlowTime(256.0);
  whole->Update();
  vtkImageData* part = voi->GetOutput();
  vtkDataArray* partValues = part->GetPointData()->GetScalars();
  vtkDataArray* wholeValues = whole->GetOutput()->GetPointData()->GetScalars();
  vtkDataArray* input = source->GetOutput()->GetPointData()->GetScalars();
  ASSERT_EQ(partValues->GetNumberOfTuples(), 11 * 16);
  double changed = 0.0;
  for (int j = 30; j <= 45; ++j)
  {
    for (int i = 10; i <= 20; ++i)
    {
      const vtkIdType w = whole->GetOutput()->ComputePointId(std::array<int, 3>{ i, j, 0 }.data());
      const vtkIdType p = part->ComputePointId(std::array<int, 3>{ i, j, 0 }.data());
      ASSERT_EQ(partValues->GetTuple1(p), wholeValues->GetTuple1(w)) << i << ", " << j;
      changed = std::max(changed, std::abs(wholeValues->GetTuple1(w) - input->GetTuple1(w)));
    }
  }
  EXPECT_GT(changed, 0.1) << "the filter changed those samples";
}
