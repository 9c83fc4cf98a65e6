// Tests of vtkImageShockAdvectionFilter in real VTK pipelines: data handling,
// array types, pass-through, flow arrays, threads, volumes, direction matrices
// and sub-extents (errors, NaN values, progress and abort, PrintSelf:
// TestImageShockAdvectionErrors.cxx; Method PDE: TestImageShockAdvectionPDE.cxx).
#include "TestImageShockAdvection.h"

#include "vtkImageChangeInformation.h"

namespace
{

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

TEST(ImageShockAdvectionFilter, CellDataFlowArraysDoNotDependOnWhereTheExtentStarts)
{
  // The same cells with their extent from 0 and from elsewhere (a piece of a
  // larger image): the flow on the points between cell centres is the same.
  const auto flowOf = [](const int extent[6]) {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetExtent(const_cast<int*>(extent));
    vtkNew<vtkDoubleArray> values;
    values->SetName("CellIntensity");
    values->SetNumberOfTuples(image->GetNumberOfCells());
    for (vtkIdType c = 0; c < image->GetNumberOfCells(); ++c)
    {
      values->SetValue(c, std::sin(0.37 * static_cast<double>(c)) + 0.01 * static_cast<double>(c % 17));
    }
    image->GetCellData()->SetScalars(values);
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputData(image);
    filter->SetFlowTime(16.0);
    filter->SetGenerateFlowArrays(true);
    filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "CellIntensity");
    filter->Update();
    vtkDataArray* flow = filter->GetOutput()->GetPointData()->GetArray("ShockFlow");
    EXPECT_NE(flow, nullptr);
    return flow ? Values(flow) : std::vector<double>();
  };
  const int fromZero[6] = { 0, 9, 0, 7, 0, 6 };
  const int elsewhere[6] = { -4, 5, 11, 18, -30, -24 };
  const auto reference = flowOf(fromZero);
  const auto shifted = flowOf(elsewhere);
  ASSERT_EQ(reference.size(), static_cast<size_t>(10 * 8 * 7 * 3));
  ASSERT_EQ(shifted, reference);
  EXPECT_TRUE(std::any_of(reference.begin(), reference.end(), [](double v) { return v != 0.0; }));
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

TEST(ImageShockAdvectionFilter, StreamedPiecesOfAnAnisotropicImageGetTheWholeImagesResult)
{
  // Serial streaming (pieces without a controller): each piece is filtered
  // with Ghost Levels layers and cropped. Its lengths are in the whole image's
  // mean edge: a piece's own differs when the spacing differs between axes.
  // (A piece has no other process to learn the whole image's range from: a
  // signal of x alone gives every piece of this cut along y the whole range.)
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, 39, 0, 59, 0, 0);
  source->SetMaximum(0.0); // no Gaussian: RTData = XMag sin(XFreq x) + a constant
  source->SetYMag(0.0);
  vtkNew<vtkImageChangeInformation> spaced;
  spaced->SetInputConnection(source->GetOutputPort());
  spaced->SetOutputSpacing(1.0, 1.7, 1.0);
  vtkNew<vtkImageShockAdvectionFilter> whole;
  whole->SetInputConnection(spaced->GetOutputPort());
  whole->SetFlowTime(64.0);
  whole->Update();
  vtkNew<vtkImageData> result; // kept: the pieces' requests execute the pipeline again
  result->DeepCopy(whole->GetOutput());
  vtkNew<vtkImageData> original;
  original->DeepCopy(spaced->GetOutput());
  vtkDataArray* expected = result->GetPointData()->GetArray("RTData");
  vtkDataArray* input = original->GetPointData()->GetArray("RTData");
  double changed = 0.0;
  for (int piece = 0; piece < 3; ++piece)
  {
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputConnection(spaced->GetOutputPort());
    filter->SetFlowTime(64.0);
    ASSERT_TRUE(filter->UpdatePiece(piece, 3, 0));
    vtkImageData* part = filter->GetOutput();
    ASSERT_GT(part->GetNumberOfPoints(), 0);
    ASSERT_LT(part->GetNumberOfPoints(), 40 * 60) << "a piece, not the whole image";
    const int* extent = part->GetExtent();
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        int ijk[3] = { i, j, 0 };
        const vtkIdType w = result->ComputePointId(ijk);
        const double value = part->GetPointData()->GetArray("RTData")->GetTuple1(part->ComputePointId(ijk));
        ASSERT_NEAR(value, expected->GetTuple1(w), 1e-12) << "piece " << piece << " at " << i << ", " << j;
        changed = std::max(changed, std::abs(expected->GetTuple1(w) - input->GetTuple1(w)));
      }
    }
  }
  EXPECT_GT(changed, 0.05) << "the filter changed the samples";
}
