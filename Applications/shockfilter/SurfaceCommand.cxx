// The "surface" subcommand: sharpens a point or cell array of a surface mesh
// file (vtkPolyDataShockAdvectionFilter).
#include "CliFiles.h"
#include "CliFilters.h"
#include "Commands.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataShockAdvectionFilter.h"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace shockcli
{
namespace
{

struct SurfaceSettings : ArrayCommandSettings
{
  ShockOptions shock;
};

std::vector<OptionSpec> SurfaceOptionSpecs(SurfaceSettings& settings)
{
  vtkNew<vtkPolyDataShockAdvectionFilter> defaults;
  std::vector<OptionSpec> specs = ShockOptionSpecs(settings.shock, ShockOptionSet::All, defaults);
  AddArrayCommandOptionSpecs(specs, settings, "point or cell array to filter (default: active scalars)");
  return specs;
}

} // namespace

std::string SurfaceHelp()
{
  SurfaceSettings unused;
  std::ostringstream text;
  text << "shockfilter surface INPUT OUTPUT [options]\n"
          "  Sharpens a point or cell array of a surface mesh (e.g. its vertex colours)\n"
          "  by advection over the surface and writes the mesh with the filtered array.\n"
       << MeshFormatsHelp()
       << "  Memory: about 1200 bytes per point; a file declaring more points or cells\n"
          "  than --max-samples is refused before it is read.\n"
       << "  The array: --array NAME is looked for in the point data, then in the cell\n"
          "  data (only in those of --association when given); by default, the active\n"
          "  scalars of the point data (of the cell data with --association cell), e.g.\n"
          "  the \"Colors\" of a PLY or OFF file. It keeps its name and type; an OUTPUT\n"
          "  that cannot store it (e.g. float values in ply) is refused.\n"
       << TimingsHelp({ "command", "points", "triangles", "array", "association", "components",
                        "time", "flow_mode", "threads", "setup", "flow", "advection", "total",
                        "trace_steps" },
            "  times in seconds: setup = mesh preparation, flow = smoothing, potential and\n"
            "  flow, advection = tracing and sampling, total = wall time of the filter\n"
            "  only (no reading/writing).\n")
       << "  Options:\n"
       << FormatOptions(SurfaceOptionSpecs(unused));
  return text.str();
}

namespace
{

/**
 * Throws unless 'format' keeps the array to filter (checked before the work):
 * ply and off keep unsigned char colours of 3 or 4 components, obj and stl no array.
 */
void RequireMeshStorable(const shockio::MeshFormat& format, const SelectedArray& selected, const std::string& path)
{
  const std::string where = "cannot write '" + path + "': ";
  const std::string kind = ChoiceName(selected.association, AssociationChoices());
  vtkDataArray* array = selected.array;
  switch (format.arrays)
  {
    case shockio::MeshArrays::All:
      return;
    case shockio::MeshArrays::Colours:
      if (array->GetDataType() == VTK_UNSIGNED_CHAR &&
        (array->GetNumberOfComponents() == 3 || array->GetNumberOfComponents() == 4))
      {
        return;
      }
      throw CliError(where + format.name + " stores only unsigned char RGB or RGBA colours; " + kind +
        " array '" + selected.name + "' is " + array->GetDataTypeAsString() + " with " +
        std::to_string(array->GetNumberOfComponents()) + " component(s) (write " +
        MeshExtensionsKeeping(shockio::MeshArrays::All) + ")");
    case shockio::MeshArrays::None:
      throw CliError(where + format.name + " does not store the filtered " + kind + " array '" +
        selected.name + "' (write " + MeshExtensionsKeeping(shockio::MeshArrays::Colours) + ")");
  }
}

} // namespace

int RunSurfaceCommand(const std::vector<std::string>& args)
{
  SurfaceSettings settings;
  const std::vector<std::string> paths =
    ParseCommandLine("surface", args, SurfaceOptionSpecs(settings), { "INPUT", "OUTPUT" });
  const std::string& inputPath = paths[0];
  const std::string& outputPath = paths[1];
  MeshFormatOfPath(inputPath);
  const shockio::MeshFormat& outputFormat = MeshFormatOfPath(outputPath); // before the work
  RequireWritable(outputPath);

  vtkSmartPointer<vtkPolyData> input = ReadMeshFile(inputPath, settings.maxSamples);
  const SelectedArray selected = SelectArray(input, settings.arrayName, settings.association, "Scalars");
  RequireMeshStorable(outputFormat, selected, outputPath);

  vtkNew<vtkPolyDataShockAdvectionFilter> filter;
  ConfigureFilter(filter, settings.shock);
  filter->SetInputArrayToProcess(0, 0, 0, selected.association, selected.name.c_str());
  MeshFrame frame;
  filter->SetInputData(InUnitFrame(input, frame));
  const double seconds = TimedUpdate(filter, MeshFilterBytes(input->GetNumberOfPoints()));

  vtkPolyData* output = filter->GetOutput();
  output->SetPoints(input->GetPoints()); // the filter changes the array only
  // The mesh writers store the active scalars as colours: make them the filtered array.
  vtkDataSetAttributes* attributes = selected.association == vtkDataObject::FIELD_ASSOCIATION_CELLS
    ? static_cast<vtkDataSetAttributes*>(output->GetCellData())
    : output->GetPointData();
  attributes->SetActiveScalars(selected.name.c_str());
  WriteMeshFile(output, outputPath);

  const char* kind = ChoiceName(selected.association, AssociationChoices());
  if (settings.timings)
  {
    JsonObject json;
    json.Add("command", "surface")
      .Add("points", input->GetNumberOfPoints())
      .Add("triangles", CountTriangles(input))
      .Add("array", selected.name)
      .Add("association", kind)
      .Add("components", selected.array->GetNumberOfComponents())
      .Add("time", filter->GetFlowTime())
      .Add("flow_mode", ChoiceName(filter->GetFlowMode(), FlowModeChoices()))
      .Add("threads", filter->GetNumberOfThreads())
      .Add("setup", filter->GetLastSetupSeconds())
      .Add("flow", filter->GetLastFlowSeconds())
      .Add("advection", filter->GetLastAdvectionSeconds())
      .Add("total", seconds)
      .Add("trace_steps", filter->GetLastTraceSteps());
    std::cout << json.Text() << std::endl;
  }
  std::cerr << "surface: " << input->GetNumberOfPoints() << " points, " << CountTriangles(input)
            << " triangles, " << selected.array->GetNumberOfComponents() << " component(s) of " << kind
            << " array '" << selected.name << "', t=" << NumberText(filter->GetFlowTime()) << ": "
            << std::fixed << std::setprecision(3) << seconds << " s -> " << outputPath << '\n';
  return 0;
}

} // namespace shockcli
