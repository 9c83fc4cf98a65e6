// The "sharpen" subcommand: sharpens the geometry of a surface mesh file
// (vtkPolyDataShockSharpenFilter).
#include "CliFiles.h"
#include "CliFilters.h"
#include "Commands.h"

#include "vtkNew.h"
#include "vtkPolyDataShockSharpenFilter.h"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace shockcli
{
namespace
{

const std::vector<Choice>& SolverChoices()
{
  static const std::vector<Choice> choices = {
    { "conjugate-gradient", vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT },
    { "conjugate-gradient-tolerance", vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT_TOLERANCE },
    { "exact", vtkPolyDataShockSharpenFilter::EXACT },
    // Earlier spellings, still accepted.
    { "cg", vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT },
    { "cg-tolerance", vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT_TOLERANCE },
  };
  return choices;
}

const std::vector<Choice>& FitTargetChoices()
{
  static const std::vector<Choice> choices = {
    { "projection", vtkPolyDataShockSharpenFilter::PROJECTION },
    { "rotation", vtkPolyDataShockSharpenFilter::ROTATION },
    { "shear", vtkPolyDataShockSharpenFilter::SHEAR },
    { "central-projection", vtkPolyDataShockSharpenFilter::CENTRAL_PROJECTION },
  };
  return choices;
}

struct SharpenSettings
{
  ShockOptions shock;
  std::optional<double> featureAngle;
  std::optional<double> curvatureContrast;
  std::optional<int> fitTarget;
  std::optional<int> normalSmoothingPasses;
  std::optional<int> keepUnmovedNormals;
  std::optional<double> screeningWeight;
  std::optional<double> anchorWeight;
  std::optional<double> anchorAngle;
  std::optional<double> driftRadius;
  std::optional<int> solver;
  std::optional<int> iterations;
  std::optional<double> tolerance;
  bool timings = false;
  std::uint64_t maxSamples = shockio::DefaultMaxSamples;
};

std::vector<OptionSpec> SharpenOptionSpecs(SharpenSettings& settings)
{
  vtkNew<vtkPolyDataShockSharpenFilter> defaults;
  std::vector<OptionSpec> specs = ShockOptionSpecs(settings.shock, ShockOptionSet::All, defaults);
  vtkPolyDataShockSharpenFilter* d = defaults;
  specs.push_back(RangeOptionSpec("--feature-angle", "DEG",
    "creases sharper than this are kept (180 = the paper)", settings.featureAngle,
    d->GetFeatureAngleMinValue(), d->GetFeatureAngleMaxValue(), d->GetFeatureAngle()));
  specs.push_back(RangeOptionSpec("--curvature-contrast", "X",
    "smooth shapes are left alone: the potential keeps what exceeds X times its minimum over 6 rings (0 = the paper)",
    settings.curvatureContrast, d->GetCurvatureContrastMinValue(), d->GetCurvatureContrastMaxValue(),
    d->GetCurvatureContrast()));
  specs.push_back(ChoiceOptionSpec("--fit-target", "NAME",
    "central-projection|shear|rotation|projection (the paper)", settings.fitTarget, FitTargetChoices(),
    d->GetFitTarget()));
  specs.push_back(RangeOptionSpec("--normal-smoothing", "N", "smoothing passes of the normals before",
    settings.normalSmoothingPasses, d->GetNormalSmoothingPassesMinValue(),
    d->GetNormalSmoothingPassesMaxValue(), d->GetNormalSmoothingPasses()));
  specs.push_back(RangeOptionSpec("--keep-unmoved-normals", "0|1",
    "a triangle the flow does not move keeps its own normal (0 = the paper's sampling)",
    settings.keepUnmovedNormals, 0, 1, static_cast<int>(d->GetKeepUnmovedNormals())));
  specs.push_back(RangeOptionSpec("--screening", "EPS", "screening weight of the fit",
    settings.screeningWeight, d->GetScreeningWeightMinValue(), d->GetScreeningWeightMaxValue(),
    d->GetScreeningWeight()));
  specs.push_back(RangeOptionSpec("--anchor-weight", "W",
    "the fit holds the points whose triangles did not turn (0 = the paper)", settings.anchorWeight,
    d->GetAnchorWeightMinValue(), d->GetAnchorWeightMaxValue(), d->GetAnchorWeight()));
  specs.push_back(RangeOptionSpec("--anchor-angle", "DEG",
    "turn below which a point is anchored, fading to none at DEG (0 = the paper)", settings.anchorAngle,
    d->GetAnchorAngleMinValue(), d->GetAnchorAngleMaxValue(), d->GetAnchorAngle()));
  specs.push_back(RangeOptionSpec("--drift-radius", "EDGES",
    "the displacement smoother than EDGES edge lengths is removed (0 = the paper)", settings.driftRadius,
    d->GetDriftRadiusMinValue(), d->GetDriftRadiusMaxValue(), d->GetDriftRadius()));
  specs.push_back(ChoiceOptionSpec(
    "--solver", "NAME", "conjugate-gradient|conjugate-gradient-tolerance|exact", settings.solver, SolverChoices(), d->GetSolver()));
  specs.push_back(RangeOptionSpec("--iterations", "K", "CG iterations (cap of conjugate-gradient-tolerance)",
    settings.iterations, d->GetSolverIterationsMinValue(), d->GetSolverIterationsMaxValue(),
    d->GetSolverIterations()));
  specs.push_back(RangeOptionSpec("--tolerance", "X", "stop residual of conjugate-gradient-tolerance (implied)",
    settings.tolerance, d->GetSolverToleranceMinValue(), d->GetSolverToleranceMaxValue(),
    d->GetSolverTolerance()));
  specs.push_back(MaxSamplesOptionSpec(settings.maxSamples));
  specs.push_back(TimingsOptionSpec(settings.timings));
  return specs;
}

} // namespace

std::string SharpenHelp()
{
  SharpenSettings unused;
  std::ostringstream text;
  text << "shockfilter sharpen INPUT OUTPUT [options]\n"
          "  Sharpens the geometry of a surface mesh: its face normals are shock-filtered,\n"
          "  then the points are fitted to them (screened Poisson equation). Creases\n"
          "  and corners become sharp; flat and smooth parts stay; creases already\n"
          "  sharper than --feature-angle are kept. Arrays pass through; active\n"
          "  normals are recomputed for the new geometry.\n"
       << MeshFormatsHelp()
       << "  Memory: about 1200 bytes per point; a file declaring more points or cells\n"
          "  than --max-samples is refused before it is read.\n"
       << TimingsHelp({ "command", "points", "triangles", "time", "smoothing", "normal_smoothing",
                        "flow_mode", "solver", "feature_angle", "fit_target", "threads", "preprocessing", "setup", "fit_setup",
                        "flow", "advection", "fitting", "total", "trace_steps", "solver_iterations",
                        "solver_residual", "flipped_triangles", "max_displacement", "feature_edges",
                        "repeated_triangles", "degenerate_triangles" },
            "  times in seconds, the phases of the paper's Table 3: preprocessing = setup\n"
            "  (mesh preparation) + fit_setup (system set-up), flow = normals, smoothing,\n"
            "  potential and flow, advection, fitting = solve; total = wall time of the\n"
            "  filter only (no reading/writing). max_displacement is relative to the\n"
            "  bounding-box diagonal.\n")
       << "  Options:\n"
       << FormatOptions(SharpenOptionSpecs(unused));
  return text.str();
}

int RunSharpenCommand(const std::vector<std::string>& args)
{
  SharpenSettings settings;
  const std::vector<std::string> paths =
    ParseCommandLine("sharpen", args, SharpenOptionSpecs(settings), { "INPUT", "OUTPUT" });
  const int tolerantSolver = vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT_TOLERANCE;
  if (settings.tolerance && settings.solver.value_or(tolerantSolver) != tolerantSolver)
  {
    throw CliError("sharpen: --tolerance applies to --solver conjugate-gradient-tolerance only");
  }
  const std::string& inputPath = paths[0];
  const std::string& outputPath = paths[1];
  MeshFormatOfPath(inputPath);
  MeshFormatOfPath(outputPath); // before the work
  RequireWritable(outputPath);
  vtkSmartPointer<vtkPolyData> input = ReadMeshFile(inputPath, settings.maxSamples);

  vtkNew<vtkPolyDataShockSharpenFilter> filter;
  ConfigureFilter(filter, settings.shock);
  using F = vtkPolyDataShockSharpenFilter;
  SetIfGiven(filter.Get(), &F::SetFeatureAngle, settings.featureAngle);
  SetIfGiven(filter.Get(), &F::SetCurvatureContrast, settings.curvatureContrast);
  SetIfGiven(filter.Get(), &F::SetFitTarget, settings.fitTarget);
  SetIfGiven(filter.Get(), &F::SetNormalSmoothingPasses, settings.normalSmoothingPasses);
  SetIfGiven(filter.Get(), &F::SetKeepUnmovedNormals, settings.keepUnmovedNormals);
  SetIfGiven(filter.Get(), &F::SetScreeningWeight, settings.screeningWeight);
  SetIfGiven(filter.Get(), &F::SetAnchorWeight, settings.anchorWeight);
  SetIfGiven(filter.Get(), &F::SetAnchorAngle, settings.anchorAngle);
  SetIfGiven(filter.Get(), &F::SetDriftRadius, settings.driftRadius);
  if (settings.solver || settings.tolerance)
  {
    filter->SetSolver(settings.solver.value_or(tolerantSolver));
  }
  SetIfGiven(filter.Get(), &F::SetSolverIterations, settings.iterations);
  SetIfGiven(filter.Get(), &F::SetSolverTolerance, settings.tolerance);
  MeshFrame frame;
  filter->SetInputData(InUnitFrame(input, frame));
  const double seconds = TimedUpdate(filter, MeshFilterBytes(input->GetNumberOfPoints()));
  BackFromUnitFrame(filter->GetOutput(), frame);
  WriteMeshFile(filter->GetOutput(), outputPath);

  if (settings.timings)
  {
    JsonObject json;
    json.Add("command", "sharpen")
      .Add("points", input->GetNumberOfPoints())
      .Add("triangles", CountTriangles(input))
      .Add("time", filter->GetFlowTime())
      .Add("smoothing", filter->GetSmoothingPasses())
      .Add("normal_smoothing", filter->GetNormalSmoothingPasses())
      .Add("flow_mode", ChoiceName(filter->GetFlowMode(), FlowModeChoices()))
      .Add("solver", ChoiceName(filter->GetSolver(), SolverChoices()))
      .Add("feature_angle", filter->GetFeatureAngle())
      .Add("curvature_contrast", filter->GetCurvatureContrast())
      .Add("fit_target", ChoiceName(filter->GetFitTarget(), FitTargetChoices()))
      .Add("threads", filter->GetNumberOfThreads())
      .Add("preprocessing", filter->GetLastSetupSeconds() + filter->GetLastFitSetupSeconds())
      .Add("setup", filter->GetLastSetupSeconds())
      .Add("fit_setup", filter->GetLastFitSetupSeconds())
      .Add("flow", filter->GetLastFlowSeconds())
      .Add("advection", filter->GetLastAdvectionSeconds())
      .Add("fitting", filter->GetLastFitSolveSeconds())
      .Add("total", seconds)
      .Add("trace_steps", filter->GetLastTraceSteps())
      .Add("solver_iterations", filter->GetLastSolverIterations())
      .Add("solver_residual", filter->GetLastSolverResidual())
      .Add("flipped_triangles", filter->GetLastFlippedTriangles())
      .Add("max_displacement", filter->GetLastMaxDisplacement())
      .Add("feature_edges", filter->GetLastFeatureEdges())
      .Add("repeated_triangles", filter->GetLastRepeatedTriangles())
      .Add("degenerate_triangles", filter->GetLastDegenerateTriangles());
    std::cout << json.Text() << std::endl;
  }
  std::cerr << "sharpen: " << input->GetNumberOfPoints() << " points, " << CountTriangles(input)
            << " triangles, t=" << NumberText(filter->GetFlowTime()) << ": " << std::fixed
            << std::setprecision(3) << seconds << " s (" << filter->GetLastSolverIterations()
            << " solver iterations, relative residual " << NumberText(filter->GetLastSolverResidual())
            << ", " << filter->GetLastFlippedTriangles() << " flipped triangles, max displacement "
            << NumberText(filter->GetLastMaxDisplacement()) << " of the diagonal) -> " << outputPath
            << '\n';
  return 0;
}

} // namespace shockcli
