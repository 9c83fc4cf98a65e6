#include "vtkImageShockAdvectionFilter.h"

#include "GridShockAdvection.h"
#include "GridGradientDomain.h"
#include "GridShockPDE.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkMultiProcessController.h"
#include "vtkCommunicator.h"
#include "vtkMatrix3x3.h"
#include "vtkDataSetAttributes.h"
#include "vtkUnsignedCharArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "ShockFilterInternals.h"
#include "ShockImageInternals.h"
#include "ShockParallel.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <sstream>
#include <cmath>
#include <cstring>
#include <string>

vtkStandardNewMacro(vtkImageShockAdvectionFilter);

namespace
{
/// Domain Gradients on a piece of an image (MPI, or serial streaming).
const char* const GradientPiecesError =
  "Domain Gradients solves one Poisson problem over the whole image and does not run on pieces; "
  "filter the image in one piece (one process), or use Domain Values";

}

using namespace ShockImageInternals;


vtkImageData* vtkImageShockAdvectionFilter::GetOutput()
{
  return this->GetOutput(0);
}

vtkImageData* vtkImageShockAdvectionFilter::GetOutput(int port)
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(port));
}

int vtkImageShockAdvectionFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

vtkImageShockAdvectionFilter::vtkImageShockAdvectionFilter()
{
  // Default array: the active point scalars.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
}

bool vtkImageShockAdvectionFilter::FiltersType(vtkDataObject* input)
{
  return vtkImageData::SafeDownCast(input) != nullptr;
}

int vtkImageShockAdvectionFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (this->PassForeignBlock(inputVector, outputVector))
  {
    return 1;
  }
  // Pieces are normalised by the range over all pieces (collective: before anything can fail).
  bool unknown = false;
  vtkMultiProcessController* controller = this->PieceController(outputVector, unknown);
  this->ParallelValueScale = this->GlobalValueScale(controller, inputVector);
  if (controller)
  {
    // A piece of a distributed image: its halo comes from the other processes.
    return this->FilterPieceWithHalo(controller, inputVector, outputVector);
  }
  if (unknown && this->Domain == GRADIENTS)
  {
    vtkErrorMacro(<< GradientPiecesError);
    return 0;
  }
  // Filter the image (a piece of one with its ghost layers), then hand back what was asked for.
  const int done = this->FilterImage(inputVector, outputVector, unknown);
  if (done)
  {
    this->CropToUpdateExtent(outputVector);
  }
  return done;
}

int vtkImageShockAdvectionFilter::FilterImage(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector, bool piece)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkImageData.");
    return 0;
  }
  if (!this->BeginExecution())
  {
    return 0;
  }
  if (input->GetNumberOfPoints() == 0)
  {
    output->ShallowCopy(input);
    if (!piece) // an empty piece of a parallel run is normal
    {
      vtkWarningMacro("The input image is empty: nothing to filter.");
    }
    return 1;
  }

  int association = -1;
  vtkDataArray* array = this->GetArrayToFilter(inputVector, association);
  if (!array)
  {
    return 0;
  }
  const std::string error = CheckImageArray(input, array, association);
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  return this->FilterImageArray(input, array, association, output);
}

int vtkImageShockAdvectionFilter::FilterImageArray(
  vtkImageData* input, vtkDataArray* array, int association, vtkImageData* output)
{
  // Everything checked: the output starts as the input, arrays shared.
  output->ShallowCopy(input);
  return this->FilterSamples(input, array, association, ShockImageInternals::SampleTarget{ output, array });
}

int vtkImageShockAdvectionFilter::FilterSamples(
  vtkImageData* input, vtkDataArray* array, int association, const ShockImageInternals::SampleTarget& target)
{
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const shock::GridShape grid = SampleGrid(input, cellData);
  // The kernel reads the array in place when it is float or double, and writes
  // its results straight into a new array of the input's type: of the target's
  // samples (a box of the grid's, for a piece with its halo).
  ShockFilterInternals::KernelOutput filtered = ShockFilterInternals::OutputForKernel(target.replaced);
  std::array<std::int64_t, 6> written{ { 0, -1, 0, -1, 0, -1 } };
  if (target.extent)
  {
    written = SamplesOfExtent(input, target.extent, cellData);
    filtered.writer = BoxWriter(filtered.writer, grid, written, array->GetNumberOfComponents());
  }
  // Blanked samples (vtkGhostType HIDDENPOINT, or HIDDENCELL for cell data)
  // neither feed nor receive values: the kernel sees them as NaN (a sample
  // that carries no flow and is never interpolated) and they keep their own.
  vtkSmartPointer<vtkDataArray> masked = MaskHiddenSamples(input, array, cellData);
  if (masked)
  {
    filtered.writer = KeepHiddenValues(filtered.writer, input, array, cellData);
  }
  shock::GridFlowFields fields;
  bool aborted = false;
  const bool ran = this->RunKernel(grid, masked ? masked.GetPointer() : array, filtered,
    this->GenerateFlowArrays ? &fields : nullptr, written, aborted);
  if (!ran)
  {
    return 0;
  }
  if (aborted)
  {
    return 1; // aborted: the output holds the unfiltered input
  }
  vtkImageData* output = target.output;
  vtkDataSetAttributes* attributes =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetCellData()) : output->GetPointData();
  ShockFilterInternals::ReplaceArray(attributes, target.replaced, filtered.array);
  if (this->GenerateFlowArrays)
  {
    if (!target.extent)
    {
      AttachFlowArrays(output, cellData, grid, fields);
      return 1;
    }
    // The flow of the grid with its halo, cropped to the target's extent.
    vtkNew<vtkImageData> flow;
    flow->CopyStructure(input);
    AttachFlowArrays(flow, cellData, grid, fields);
    if (!CropByRows(flow, target.extent))
    {
      flow->Crop(target.extent);
    }
    TakeResultArrays(flow, output, nullptr);
  }
  return 1;
}

int vtkImageShockAdvectionFilter::FilterPieceWithHalo(vtkMultiProcessController* controller,
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkImageData."); // the same on every process
    return 0;
  }
  // Checks first, then every process agrees (before the exchange, a collective step).
  const bool ok = this->BeginExecution();
  const bool empty = input->GetNumberOfPoints() == 0;
  int association = -1;
  vtkDataArray* array = ok && !empty ? this->GetArrayToFilter(inputVector, association) : nullptr;
  std::string error = !ok ? "the execution could not start" : (!empty && !array ? "no array to filter (see the message above)" : "");
  std::string selection;
  if (array)
  {
    error = CheckImageArray(input, array, association);
    selection = std::string("filtered ") + (association == vtkDataObject::FIELD_ASSOCIATION_CELLS ? "cell" : "point") +
      " array '" + (array->GetName() ? array->GetName() : "(unnamed)") + "';";
  }
  if (error.empty() && this->Domain == GRADIENTS)
  {
    error = GradientPiecesError; // the same on every process, before the collective steps
  }
  const std::string arrays = ShockParallel::ArraysFingerprintText(input);
  if (!ShockParallel::Agree(controller, error, this->ParametersText(), arrays.empty() ? arrays : arrays + selection, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  vtkSmartPointer<vtkImageData> withHalo;
  {
    vtkLogScopeF(TRACE, "shock: image halo exchange");
    withHalo = ShockParallel::ImageWithHalo(controller, input, array, cellData,
      array && AnyHidden(input, array, cellData), this->GhostLevels);
  }
  if (!withHalo)
  {
    output->ShallowCopy(input); // an empty piece of a parallel run is normal
    return 1;
  }
  vtkDataArray* grownArray = (cellData ? static_cast<vtkDataSetAttributes*>(withHalo->GetCellData())
                                        : static_cast<vtkDataSetAttributes*>(withHalo->GetPointData()))
                               ->GetScalars();
  // The kernel traces the piece's own samples only (the halo feeds their
  // flow and traces) and writes them straight into the piece's new array.
  output->ShallowCopy(input);
  return this->FilterSamples(withHalo, grownArray, association,
    ShockImageInternals::SampleTarget{ output, array, input->GetExtent() });
}

namespace ShockFilterInternals
{
/// What a grid kernel runs on: the samples' shape and signal, where its results go, its flow fields and progress.
struct GridRun
{
  const shock::GridShape& grid;
  vtkDataArray* array;
  KernelSignal signal;
  const shock::SampleWriter& output;
  shock::GridFlowFields* fields;
  shock::ProgressFunction progress;
  const std::array<std::int64_t, 6>& written; ///< AdvectionParameters::writtenSamples
};
}

bool vtkImageShockAdvectionFilter::RunKernel(const shock::GridShape& grid, vtkDataArray* array,
  const ShockFilterInternals::KernelOutput& filtered, shock::GridFlowFields* fields,
  const std::array<std::int64_t, 6>& written, bool& aborted)
{
  // The phase a fraction belongs to (the gradient domain solves after 0.8).
  const bool gradients = this->Domain == GRADIENTS && this->Method == ADVECTION;
  const char* const tracing = this->Method == PDE ? "integrating the shock PDE" : "tracing the flow lines";
  const shock::ProgressFunction progress = [this, gradients, tracing](double fraction) {
    return this->ReportProgress(
      fraction, gradients && fraction >= 0.8 ? "integrating the advected gradients" : tracing);
  };
  ShockFilterInternals::GridRun run{ grid, array, ShockFilterInternals::SignalForKernel(array, this->NumberOfThreads),
    filtered.writer, fields, progress, written };
  shock::Status status;
  if (this->Domain == GRADIENTS && this->Method != ADVECTION)
  {
    status.error = "Domain Gradients works with Method Advection only";
  }
  else if (this->Method == ADVECTION)
  {
    status = this->RunAdvection(run, aborted);
  }
  else
  {
    status = this->RunPDE(run, aborted);
  }
  if (!status.Ok())
  {
    vtkErrorMacro("Shock filter failed: " << status.error);
    return false;
  }
  return true;
}

shock::Status vtkImageShockAdvectionFilter::RunAdvection(const ShockFilterInternals::GridRun& run, bool& aborted)
{
  const shock::GridShape& grid = run.grid;
  const int components = run.array->GetNumberOfComponents();
  const shock::SampleWriter& output = run.output;
  shock::GridFlowFields* fields = run.fields;
  const shock::ProgressFunction& progress = run.progress;
  const ShockFilterInternals::KernelSignal& signal = run.signal;
  shock::AdvectionReport report;
  shock::AdvectionParameters parameters = ShockFilterInternals::MakeParameters(this);
  parameters.hierarchyLevels = this->HierarchyLevels;
  parameters.writtenSamples = run.written;
  shock::GradientDomainParameters domain;
  domain.screening = this->GradientScreening;
  const auto advect = [&](const auto* values) {
    return this->Domain == GRADIENTS
      ? shock::AdvectGridGradients(grid, components, values, output, parameters, domain, &report, fields, progress)
      : shock::AdvectGridSignal(grid, components, values, output, parameters, &report, fields, progress);
  };
  const shock::Status status =
    signal.floats ? advect(signal.floats) : (signal.bytes ? advect(signal.bytes) : advect(signal.doubles));
  if (status.Ok())
  {
    this->RecordRun(report.flowSeconds, report.advectionSeconds, report.traceSteps, report.truncatedTraces);
    aborted = report.aborted;
  }
  return status;
}

shock::Status vtkImageShockAdvectionFilter::RunPDE(ShockFilterInternals::GridRun& run, bool& aborted)
{
  vtkDataArray* array = run.array;
  ShockFilterInternals::KernelSignal& signal = run.signal;
  shock::PDEParameters parameters;
  parameters.time = this->FlowTime;
  parameters.smoothingPasses = this->SmoothingPasses;
  parameters.courantNumber = this->CourantNumber;
  parameters.maximumIterations = this->MaximumIterations;
  parameters.numberOfThreads = this->NumberOfThreads;
  parameters.valueScale = this->ParallelValueScale;
  shock::PDEReport report;
  // The PDE works on double buffers.
  if (!signal.doubles)
  {
    const vtkIdType count = array->GetNumberOfValues();
    signal.doubleCopy = shock::AllocateLargeArray<double>(count);
    if (signal.floats)
    {
      std::copy(signal.floats, signal.floats + count, signal.doubleCopy.get());
    }
    else
    {
      std::copy(signal.bytes, signal.bytes + count, signal.doubleCopy.get());
    }
    signal.doubles = signal.doubleCopy.get();
  }
  const shock::LargeArray<double> solved = shock::AllocateLargeArray<double>(array->GetNumberOfValues());
  const shock::Status status = shock::SolveGridShockPDE(run.grid, array->GetNumberOfComponents(), signal.doubles,
    solved.get(), parameters, &report, run.fields, run.progress);
  if (status.Ok())
  {
    run.output(0, run.grid.NumberOfSamples(), solved.get());
    this->RecordRun(report.flowSeconds, report.updateSeconds, 0, 0);
    this->LastIterations = report.iterations;
    this->LastReachedTime = report.reachedTime;
    aborted = report.aborted;
    if (report.iterationLimit)
    {
      vtkWarningMacro("The PDE stopped at MaximumIterations (" << this->MaximumIterations << " steps) at flow time "
                                                               << report.reachedTime << " of " << this->FlowTime
                                                               << ".");
    }
  }
  return status;
}

void vtkImageShockAdvectionFilter::ResetMeasurements()
{
  this->Superclass::ResetMeasurements();
  this->LastIterations = 0;
  this->LastReachedTime = 0.0;
}

// --- Parallel execution: ghost samples in, cropped output out ------------------
//
// VTK 9 pipelines keep UPDATE_EXTENT at the whole extent when pieces are
// requested: the source (CAN_PRODUCE_SUB_EXTENT) splits it with an extent
// translator and adds UPDATE_NUMBER_OF_GHOST_LEVELS layers. So a piece gets
// its ghost samples from the ghost levels; an explicit sub-extent request
// (one piece) is grown here instead. Either way the output is cropped back to
// what was asked for.

int vtkImageShockAdvectionFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!inInfo || !outInfo)
  {
    return 1;
  }
  if (ShockParallel::UpstreamIsComposite(this))
  {
    return 1; // composite input: each block as it comes (no ghost layers, no crop)
  }
  bool unknown = false;
  if (UpdatePieces(outInfo) > 1 && this->PieceController(outputVector, unknown))
  {
    return 1; // a piece of a distributed image: the halo comes from the other processes
  }
  if (UpdatePieces(outInfo) > 1)
  {
    // No controller to exchange a halo (serial streaming): the source adds the
    // layers to the piece it cuts (and marks them as ghosts), cropped afterwards.
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), UpdateGhostLevels(outInfo) + this->GhostLevels);
  }
  else if (outInfo->Has(SDDP::UPDATE_EXTENT()) && inInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    // A sub-extent (vtkExtractVOI, a zoomed view): the whole image is filtered
    // and cropped, so that the samples asked for are those of the whole
    // image's result (its data range normalises the flow, and a flow line may
    // start anywhere); an empty request stays empty.
    int extent[6];
    int whole[6];
    outInfo->Get(SDDP::UPDATE_EXTENT(), extent);
    inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    const bool empty = extent[0] > extent[1] || extent[2] > extent[3] || extent[4] > extent[5];
    if (!empty && !std::equal(extent, extent + 6, whole))
    {
      inInfo->Set(SDDP::UPDATE_EXTENT(), whole, 6);
    }
  }
  return 1;
}

void vtkImageShockAdvectionFilter::CropToUpdateExtent(vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = outInfo ? vtkImageData::GetData(outInfo) : nullptr;
  if (!output || !outInfo->Has(SDDP::UPDATE_EXTENT()) || output->GetNumberOfPoints() == 0)
  {
    return;
  }
  int requested[6];
  outInfo->Get(SDDP::UPDATE_EXTENT(), requested);
  for (int i = 0; i < 6; i += 2)
  {
    if (requested[i] > requested[i + 1])
    {
      return; // an empty request: leave the output as it is
    }
  }
  int target[6];
  std::copy(requested, requested + 6, target);
  if (UpdatePieces(outInfo) > 1)
  {
    // Keep the piece with the ghost levels asked of this filter and drop the layers
    // it added (or more, when the source kept more from an earlier request). But a
    // source that cannot cut pieces (e.g. a legacy .vtk reader) hands the whole
    // extent to one process and nothing to the others: keep that whole.
    const int* extent = output->GetExtent();
    int asked[6];
    PieceExtent(outInfo, requested, UpdateGhostLevels(outInfo) + this->GhostLevels, asked);
    if (std::equal(extent, extent + 6, requested) && !std::equal(asked, asked + 6, requested))
    {
      return;
    }
    PieceExtent(outInfo, requested, UpdateGhostLevels(outInfo), target);
  }
  const int* extent = output->GetExtent();
  if (!std::equal(extent, extent + 6, target))
  {
    if (!CropByRows(output, target))
    {
      output->Crop(target); // intersects with the filtered extent
    }
  }
}

std::string vtkImageShockAdvectionFilter::ParametersText()
{
  std::ostringstream text;
  text.precision(17);
  text << this->Superclass::ParametersText()
       << "Method=" << this->Method << ";"
       << "Domain=" << this->Domain << ";"
       << "GradientScreening=" << this->GradientScreening << ";"
       << "HierarchyLevels=" << this->HierarchyLevels << ";"
       << "CourantNumber=" << this->CourantNumber << ";"
       << "MaximumIterations=" << this->MaximumIterations << ";";
  return text.str();
}

void vtkImageShockAdvectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << (this->Method == ADVECTION ? "Advection" : "PDE") << "\n";
  os << indent << "Domain: " << (this->Domain == VALUES ? "Values" : "Gradients") << "\n";
  os << indent << "GradientScreening: " << this->GradientScreening << "\n";
  os << indent << "HierarchyLevels: " << this->HierarchyLevels << "\n";
  os << indent << "CourantNumber: " << this->CourantNumber << "\n";
  os << indent << "MaximumIterations: " << this->MaximumIterations << "\n";
  os << indent << "LastIterations: " << this->LastIterations << "\n";
  os << indent << "LastReachedTime: " << this->LastReachedTime << "\n";
}
