#include "CliFilters.h"
#include "CliFiles.h"

#include "ShockIOMessages.h"
#include "ShockImageChecks.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"

#include <algorithm>
#include <cmath>

#include <chrono>
#include <new>

namespace shockcli
{

const std::vector<Choice>& FlowModeChoices()
{
  static const std::vector<Choice> choices = { { "fixed", vtkShockAdvectionFilter::FIXED },
    { "composed", vtkShockAdvectionFilter::COMPOSED }, { "naive", vtkShockAdvectionFilter::NAIVE } };
  return choices;
}

const std::vector<Choice>& MethodChoices()
{
  static const std::vector<Choice> choices = { { "advection", vtkImageShockAdvectionFilter::ADVECTION },
    { "pde", vtkImageShockAdvectionFilter::PDE } };
  return choices;
}

const std::vector<Choice>& DomainChoices()
{
  static const std::vector<Choice> choices = { { "values", vtkImageShockAdvectionFilter::VALUES },
    { "gradients", vtkImageShockAdvectionFilter::GRADIENTS } };
  return choices;
}

const std::vector<Choice>& SamplingChoices()
{
  static const std::vector<Choice> choices = { { "linear", vtkShockAdvectionFilter::LINEAR },
    { "nearest", vtkShockAdvectionFilter::NEAREST } };
  return choices;
}

const std::vector<Choice>& TracingChoices()
{
  static const std::vector<Choice> choices = { { "face-crossing", vtkShockAdvectionFilter::FACE_CROSSING },
    { "stepped", vtkShockAdvectionFilter::STEPPED },
    { "exact", vtkShockAdvectionFilter::FACE_CROSSING } }; // an earlier spelling, still accepted
  return choices;
}

/**
 * The options setting ShockOptions. Ranges are the clamps of vtkShockAdvectionFilter
 * (whose setters would clamp silently: out of range is refused here); the defaults shown are those of
 * 'defaults', a new filter of the kind the command runs.
 */
std::vector<OptionSpec> ShockOptionSpecs(
  ShockOptions& target, ShockOptionSet set, vtkShockAdvectionFilter* defaults)
{
  vtkShockAdvectionFilter* d = defaults; // the ranges: its clamps (vtkSetClampMacro's Min/MaxValue)
  std::vector<OptionSpec> specs;
  if (set == ShockOptionSet::All)
  {
    specs.push_back({ "--time", "T",
      "flow time t >= 0, normalised units" + DefaultText(NumberText(d->GetFlowTime())),
      [&target](const std::string& v)
      { target.time = ParseInRange("--time", v, 0.0, std::numeric_limits<double>::max()); } });
    specs.push_back(RangeOptionSpec("--smoothing", "N", "smoothing passes", target.smoothingPasses,
      d->GetSmoothingPassesMinValue(), d->GetSmoothingPassesMaxValue(), d->GetSmoothingPasses()));
    specs.push_back(ChoiceOptionSpec(
      "--flow", "MODE", "fixed|composed|naive", target.flowMode, FlowModeChoices(), d->GetFlowMode()));
    specs.push_back(RangeOptionSpec("--updates", "K", "flow updates of composed/naive",
      target.flowUpdates, d->GetNumberOfFlowUpdatesMinValue(), d->GetNumberOfFlowUpdatesMaxValue(),
      d->GetNumberOfFlowUpdates()));
    specs.push_back(ChoiceOptionSpec(
      "--sampling", "MODE", "linear|nearest", target.sampling, SamplingChoices(), d->GetSampling()));
    specs.push_back(ChoiceOptionSpec("--tracing", "MODE", "face-crossing|stepped",
      target.tracingMode, TracingChoices(), d->GetTracingMode()));
    specs.push_back(RangeOptionSpec("--step-fraction", "F", "step of stepped tracing (edges)",
      target.stepFraction, d->GetStepFractionMinValue(), d->GetStepFractionMaxValue(),
      d->GetStepFraction()));
  }
  specs.push_back(RangeOptionSpec("--threads", "N", "OpenMP threads", target.threads,
    d->GetNumberOfThreadsMinValue(), d->GetNumberOfThreadsMaxValue(), d->GetNumberOfThreads(),
    ", 0 = all cores"));
  return specs;
}

/// Sets the given parameters on a filter; the others keep their defaults.
void ConfigureFilter(vtkShockAdvectionFilter* filter, const ShockOptions& options)
{
  using F = vtkShockAdvectionFilter;
  SetIfGiven(filter, &F::SetFlowTime, options.time);
  SetIfGiven(filter, &F::SetSmoothingPasses, options.smoothingPasses);
  SetIfGiven(filter, &F::SetFlowMode, options.flowMode);
  SetIfGiven(filter, &F::SetNumberOfFlowUpdates, options.flowUpdates);
  SetIfGiven(filter, &F::SetSampling, options.sampling);
  SetIfGiven(filter, &F::SetTracingMode, options.tracingMode);
  SetIfGiven(filter, &F::SetStepFraction, options.stepFraction);
  SetIfGiven(filter, &F::SetNumberOfThreads, options.threads);
}

void UpdateOrThrow(vtkAlgorithm* algorithm, const std::string& context)
{
  vtkNew<shockio::MessageTrap> trap;
  trap->Watch(algorithm);
  algorithm->Update();
  std::string error;
  Require(trap->Finish(context, error, shockio::Strictness::Lenient), error);
}

std::uint64_t ImageFilterBytes(vtkIdType samples, int components)
{
  return static_cast<std::uint64_t>(samples) * (16 + 16 * static_cast<std::uint64_t>(components));
}

std::uint64_t MeshFilterBytes(vtkIdType points)
{
  return static_cast<std::uint64_t>(points) * 1200;
}

double TimedUpdate(vtkAlgorithm* filter, std::uint64_t bytesNeeded)
{
  const auto start = std::chrono::steady_clock::now();
  try
  {
    UpdateOrThrow(filter, "shock filter failed");
  }
  catch (const std::bad_alloc&)
  {
    throw CliError("out of memory: the filter needs about " + shockio::BytesText(bytesNeeded) +
      " for this input (see the memory notes of '" + ProgramName + " COMMAND --help')");
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  return elapsed.count();
}

const std::vector<Choice>& AssociationChoices()
{
  static const std::vector<Choice> choices = { { "point", vtkDataObject::FIELD_ASSOCIATION_POINTS },
    { "cell", vtkDataObject::FIELD_ASSOCIATION_CELLS } };
  return choices;
}

void AddArrayCommandOptionSpecs(
  std::vector<OptionSpec>& specs, ArrayCommandSettings& settings, const std::string& arrayHelp)
{
  specs.push_back(ArrayOptionSpec(settings.arrayName, arrayHelp));
  specs.push_back({ "--association", "WHERE", "point|cell data only, for --array and the default scalars",
    [&settings](const std::string& v)
    { settings.association = ParseChoice("--association", v, AssociationChoices()); } });
  specs.push_back(MaxSamplesOptionSpec(settings.maxSamples));
  specs.push_back(TimingsOptionSpec(settings.timings));
}

namespace
{

/// Names of the arrays of 'attributes', for messages ("none" if there are none).
std::string ArrayNames(vtkDataSetAttributes* attributes)
{
  std::string names;
  for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
  {
    const char* name = attributes->GetArrayName(i);
    names += (names.empty() ? "" : ", ") + std::string(name ? name : "(unnamed)");
  }
  return names.empty() ? "none" : names;
}

} // namespace

/**
 * The array to filter: the numeric array named 'requested', looked for in the
 * point data then in the cell data (only in those of 'association' when given);
 * without a name, the active scalars of 'association' (default: those of the
 * point data, else of the cell data), named 'unnamedName' if they have no name. Throws, listing the arrays
 * there are, when there is no such array.
 */
SelectedArray SelectArray(vtkDataSet* data, const std::string& requested, std::optional<int> association,
  const char* unnamedName)
{
  const auto attributesOf = [data](int where) -> vtkDataSetAttributes*
  {
    return where == vtkDataObject::FIELD_ASSOCIATION_CELLS
      ? static_cast<vtkDataSetAttributes*>(data->GetCellData())
      : data->GetPointData();
  };
  const auto kind = [](int where) { return std::string(ChoiceName(where, AssociationChoices())); };
  std::vector<int> searched = { vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataObject::FIELD_ASSOCIATION_CELLS };
  if (association)
  {
    searched = { *association };
  }
  std::string available;
  for (const int where : searched)
  {
    available += (available.empty() ? "" : "; ") + kind(where) + " arrays: " + ArrayNames(attributesOf(where));
  }

  SelectedArray selected;
  if (requested.empty())
  {
    // As the VTK classes: the active point scalars, else the active cell scalars.
    selected.association = association.value_or(data->GetPointData()->GetScalars() || !data->GetCellData()->GetScalars()
        ? vtkDataObject::FIELD_ASSOCIATION_POINTS
        : vtkDataObject::FIELD_ASSOCIATION_CELLS);
    selected.array = attributesOf(selected.association)->GetScalars();
    if (!selected.array)
    {
      throw CliError("the input has no active " + kind(selected.association) +
        " scalars; choose an array with --array (" + available + ")");
    }
    if (!selected.array->GetName() || !*selected.array->GetName())
    {
      selected.array->SetName(unnamedName);
    }
    selected.name = selected.array->GetName();
    return selected;
  }
  for (const int where : searched)
  {
    vtkAbstractArray* found = attributesOf(where)->GetAbstractArray(requested.c_str());
    if (!found)
    {
      continue;
    }
    selected.array = vtkDataArray::SafeDownCast(found);
    if (!selected.array)
    {
      throw CliError("the " + kind(where) + " array '" + requested + "' is not numeric (" +
        found->GetClassName() + ")");
    }
    selected.name = requested;
    selected.association = where;
    return selected;
  }
  const std::string what = association ? kind(*association) + " array" : "point or cell array";
  throw CliError("the input has no " + what + " '" + requested + "' (" + available + ")");
}

namespace
{

/// Double points whose coordinates are map(x, axis) of those of `mesh`.
template <typename Map>
vtkSmartPointer<vtkPoints> MappedPoints(vtkPolyData* mesh, Map map)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    points->SetPoint(p, map(x[0], 0), map(x[1], 1), map(x[2], 2));
  }
  return points;
}

} // namespace

vtkSmartPointer<vtkPolyData> InUnitFrame(vtkPolyData* mesh, MeshFrame& frame)
{
  double bounds[6];
  mesh->GetBounds(bounds);
  frame.scale = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    frame.centre[a] = 0.5 * bounds[2 * a] + 0.5 * bounds[2 * a + 1];
    frame.scale = std::max(frame.scale, bounds[2 * a + 1] - bounds[2 * a]);
  }
  if (!std::isfinite(frame.scale) || !std::isfinite(frame.centre[0] + frame.centre[1] + frame.centre[2]))
  {
    throw CliError("the mesh spans more than the double range (its size is not a finite number)");
  }
  frame.scale = frame.scale > 0.0 ? frame.scale : 1.0; // a single point: the filter tells
  auto unit = vtkSmartPointer<vtkPolyData>::New();
  unit->ShallowCopy(mesh);
  unit->SetPoints(MappedPoints(mesh, [&frame](double x, int a) { return (x - frame.centre[a]) / frame.scale; }));
  return unit;
}

void BackFromUnitFrame(vtkPolyData* mesh, const MeshFrame& frame)
{
  mesh->SetPoints(MappedPoints(mesh, [&frame](double x, int a) { return x * frame.scale + frame.centre[a]; }));
}

/// Filters the point array 'arrayName' of 'input'; throws "shock filter failed: ..." on error.
FilterRun RunImageFilter(vtkImageData* input, const std::string& arrayName,
  const ShockOptions& options, const ImageMethodOptions& methodOptions, int association)
{
  vtkDataSetAttributes* attributes = association == vtkDataObject::FIELD_ASSOCIATION_CELLS
    ? static_cast<vtkDataSetAttributes*>(input->GetCellData())
    : input->GetPointData();
  vtkNew<vtkImageShockAdvectionFilter> filter;
  ConfigureFilter(filter, options);
  using F = vtkImageShockAdvectionFilter;
  SetIfGiven(filter.Get(), &F::SetMethod, methodOptions.method);
  SetIfGiven(filter.Get(), &F::SetCourantNumber, methodOptions.courantNumber);
  SetIfGiven(filter.Get(), &F::SetMaximumIterations, methodOptions.maximumIterations);
  SetIfGiven(filter.Get(), &F::SetHierarchyLevels, methodOptions.hierarchyLevels);
  SetIfGiven(filter.Get(), &F::SetDomain, methodOptions.domain);
  SetIfGiven(filter.Get(), &F::SetGradientScreening, methodOptions.gradientScreening);
  filter->SetInputArrayToProcess(0, 0, 0, association, arrayName.c_str());
  filter->SetInputData(input);

  FilterRun run;
  vtkDataArray* values = attributes->GetArray(arrayName.c_str());
  run.totalSeconds = TimedUpdate(filter,
    ImageFilterBytes(values ? values->GetNumberOfTuples() : input->GetNumberOfPoints(),
      values ? values->GetNumberOfComponents() : 1));
  run.output = vtkSmartPointer<vtkImageData>::New();
  run.output->ShallowCopy(filter->GetOutput());
  run.time = filter->GetFlowTime();
  run.flowMode = filter->GetFlowMode();
  run.threads = filter->GetNumberOfThreads();
  run.components = values ? values->GetNumberOfComponents() : 0;
  run.flowSeconds = filter->GetLastFlowSeconds();
  run.advectionSeconds = filter->GetLastAdvectionSeconds();
  run.traceSteps = filter->GetLastTraceSteps();
  run.method = filter->GetMethod();
  run.iterations = filter->GetLastIterations();
  run.levels = filter->GetHierarchyLevels();
  run.domain = filter->GetDomain();
  return run;
}

} // namespace shockcli
