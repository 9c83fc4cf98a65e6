// The picture and volume parts of the "demo" subcommand: synthetic data,
// blurred, sharpened with vtkImageShockAdvectionFilter, written with
// side-by-side comparisons.
#include "CliFiles.h"
#include "CliFilters.h"
#include "Demo.h"

#include "vtkFloatArray.h"
#include "vtkImageAppend.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <vector>

namespace shockcli
{
namespace
{

/// Colour of the synthetic picture at pixel (x, y): gradient background and shapes, painted in order.
Rgb DemoPictureColour(int x, int y, int width, int height)
{
  const double fx = static_cast<double>(x) / (width - 1);
  const double fy = static_cast<double>(y) / (height - 1);
  Rgb colour = { 40 + 150 * fy, 70 + 120 * fy + 30 * fx, 140 + 90 * fy }; // blue-grey sky gradient

  const auto inDisk = [&](double cx, double cy, double r)
  { return (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r; };

  // Thin stripes (4 px black/white) at the lower left: the hardest case after blurring.
  if (x >= 30 && x < 190 && y >= 30 && y < 130)
  {
    colour = ((x - 30) / 4) % 2 == 0 ? Rgb{ 20, 20, 20 } : Rgb{ 235, 235, 235 };
  }
  // Wider stripes (10 px) above them.
  if (x >= 30 && x < 190 && y >= 150 && y < 210)
  {
    colour = ((x - 30) / 10) % 2 == 0 ? Rgb{ 30, 30, 90 } : Rgb{ 250, 240, 200 };
  }
  // Red disk.
  if (inDisk(120, 290, 65))
  {
    colour = { 220, 40, 35 };
  }
  // Green rectangle.
  if (x >= 230 && x < 370 && y >= 40 && y < 170)
  {
    colour = { 40, 170, 70 };
  }
  // Orange ring.
  if (inDisk(400, 270, 80) && !inDisk(400, 270, 52))
  {
    colour = { 245, 150, 20 };
  }
  // Purple diamond inside the ring.
  if (std::abs(x - 400) + std::abs(y - 270) < 30)
  {
    colour = { 150, 40, 170 };
  }
  // Yellow bar crossing the rectangle.
  if (x >= 200 && x < 480 && y >= 95 && y < 115)
  {
    colour = { 250, 225, 40 };
  }
  return colour;
}

/// An image of the given size whose point scalars 'array' are filled by 'value(x, y, z, component)'.
vtkSmartPointer<vtkImageData> MakeImage(const std::array<int, 3>& dims, int components,
  const std::string& arrayName, const std::function<double(int, int, int, int)>& value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims.data());
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName(arrayName.c_str());
  scalars->SetNumberOfComponents(components);
  scalars->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x, ++id)
      {
        for (int c = 0; c < components; ++c)
        {
          scalars->SetTypedComponent(id, c, static_cast<float>(value(x, y, z, c)));
        }
      }
    }
  }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

/// Gaussian blur with standard deviation 'sigma' samples along the image's first 'dimensionality' axes.
vtkSmartPointer<vtkImageData> GaussianBlur(vtkImageData* image, int dimensionality, double sigma)
{
  vtkNew<vtkImageGaussianSmooth> blur;
  blur->SetInputData(image);
  blur->SetDimensionality(dimensionality);
  blur->SetStandardDeviations(sigma, sigma, sigma);
  blur->SetRadiusFactors(3.0, 3.0, 3.0);
  UpdateOrThrow(blur, "Gaussian blur failed");
  auto blurred = vtkSmartPointer<vtkImageData>::New();
  blurred->ShallowCopy(blur->GetOutput());
  blurred->GetPointData()->GetScalars()->SetName(image->GetPointData()->GetScalars()->GetName());
  return blurred;
}

/// Adds Gaussian noise of standard deviation 'sigma' to every value (fixed seed: reproducible).
void AddNoise(vtkDataArray* values, double sigma, unsigned seed)
{
  std::mt19937 generator(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const int components = values->GetNumberOfComponents();
  for (vtkIdType t = 0; t < values->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < components; ++c)
    {
      values->SetComponent(t, c, values->GetComponent(t, c) + noise(generator));
    }
  }
}

/// Replaces the point scalars of 'image' by their rounded, clamped unsigned char version.
void QuantizeScalars(vtkImageData* image, double scale)
{
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  image->GetPointData()->SetScalars(shockio::QuantizeToBytes(scalars, scale));
}

/**
 * Sharpness figure: the root mean square over the interior samples of |grad L|,
 * L the luminance (Rec. 601 weights for 3 or more components, else the first
 * component), by central differences in sample units. (The mean of |grad L|
 * would not do: across a monotone edge it sums to the edge height however
 * sharp the edge is; the mean square grows as the edge narrows.)
 */
double RmsLuminanceGradient(vtkImageData* image, const std::string& arrayName)
{
  vtkDataArray* array = image->GetPointData()->GetArray(arrayName.c_str());
  int dims[3];
  image->GetDimensions(dims);
  const vtkIdType count = image->GetNumberOfPoints();
  std::vector<double> luminance(static_cast<std::size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    luminance[i] = array->GetNumberOfComponents() >= 3
      ? 0.299 * array->GetComponent(i, 0) + 0.587 * array->GetComponent(i, 1) +
        0.114 * array->GetComponent(i, 2)
      : array->GetComponent(i, 0);
  }
  const std::array<vtkIdType, 3> stride = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const auto interior = [&](int axis, int index)
  { return dims[axis] == 1 || (index > 0 && index < dims[axis] - 1); };
  double sum = 0.0;
  vtkIdType samples = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        if (!interior(0, i) || !interior(1, j) || !interior(2, k))
        {
          continue;
        }
        const vtkIdType id = i + j * stride[1] + k * stride[2];
        for (int a = 0; a < 3; ++a)
        {
          if (dims[a] > 1)
          {
            const double g = 0.5 * (luminance[id + stride[a]] - luminance[id - stride[a]]);
            sum += g * g;
          }
        }
        ++samples;
      }
    }
  }
  return samples > 0 ? std::sqrt(sum / static_cast<double>(samples)) : 0.0;
}

/// A 2D image of the given size filled with one byte value, for gaps between pictures.
vtkSmartPointer<vtkImageData> MakeFilledBytes(
  int width, int height, int components, const std::string& arrayName, unsigned char value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetName(arrayName.c_str());
  bytes->SetNumberOfComponents(components);
  bytes->SetNumberOfTuples(image->GetNumberOfPoints());
  bytes->FillValue(value);
  image->GetPointData()->SetScalars(bytes);
  return image;
}

/**
 * Two 2D byte images of the same height side by side along X, separated by a
 * white gap of 'gap' pixels. Their point scalars must have the same name and
 * number of components; only the scalars are kept.
 */
vtkSmartPointer<vtkImageData> SideBySide(vtkImageData* left, vtkImageData* right, int gap)
{
  vtkDataArray* scalars = left->GetPointData()->GetScalars();
  const std::string name = scalars->GetName() ? scalars->GetName() : "Scalars";
  int dims[3];
  left->GetDimensions(dims);
  vtkSmartPointer<vtkImageData> whiteGap =
    MakeFilledBytes(gap, dims[1], scalars->GetNumberOfComponents(), name, 255);
  vtkNew<vtkImageAppend> append;
  append->SetAppendAxis(0);
  append->PreserveExtentsOff();
  for (vtkImageData* piece : { left, whiteGap.Get(), right })
  {
    // Only the scalars, so that the pieces append array by array.
    auto scalarsOnly = vtkSmartPointer<vtkImageData>::New();
    scalarsOnly->CopyStructure(piece);
    scalarsOnly->GetPointData()->SetScalars(piece->GetPointData()->GetScalars());
    append->AddInputData(scalarsOnly);
  }
  UpdateOrThrow(append, "cannot put images side by side");
  auto result = vtkSmartPointer<vtkImageData>::New();
  result->ShallowCopy(append->GetOutput());
  return result;
}

/**
 * The middle z-slice of a one-component volume as a 2D unsigned char image:
 * values times 'scale', pixels enlarged 'zoom' times (nearest neighbour).
 */
vtkSmartPointer<vtkImageData> MiddleSliceAsBytes(
  vtkImageData* volume, const std::string& arrayName, double scale, int zoom)
{
  int dims[3];
  volume->GetDimensions(dims);
  vtkDataArray* values = volume->GetPointData()->GetArray(arrayName.c_str());
  const vtkIdType sliceStart = static_cast<vtkIdType>(dims[0]) * dims[1] * (dims[2] / 2);
  vtkSmartPointer<vtkImageData> slice =
    MakeImage({ dims[0] * zoom, dims[1] * zoom, 1 }, 1, arrayName, [&](int x, int y, int, int)
      { return values->GetComponent(sliceStart + x / zoom + static_cast<vtkIdType>(dims[0]) * (y / zoom), 0); });
  QuantizeScalars(slice, scale);
  return slice;
}

/// Writes 'image' to 'directory'/'name' and tells so on stderr.
void WriteDemoFile(vtkImageData* image, const std::filesystem::path& directory, const std::string& name,
  const std::string& arrayName, const std::string& description)
{
  const std::string path = (directory / name).string();
  WriteImageFile(image, path, arrayName);
  std::cerr << "demo: wrote " << path << " (" << description << ")\n";
}

/// "0.123 s (flow 0.010 s, advection 0.113 s)"
std::string RunTimesText(const FilterRun& run)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << run.totalSeconds << " s (flow " << run.flowSeconds
       << " s, advection " << run.advectionSeconds << " s)";
  return text.str();
}

} // namespace

/// Creates 'directory' (and parents) if missing.
void CreateDirectory(const std::filesystem::path& directory)
{
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory))
  {
    throw CliError("cannot create directory '" + directory.string() + "'" +
      (error ? ": " + error.message() : ""));
  }
}

/// The 2D part of the demo: picture, sharpened pictures for several t, before/after.
void RunPictureDemo(const std::filesystem::path& directory, const ShockOptions& common)
{
  const std::string arrayName = "Picture";
  const int width = 512;
  const int height = 384;
  const double blurSigma = 3.0;
  const double noiseSigma = 2.0;

  vtkSmartPointer<vtkImageData> sharp = MakeImage({ width, height, 1 }, 3, arrayName,
    [&](int x, int y, int, int c) { return DemoPictureColour(x, y, width, height)[c]; });
  vtkSmartPointer<vtkImageData> picture = GaussianBlur(sharp, 2, blurSigma);
  AddNoise(picture->GetPointData()->GetScalars(), noiseSigma, 2015u);
  QuantizeScalars(picture, 1.0);
  WriteDemoFile(picture, directory, "input.png", arrayName,
    "512x384 RGB, Gaussian blur sigma 3 px, noise sigma 2");

  const double inputSharpness = RmsLuminanceGradient(picture, arrayName);
  std::cerr << "demo: sharpness (RMS luminance gradient) of the input: " << NumberText(inputSharpness)
            << '\n';
  double previousSharpness = inputSharpness;
  bool increasing = true;
  vtkSmartPointer<vtkImageData> shown;
  for (const double t : PictureDemoTimes)
  {
    ShockOptions options = common;
    options.time = t;
    options.flowMode = vtkShockAdvectionFilter::FIXED;
    const FilterRun run = RunImageFilter(picture, arrayName, options);
    const std::string name = "sharpened_t" + NumberText(t) + ".png";
    const double sharpness = RmsLuminanceGradient(run.output, arrayName);
    increasing = increasing && sharpness > previousSharpness;
    previousSharpness = sharpness;
    WriteDemoFile(run.output, directory, name, arrayName,
      "t=" + NumberText(t) + ", fixed flow: " + RunTimesText(run));
    std::cerr << "demo: sharpness at t=" << NumberText(t) << ": " << NumberText(sharpness) << " (input "
              << NumberText(inputSharpness) << ")\n";
    if (t == PictureDemoShownTime)
    {
      shown = run.output;
    }
  }
  std::cerr << "demo: sharpness " << (increasing ? "increases" : "does NOT increase")
            << " with t\n";
  WriteDemoFile(SideBySide(picture, shown, 8), directory, "before_after.png", arrayName,
    "input | t=" + NumberText(PictureDemoShownTime));
}

namespace
{

/// Value of the synthetic volume at voxel (x, y, z): spheres and a box, 0..1.
double DemoVolumeValue(int x, int y, int z)
{
  const auto inBall = [&](double cx, double cy, double cz, double r)
  { return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) <= r * r; };
  if (inBall(22, 24, 32, 14))
  {
    return 1.0;
  }
  if (inBall(46, 44, 30, 10))
  {
    return 0.75;
  }
  if (inBall(18, 50, 36, 6))
  {
    return 0.9;
  }
  if (x >= 34 && x < 56 && y >= 8 && y < 24 && z >= 16 && z < 48)
  {
    return 0.5;
  }
  return 0.05;
}

} // namespace

/// The 3D part of the demo: blurred volume, sharpened at VolumeDemoTime, middle slices side by side.
void RunVolumeDemo(const std::filesystem::path& directory, const ShockOptions& common)
{
  const std::string arrayName = "Density";
  const int size = 64;
  vtkSmartPointer<vtkImageData> sharp = MakeImage({ size, size, size }, 1, arrayName,
    [](int x, int y, int z, int) { return DemoVolumeValue(x, y, z); });
  vtkSmartPointer<vtkImageData> volume = GaussianBlur(sharp, 3, 2.0);
  WriteDemoFile(volume, directory, "volume_input.vti", arrayName,
    "64^3 float, 3 spheres and a box, Gaussian blur sigma 2 voxels");

  ShockOptions options = common;
  options.time = VolumeDemoTime;
  options.flowMode = vtkShockAdvectionFilter::FIXED;
  const FilterRun run = RunImageFilter(volume, arrayName, options);
  WriteDemoFile(run.output, directory, "volume_sharpened.vti", arrayName,
    "t=" + NumberText(VolumeDemoTime) + ": " + RunTimesText(run));
  std::cerr << "demo: volume sharpness (RMS gradient): input "
            << NumberText(RmsLuminanceGradient(volume, arrayName)) << ", t=" << NumberText(VolumeDemoTime) << " "
            << NumberText(RmsLuminanceGradient(run.output, arrayName)) << '\n';

  const int zoom = 4;
  vtkSmartPointer<vtkImageData> before = MiddleSliceAsBytes(volume, arrayName, 255.0, zoom);
  vtkSmartPointer<vtkImageData> after = MiddleSliceAsBytes(run.output, arrayName, 255.0, zoom);
  WriteDemoFile(SideBySide(before, after, 8), directory, "volume_before_after.png", arrayName,
    "middle z-slice, input | t=" + NumberText(VolumeDemoTime) + ", 0..1 shown as 0..255, " +
      "pixels enlarged " + std::to_string(zoom) + "x");
}

} // namespace shockcli
