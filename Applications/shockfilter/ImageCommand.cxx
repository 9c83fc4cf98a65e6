// The "image" subcommand: sharpens an image or volume file (vtkImageShockAdvectionFilter).
#include "CliFiles.h"
#include "CliFilters.h"
#include "Commands.h"
#include "ShockImageChecks.h"

#include "vtkImageShockAdvectionFilter.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace shockcli
{
namespace
{

/// The --timings report of the image command: one JSON object on one line.
std::string TimingsJson(const std::string& command, vtkImageData* image, const FilterRun& run)
{
  int dims[3];
  image->GetDimensions(dims);
  JsonObject json;
  json.Add("command", command)
    .AddRaw("dimensions",
      "[" + std::to_string(dims[0]) + "," + std::to_string(dims[1]) + "," + std::to_string(dims[2]) + "]")
    .Add("samples", image->GetNumberOfPoints())
    .Add("components", run.components)
    .Add("time", run.time)
    .Add("flow_mode", ChoiceName(run.flowMode, FlowModeChoices()))
    .Add("threads", run.threads)
    .Add("flow", run.flowSeconds)
    .Add("advection", run.advectionSeconds)
    .Add("total", run.totalSeconds)
    .Add("trace_steps", run.traceSteps)
    .Add("method", ChoiceName(run.method, MethodChoices()))
    .Add("iterations", run.iterations)
    .Add("levels", run.levels);
  return json.Text();
}

struct ImageSettings
{
  ShockOptions shock;
  ImageMethodOptions method;
  std::string arrayName;
  bool timings = false;
  std::uint64_t maxSamples = shockio::DefaultMaxSamples;
};

std::vector<OptionSpec> ImageOptionSpecs(ImageSettings& settings)
{
  vtkNew<vtkImageShockAdvectionFilter> defaults;
  std::vector<OptionSpec> specs;
  ImageMethodOptions& method = settings.method;
  specs.push_back(ChoiceOptionSpec("--method", "METHOD",
    "advection|pde (the Osher-Rudin PDE baseline, linear in t)", method.method, MethodChoices(),
    defaults->GetMethod()));
  const std::vector<OptionSpec> shared = ShockOptionSpecs(settings.shock, ShockOptionSet::All, defaults);
  specs.insert(specs.end(), shared.begin(), shared.end());
  specs.push_back(RangeOptionSpec("--levels", "N", "advection: coarse-to-fine resolution levels",
    method.hierarchyLevels, defaults->GetHierarchyLevelsMinValue(), defaults->GetHierarchyLevelsMaxValue(),
    defaults->GetHierarchyLevels(), ", 1 = the paper's single level"));
  specs.push_back(RangeOptionSpec("--courant", "C", "pde: Courant number of the explicit step",
    method.courantNumber, defaults->GetCourantNumberMinValue(), defaults->GetCourantNumberMaxValue(),
    defaults->GetCourantNumber()));
  specs.push_back(RangeOptionSpec("--max-iterations", "N", "pde: most explicit steps",
    method.maximumIterations, defaults->GetMaximumIterationsMinValue(),
    defaults->GetMaximumIterationsMaxValue(), defaults->GetMaximumIterations()));
  specs.push_back(
    ArrayOptionSpec(settings.arrayName, "point array to filter (default: active point scalars)"));
  specs.push_back(MaxSamplesOptionSpec(settings.maxSamples));
  specs.push_back(TimingsOptionSpec(settings.timings));
  return specs;
}

} // namespace

std::string ImageHelp()
{
  ImageSettings unused;
  std::ostringstream text;
  text << "shockfilter image INPUT OUTPUT [options]\n"
          "  Sharpens the selected point array of an image or volume and writes it.\n"
          "  Formats, chosen by extension (case-insensitive):\n"
          "    read:  png jpg jpeg tif tiff bmp pnm ppm pgm vti vtk (structured points)\n"
          "    write: png jpg jpeg tif tiff bmp pnm ppm pgm vti vtk\n"
          "  The filtered array keeps its type; vti and vtk store all arrays unchanged.\n"
          "  The raster formats store the filtered array only:\n"
          "    png          unsigned char or unsigned short, 1 to 4 components, 2D\n"
          "    tif          unsigned char, unsigned short or float (other types are\n"
          "                 converted to float), 1, 3 or 4 components, 2D or 3D\n"
          "    jpg bmp pnm  unsigned char, 1 or 3 components, 2D\n"
          "  For png/jpg/bmp/pnm other types are rounded and clamped to 0..255 (a note\n"
          "  on stderr says so); other component counts and volumes are refused.\n"
          "  Memory: about 8 bytes per pixel (12 per voxel) plus 2 to 16 per sample\n"
          "  and component (14 per pixel of a large 8-bit RGB photo, 20 per voxel of\n"
          "  a float volume); an input declaring more samples than --max-samples is\n"
          "  refused before it is read.\n"
       << TimingsHelp({ "command", "dimensions", "samples", "components", "time", "flow_mode",
                        "threads", "flow", "advection", "total", "trace_steps", "method",
                        "iterations", "levels" },
            "  times in seconds, total = wall time of the filter only (no reading/writing);\n"
            "  for --method pde, advection = the explicit updates, iterations = their number;\n"
            "  levels = --levels.\n")
       << "  Options:\n"
       << FormatOptions(ImageOptionSpecs(unused));
  return text.str();
}

int RunImageCommand(const std::vector<std::string>& args)
{
  ImageSettings settings;
  const std::vector<std::string> paths =
    ParseCommandLine("image", args, ImageOptionSpecs(settings), { "INPUT", "OUTPUT" });
  const std::string& inputPath = paths[0];
  const std::string& outputPath = paths[1];
  ImageFormatOfPath(inputPath);
  const shockio::ImageFormat& outputFormat = ImageFormatOfPath(outputPath); // before the work
  RequireWritable(outputPath);

  vtkSmartPointer<vtkImageData> input = ReadImageFile(inputPath, settings.maxSamples);
  const std::string arrayName =
    SelectArray(input, settings.arrayName, vtkDataObject::FIELD_ASSOCIATION_POINTS, "ImageScalars").name;
  std::string error;
  Require(shockio::CheckStorable(input, arrayName, outputFormat, outputPath, error), error);
  const FilterRun run = RunImageFilter(input, arrayName, settings.shock, settings.method);
  WriteImageFile(run.output, outputPath, arrayName);

  if (settings.timings)
  {
    std::cout << TimingsJson("image", input, run) << std::endl;
  }
  std::cerr << "image: " << shockio::DimensionsText(input) << ", " << run.components << " component(s) of '"
            << arrayName << "', t=" << NumberText(run.time)
            << (run.method == vtkImageShockAdvectionFilter::PDE
                   ? " (pde, " + std::to_string(run.iterations) + " steps)"
                   : std::string())
            << ": " << std::fixed
            << std::setprecision(3) << run.totalSeconds << " s -> " << outputPath << '\n';
  return 0;
}

} // namespace shockcli
