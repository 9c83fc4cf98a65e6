// The "image" subcommand: sharpens an image or volume file (vtkImageShockAdvectionFilter).
#include "CliFiles.h"
#include "CliFilters.h"
#include "Commands.h"
#include "ShockImageChecks.h"

#include "vtkImageShockAdvectionFilter.h"
#include "vtkNew.h"
#include "vtkCellData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <iomanip>
#include <iostream>
#include <optional>
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
    .Add("levels", run.levels)
    .Add("domain", ChoiceName(run.domain, DomainChoices()));
  return json.Text();
}

/**
 * The cells of `image` as the points of an image (the cells' centres, same
 * raster): the form the raster writers store, for an image whose pixels are
 * cells (ParaView's GDAL reader gives photos so). Shares the cell array `arrayName`.
 */
vtkSmartPointer<vtkImageData> PixelsAsPoints(vtkImageData* image, const std::string& arrayName)
{
  int extent[6];
  image->GetExtent(extent);
  double half[3];
  for (int a = 0; a < 3; ++a)
  {
    const bool flat = extent[2 * a + 1] == extent[2 * a];
    half[a] = flat ? 0.0 : 0.5; // a flat axis has one layer of cells, centred on its points
    extent[2 * a + 1] = flat ? extent[2 * a + 1] : extent[2 * a + 1] - 1;
  }
  // Physical(i) = origin + D (i spacing): with the same extent start, the
  // origin moves by half a cell, to the physical point of index `half`.
  double origin[3];
  image->TransformContinuousIndexToPhysicalPoint(half, origin);
  auto pixels = vtkSmartPointer<vtkImageData>::New();
  pixels->SetExtent(extent);
  pixels->SetSpacing(image->GetSpacing());
  pixels->SetDirectionMatrix(image->GetDirectionMatrix());
  pixels->SetOrigin(origin);
  pixels->GetPointData()->SetScalars(image->GetCellData()->GetArray(arrayName.c_str()));
  return pixels;
}

struct ImageSettings : ArrayCommandSettings
{
  ShockOptions shock;
  ImageMethodOptions method;
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
  specs.push_back(ChoiceOptionSpec("--domain", "DOMAIN",
    "advection: values (the paper) | gradients (carried along the flow, integrated back;\n"
    "    whole image, finite values, fixed flow; docs/gradient-domain.md)",
    method.domain, DomainChoices(), defaults->GetDomain()));
  specs.push_back(RangeOptionSpec("--gradient-screening", "W",
    "gradients: screening weight of the Poisson solve (per squared edge length;\n"
    "    larger stays closer to the input)",
    method.gradientScreening, defaults->GetGradientScreeningMinValue(),
    defaults->GetGradientScreeningMaxValue(), defaults->GetGradientScreening()));
  specs.push_back(RangeOptionSpec("--courant", "C", "pde: Courant number of the explicit step",
    method.courantNumber, defaults->GetCourantNumberMinValue(), defaults->GetCourantNumberMaxValue(),
    defaults->GetCourantNumber()));
  specs.push_back(RangeOptionSpec("--max-iterations", "N", "pde: most explicit steps",
    method.maximumIterations, defaults->GetMaximumIterationsMinValue(),
    defaults->GetMaximumIterationsMaxValue(), defaults->GetMaximumIterations()));
  AddArrayCommandOptionSpecs(
    specs, settings, "point or cell array to filter (default: active point scalars, else cell scalars)");
  return specs;
}

} // namespace

std::string ImageHelp()
{
  ImageSettings unused;
  std::ostringstream text;
  text << "shockfilter image INPUT OUTPUT [options]\n"
          "  Sharpens the selected point or cell array of an image or volume and writes it\n"
          "  (cell data: each cell a pixel, as in the .vti ParaView saves from a photo).\n"
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
          "  refused before it is read. --domain gradients needs about 8 x C x (1 + 2 x axes)\n"
          "  bytes per sample more (C components: 120 per pixel of an RGB photo).\n"
       << TimingsHelp({ "command", "dimensions", "samples", "components", "time", "flow_mode",
                        "threads", "flow", "advection", "total", "trace_steps", "method",
                        "iterations", "levels", "domain" },
            "  times in seconds, total = wall time of the filter only (no reading/writing);\n"
            "  for --method pde, advection = the explicit updates, iterations = their number;\n"
            "  levels = --levels; domain = --domain.\n")
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
  const SelectedArray selected = SelectArray(input, settings.arrayName, settings.association, "ImageScalars");
  const std::string& arrayName = selected.name;
  // Pixels stored as cells (e.g. a .vti ParaView saved from its GDAL reader):
  // .vti and .vtk keep them so; the raster formats store the same raster as points.
  const bool cells = selected.association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const bool raster =
    outputFormat.id != shockio::ImageFormat::VTI && outputFormat.id != shockio::ImageFormat::LegacyVTK;
  std::string error;
  Require(shockio::CheckStorable(cells ? PixelsAsPoints(input, arrayName).GetPointer() : input.GetPointer(),
            arrayName, outputFormat, outputPath, error),
    error);
  const FilterRun run = RunImageFilter(input, arrayName, settings.shock, settings.method, selected.association);
  WriteImageFile(cells && raster ? PixelsAsPoints(run.output, arrayName).GetPointer() : run.output.GetPointer(),
    outputPath, arrayName);

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
