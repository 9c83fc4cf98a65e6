/**
 * @file   CliFilters.h
 * @brief  The shock-filter parameters every subcommand of shockfilter shares
 *         (ShockOptions: options, defaults, ranges), the choice of the array
 *         to filter, and running a filter with its messages caught.
 */
#ifndef CliFilters_h
#define CliFilters_h

#include "CliOptions.h"
#include "ShockIOFiles.h" // DefaultMaxSamples

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkImageShockAdvectionFilter.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
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
const std::vector<Choice>& DomainChoices();
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
 * What a filter needs, the input and the output included, as an upper bound of
 * the peak memory above the program's own (about 50 MiB): an image or volume
 * at most 16 bytes per sample plus 16 per sample and component (measured: 32
 * per pixel of an RGB photo, 20 per voxel of a float volume), a mesh about
 * 1200 bytes per point (measured on meshes of 60,000 points; the surface and
 * the sharpen commands alike).
 */
std::uint64_t ImageFilterBytes(vtkIdType samples, int components);
std::uint64_t MeshFilterBytes(vtkIdType points);

/**
 * Runs the pipeline of a shock filter whose input is set: returns the wall time
 * of the update in seconds; its warnings are printed; throws "shock filter
 * failed: <VTK error>" when it fails, and "out of memory: ... needs about
 * <bytesNeeded>" when an allocation fails.
 */
double TimedUpdate(vtkAlgorithm* filter, std::uint64_t bytesNeeded);

/// What a command that filters an array of its input reads besides the shock options.
struct ArrayCommandSettings
{
  std::string arrayName; ///< --array (empty: the default scalars)
  std::optional<int> association; ///< --association
  bool timings = false;
  std::uint64_t maxSamples = shockio::DefaultMaxSamples;
};

/**
 * The options of ArrayCommandSettings, last on such a command's list: --array
 * (described by `arrayHelp`), --association, --max-samples and --timings.
 */
void AddArrayCommandOptionSpecs(
  std::vector<OptionSpec>& specs, ArrayCommandSettings& settings, const std::string& arrayHelp);

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

/**
 * Where a mesh lies: the mesh filters run on a copy centred at the origin and
 * scaled to unit size, so that their results scale with the mesh at any
 * scale a double holds (lengths to the fourth power would leave the double
 * range beyond about 1e+-75) and the output is put back in place.
 */
struct MeshFrame
{
  double centre[3] = { 0.0, 0.0, 0.0 };
  double scale = 1.0; ///< the largest side of the bounding box
};

/// A copy of `mesh` (sharing all but its points) in unit size (see MeshFrame); throws if its size is not finite.
vtkSmartPointer<vtkPolyData> InUnitFrame(vtkPolyData* mesh, MeshFrame& frame);

/// Moves the points of `mesh` (a filter's output of an InUnitFrame() copy) back into `frame`.
void BackFromUnitFrame(vtkPolyData* mesh, const MeshFrame& frame);

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
  int levels = 1;                                        ///< HierarchyLevels (image filter only)
  int domain = vtkImageShockAdvectionFilter::VALUES;     ///< Domain (image filter only)
};

/// The image filter's own parameters (the PDE baseline); unset ones keep the defaults.
struct ImageMethodOptions
{
  std::optional<int> method;
  std::optional<double> courantNumber;
  std::optional<int> maximumIterations;
  std::optional<int> hierarchyLevels;
  std::optional<int> domain;
  std::optional<double> gradientScreening;
};

/// Filters the point array 'arrayName' of 'input'; throws "shock filter failed: ..." on error.
FilterRun RunImageFilter(vtkImageData* input, const std::string& arrayName,
  const ShockOptions& options, const ImageMethodOptions& methodOptions = ImageMethodOptions(),
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS);

} // namespace shockcli

#endif
