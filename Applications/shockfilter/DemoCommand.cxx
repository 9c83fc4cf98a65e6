// The "demo" subcommand: sharpens built-in data (a picture, a volume, the
// colours of a sphere, the geometry of a rounded box) and writes inputs,
// results and comparisons to a directory.
#include "CliFiles.h"
#include "CliFilters.h"
#include "Commands.h"
#include "Demo.h"
#include "ShockShapesVTK.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyDataShockAdvectionFilter.h"
#include "vtkPolyDataShockSharpenFilter.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <vector>

namespace shockcli
{
namespace
{

/**
 * The surface of the cube [-1, 1]^3 with n x n squares per face, its creases
 * rounded to radius 'rounding' in [0, 1] (1 gives the unit sphere): the
 * tests' rounded box (Applications/Shapes).
 */
vtkSmartPointer<vtkPolyData> RoundedCube(int n, double rounding)
{
  return shockshapes::ToPolyData(shockshapes::RoundedBox(n, 2.0, rounding));
}

/// Colour of the sphere demo at a point of the unit sphere: three regions with blurred borders.
Rgb DemoSphereColour(const double p[3])
{
  const auto step = [](double signedDistance) { return 0.5 + 0.5 * std::tanh(signedDistance / 0.1); };
  const double a = step(p[0] + 0.3 * p[1]); // across a tilted great circle
  const double b = step(p[2] - 0.45);       // across a latitude
  const Rgb blue = { 30, 70, 190 }, orange = { 240, 140, 25 }, white = { 235, 235, 225 };
  Rgb colour;
  for (int c = 0; c < 3; ++c)
  {
    colour[c] = (1.0 - b) * ((1.0 - a) * blue[c] + a * orange[c]) + b * white[c];
  }
  return colour;
}

/// Writes 'mesh' to 'directory'/'name' and tells so on stderr.
void WriteDemoMesh(vtkPolyData* mesh, const std::filesystem::path& directory, const std::string& name,
  const std::string& description)
{
  const std::string path = (directory / name).string();
  WriteMeshFile(mesh, path);
  std::cerr << "demo: wrote " << path << " (" << description << ")\n";
}

/// The mesh part of the demo: blurred colours on a sphere, the geometry of a rounded box.
void RunMeshDemo(const std::filesystem::path& directory, const ShockOptions& common)
{
  vtkSmartPointer<vtkPolyData> sphere = RoundedCube(40, 1.0);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName(shockio::PointColorsName);
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(sphere->GetNumberOfPoints());
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    const Rgb colour = DemoSphereColour(sphere->GetPoint(p));
    for (int c = 0; c < 3; ++c)
    {
      colours->SetTypedComponent(p, c, static_cast<unsigned char>(std::lround(colour[c])));
    }
  }
  sphere->GetPointData()->SetScalars(colours);
  WriteDemoMesh(sphere, directory, "sphere_input.ply",
    std::to_string(sphere->GetNumberOfPoints()) + "-point sphere, blurred vertex colours");
  vtkNew<vtkPolyDataShockAdvectionFilter> surface;
  ConfigureFilter(surface, common);
  surface->SetFlowTime(SphereDemoTime);
  surface->SetInputData(sphere);
  const double surfaceSeconds = TimedUpdate(surface, MeshFilterBytes(sphere->GetNumberOfPoints()));
  WriteDemoMesh(surface->GetOutput(), directory, "sphere_sharpened.ply",
    "colours filtered at t=" + NumberText(SphereDemoTime) + ": " + SecondsText(surfaceSeconds));

  vtkSmartPointer<vtkPolyData> box = RoundedCube(32, 0.3);
  WriteDemoMesh(box, directory, "rounded_box_input.ply",
    std::to_string(box->GetNumberOfPoints()) + "-point cube, creases rounded to 0.3 of the half side");
  vtkNew<vtkPolyDataShockSharpenFilter> sharpen;
  ConfigureFilter(sharpen, common);
  sharpen->SetFlowTime(BoxDemoTime);
  sharpen->SetInputData(box);
  const double sharpenSeconds = TimedUpdate(sharpen, MeshFilterBytes(box->GetNumberOfPoints()));
  WriteDemoMesh(sharpen->GetOutput(), directory, "rounded_box_sharpened.ply",
    "geometry sharpened at t=" + NumberText(BoxDemoTime) + ": " + SecondsText(sharpenSeconds) +
      ", largest displacement " + NumberText(sharpen->GetLastMaxDisplacement()) + " of the diagonal");
}

struct DemoSettings
{
  ShockOptions shock;
};

std::vector<OptionSpec> DemoOptionSpecs(DemoSettings& settings)
{
  vtkNew<vtkImageShockAdvectionFilter> defaults;
  return ShockOptionSpecs(settings.shock, ShockOptionSet::ThreadsOnly, defaults);
}

} // namespace

std::string DemoHelp()
{
  DemoSettings unused;
  std::ostringstream text;
  std::string times;
  for (const double t : PictureDemoTimes)
  {
    times += (times.empty() ? "" : ", ") + NumberText(t);
  }
  text << "shockfilter demo OUTDIR [options]\n"
          "  Runs the filter on built-in data and writes to OUTDIR (created if missing):\n"
          "    input.png               blurred, slightly noisy 512x384 RGB test picture\n"
          "    sharpened_t<T>.png      the picture filtered at T = "
       << times << "\n"
       << "    before_after.png        input | t=" << NumberText(PictureDemoShownTime) << "\n"
       << "    volume_input.vti        blurred 64^3 float volume of spheres and a box\n"
          "    volume_sharpened.vti    the volume filtered at t="
       << NumberText(VolumeDemoTime) << "\n"
       << "    volume_before_after.png middle z-slices, input | t=" << NumberText(VolumeDemoTime)
       << "\n"
          "    sphere_input.ply        sphere with blurred vertex colours\n"
          "    sphere_sharpened.ply    its colours filtered at t="
       << NumberText(SphereDemoTime) << "\n"
       << "    rounded_box_input.ply   cube with rounded creases\n"
          "    rounded_box_sharpened.ply  its geometry sharpened at t="
       << NumberText(BoxDemoTime) << "\n"
       << "  Fixed flow, other parameters at their defaults. Prints on stderr what it\n"
          "  wrote, the run times and a sharpness figure per t of the picture.\n"
          "  Options:\n"
       << FormatOptions(DemoOptionSpecs(unused));
  return text.str();
}

int RunDemoCommand(const std::vector<std::string>& args)
{
  DemoSettings settings;
  const std::filesystem::path directory =
    ParseCommandLine("demo", args, DemoOptionSpecs(settings), { "OUTDIR" })[0];
  CreateDirectory(directory);
  const bool sharper = RunPictureDemo(directory, settings.shock);
  RunVolumeDemo(directory, settings.shock);
  RunMeshDemo(directory, settings.shock);
  if (!sharper)
  {
    std::cerr << "demo: FAILED: the pictures do not get sharper with t\n";
    return 1; // its own check failed (2 is for bad input)
  }
  return 0;
}

} // namespace shockcli
