/**
 * @file   CliFilters.h
 * @brief  The shock-filter parameters every subcommand of shockfilter shares
 *         (ShockOptions: options, defaults, ranges), the choice of the array
 *         to filter, and running a filter with its messages caught.
 */
#ifndef CliFilters_h
#define CliFilters_h

#include "CliOptions.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkImageShockAdvectionFilter.h"
#include "vtkSmartPointer.h"

#include <optional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkDataSet;

namespace shockcli
{

const std::vector<Choice>& FlowModeChoices();
const std::vector<Choice>& MethodChoices();
const std::vector<Choice>& SamplingChoices();
const std::vector<Choice>& TracingChoices();
const std::vector<Choice>& AssociationChoices();

/// The filter parameters given on the command line; unset ones keep the filter's defaults.
struct ShockOptions
{
  std::optional<double> time;
  std::optional<int> smoothingPasses;
  std::optional<int> flowMode;
  std::optional<int> flowUpdates;
  std::optional<int> sampling;
  std::optional<int> tracingMode;
  std::optional<double> stepFraction;
  std::optional<int> threads;
};

/// Which of the shared shock options a command accepts.
enum class ShockOptionSet
{
  All,        ///< every parameter
  ThreadsOnly ///< only --threads (the demo fixes the rest)
};

/**
 * The options setting ShockOptions. Ranges are those of vtkShockAdvectionFilter
 * (whose setters would clamp silently); the defaults shown are those of
 * 'defaults', a new filter of the kind the command runs.
 */
std::vector<OptionSpec> ShockOptionSpecs(
  ShockOptions& target, ShockOptionSet set, vtkShockAdvectionFilter* defaults);

/// Sets the given parameters on a filter; the others keep their defaults.
void ConfigureFilter(vtkShockAdvectionFilter* filter, const ShockOptions& options);

/// Updates an algorithm whose input is set; throws "<context>: <VTK error>" when it fails.
void UpdateOrThrow(vtkAlgorithm* algorithm, const std::string& context);

/**
 * Runs the pipeline of a shock filter whose input is set: returns the wall time
 * of the update in seconds; its warnings are printed; throws "shock filter
 * failed: <VTK error>" when it fails.
 */
double TimedUpdate(vtkAlgorithm* filter);

/// The array a command filters.
struct SelectedArray
{
  std::string name;
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS; ///< points or cells
  vtkDataArray* array = nullptr;
};

/**
 * The array to filter: the numeric array named 'requested', looked for in the
 * point data then in the cell data (only in those of 'association' when given);
 * without a name, the active scalars of 'association' (default: the point
 * data), named 'unnamedName' if they have no name. Throws, listing the arrays
 * there are, when there is no such array.
 */
SelectedArray SelectArray(vtkDataSet* data, const std::string& requested, std::optional<int> association,
  const char* unnamedName);

/// The result and measurements of one image filter execution.
struct FilterRun
{
  vtkSmartPointer<vtkImageData> output;
  double time = 0.0;
  int flowMode = 0;
  int threads = 0;
  int components = 0;
  double totalSeconds = 0.0; ///< wall time of Update()
  double flowSeconds = 0.0;
  double advectionSeconds = 0.0;
  vtkTypeUInt64 traceSteps = 0;
  int method = vtkImageShockAdvectionFilter::ADVECTION; ///< image filter only
  vtkTypeInt64 iterations = 0;                           ///< PDE steps (image filter only)
};

/// The image filter's own parameters (the PDE baseline); unset ones keep the defaults.
struct ImageMethodOptions
{
  std::optional<int> method;
  std::optional<double> courantNumber;
  std::optional<int> maximumIterations;
};

/// Filters the point array 'arrayName' of 'input'; throws "shock filter failed: ..." on error.
FilterRun RunImageFilter(vtkImageData* input, const std::string& arrayName,
  const ShockOptions& options, const ImageMethodOptions& methodOptions = ImageMethodOptions());

} // namespace shockcli

#endif
