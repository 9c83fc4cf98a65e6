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
#include <type_traits>

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

namespace
{
/// What identifies an input between executions (compared only): the image, its size, the filtered array.
std::array<std::uintptr_t, 3> ImageStamp(vtkImageData* input, vtkDataArray* array)
{
  return { reinterpret_cast<std::uintptr_t>(input),
    input ? static_cast<std::uintptr_t>(input->GetNumberOfPoints()) : 0, reinterpret_cast<std::uintptr_t>(array) };
}

/**
 * The halo samples the traces of a piece's own samples needed to be exact:
 * their reach beyond the faces beside them plus the flow's stencil
 * (shock::GridStencilLayers), on each side whose halo does not end at the
 * whole image's boundary (`whole`, the whole extent; null: the sides whose
 * halo has fewer than `layers` samples are taken to end there). There the
 * piece's grid ends where the whole image's does: exact however far the
 * traces went. 0 when no side needed any. `piece`: the piece's point extent.
 */
int HaloNeeded(vtkImageData* withHalo, const int piece[6], bool cellData, int layers, const int* whole,
  const std::array<std::int64_t, 6>& reach, int stencil)
{
  const std::array<std::int64_t, 6> own = SamplesOfExtent(withHalo, piece, cellData);
  const shock::GridShape grid = SampleGrid(withHalo, cellData);
  const int* grown = withHalo->GetExtent();
  std::int64_t needed = 0;
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t below = own[2 * a];
    const std::int64_t above = grid.dimensions[a] - 1 - own[2 * a + 1];
    const bool openBelow = whole ? grown[2 * a] > whole[2 * a] : below >= layers;
    const bool openAbove = whole ? grown[2 * a + 1] < whole[2 * a + 1] : above >= layers;
    if (openBelow)
    {
      needed = std::max(needed, reach[2 * a] + stencil);
    }
    if (openAbove)
    {
      needed = std::max(needed, reach[2 * a + 1] + stencil);
    }
  }
  return static_cast<int>(std::min<std::int64_t>(needed, 1 << 20));
}

/// The piece's point extent with `layers` more on each axis the whole extent spans, within it.
void GrowWithin(const int piece[6], const int whole[6], int layers, int grown[6])
{
  for (int a = 0; a < 3; ++a)
  {
    const bool spans = whole[2 * a + 1] > whole[2 * a];
    grown[2 * a] = spans ? std::max(whole[2 * a], piece[2 * a] - layers) : piece[2 * a];
    grown[2 * a + 1] = spans ? std::min(whole[2 * a + 1], piece[2 * a + 1] + layers) : piece[2 * a + 1];
  }
}

/**
 * `extent` cut to within `whole` on every axis it is not empty on: a request
 * left from before the whole extent shrank may reach beyond it.
 */
void KeepWithinWhole(int extent[6], const int whole[6])
{
  for (int a = 0; a < 3; ++a)
  {
    if (extent[2 * a] <= extent[2 * a + 1])
    {
      extent[2 * a] = std::max(extent[2 * a], whole[2 * a]);
      extent[2 * a + 1] = std::min(extent[2 * a + 1], whole[2 * a + 1]);
    }
  }
}

/**
 * Whether the algorithm that produces the filter's input cuts any extent it is
 * asked for (vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT: image readers, the Wavelet),
 * looking through ParaView's vtkPVPostFilter, which ParaView puts after every
 * source and hands requests and data through unchanged.
 */
bool SourceCutsExtents(vtkAlgorithm* filter)
{
  if (filter->GetNumberOfInputConnections(0) != 1)
  {
    return false;
  }
  int port = 0;
  vtkAlgorithm* upstream = filter->GetInputAlgorithm(0, 0, port);
  while (upstream && upstream->IsA("vtkPVPostFilter") && upstream->GetNumberOfInputPorts() == 1 &&
    upstream->GetNumberOfInputConnections(0) == 1)
  {
    upstream = upstream->GetInputAlgorithm(0, 0, port);
  }
  vtkInformation* info = upstream ? upstream->GetOutputInformation(port) : nullptr;
  return info && info->Has(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT()) &&
    info->Get(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT()) != 0;
}

/// Bytes per sample of every point array (one tuple per point) and cell array (one per cell) of `image`.
double BytesPerSample(vtkImageData* image)
{
  double bytes = 0.0;
  for (int which = 0; which < 2; ++which)
  {
    vtkDataSetAttributes* data = which == 0 ? static_cast<vtkDataSetAttributes*>(image->GetPointData())
                                            : static_cast<vtkDataSetAttributes*>(image->GetCellData());
    const vtkIdType tuples = which == 0 ? image->GetNumberOfPoints() : image->GetNumberOfCells();
    for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    {
      vtkAbstractArray* array = data->GetAbstractArray(k);
      if (array && array->GetNumberOfTuples() == tuples)
      {
        bytes += static_cast<double>(array->GetDataTypeSize()) * array->GetNumberOfComponents();
      }
    }
  }
  return bytes;
}

/**
 * The array `filter` would filter on `image` (the one named by its selection,
 * else the active point scalars, else the active cell scalars), found without
 * messages; null when there is none.
 */
vtkAbstractArray* SelectedArray(vtkAlgorithm* filter, vtkImageData* image)
{
  vtkInformation* selection = filter->GetInputArrayInformation(0);
  vtkAbstractArray* array = nullptr;
  if (selection->Has(vtkDataObject::FIELD_NAME()) && *selection->Get(vtkDataObject::FIELD_NAME()))
  {
    const char* name = selection->Get(vtkDataObject::FIELD_NAME());
    const bool cells = selection->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
      selection->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_CELLS;
    array = cells ? image->GetCellData()->GetAbstractArray(name) : image->GetPointData()->GetAbstractArray(name);
  }
  else
  {
    array = image->GetPointData()->GetScalars() ? image->GetPointData()->GetScalars()
                                                : image->GetCellData()->GetScalars();
  }
  return array;
}

/// Bytes per sample of SelectedArray; 0 when there is none.
double SelectedBytesPerSample(vtkAlgorithm* filter, vtkImageData* image)
{
  vtkAbstractArray* array = SelectedArray(filter, image);
  return array ? static_cast<double>(array->GetDataTypeSize()) * array->GetNumberOfComponents() : 0.0;
}

/// Whether `outer` contains `inner` (point extents; an empty `inner` is contained).
bool Contains(const int outer[6], const int inner[6])
{
  for (int a = 0; a < 3; ++a)
  {
    if (inner[2 * a] > inner[2 * a + 1])
    {
      return true;
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    if (inner[2 * a] < outer[2 * a] || inner[2 * a + 1] > outer[2 * a + 1])
    {
      return false;
    }
  }
  return true;
}
} // namespace

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
  // A piece with its ghost layers (serial streaming): lengths and the trace
  // step cap are the whole image's, as when the whole image is filtered.
  int whole[6];
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  const bool knowsWhole = piece && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  if (knowsWhole)
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  }
  return this->FilterImageArray(input, array, association, output, knowsWhole ? whole : nullptr);
}

int vtkImageShockAdvectionFilter::FilterImageArray(
  vtkImageData* input, vtkDataArray* array, int association, vtkImageData* output, const int* wholeExtent)
{
  // Everything checked: the output starts as the input, arrays shared.
  output->ShallowCopy(input);
  ShockImageInternals::SampleTarget target{ output, array };
  target.wholeExtent = wholeExtent;
  return this->FilterSamples(input, array, association, target);
}

int vtkImageShockAdvectionFilter::FilterSamples(
  vtkImageData* input, vtkDataArray* array, int association, const ShockImageInternals::SampleTarget& target)
{
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  shock::GridShape grid = SampleGrid(input, cellData);
  if (target.wholeExtent) // a piece of a larger image
  {
    for (int a = 0; a < 3; ++a)
    {
      const int points = target.wholeExtent[2 * a + 1] - target.wholeExtent[2 * a] + 1;
      grid.wholeDimensions[a] = std::max(cellData && points > 1 ? points - 1 : points, grid.dimensions[a]);
    }
  }
  // The kernel reads the array in place when it is float or double, and writes
  // its results straight into a new array of the input's type: of the target's
  // samples (a box of the grid's, for a piece with its halo).
  std::array<std::int64_t, 6> written{ { 0, -1, 0, -1, 0, -1 } };
  vtkIdType tuples = -1;
  if (target.extent)
  {
    written = SamplesOfExtent(input, target.extent, cellData);
    tuples = (written[1] - written[0] + 1) * (written[3] - written[2] + 1) * (written[5] - written[4] + 1);
  }
  ShockFilterInternals::KernelOutput filtered = ShockFilterInternals::OutputForKernel(target.replaced, tuples);
  if (target.extent)
  {
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
  std::array<std::int64_t, 6> reach{};
  const bool ran = this->RunKernel(grid, masked ? masked.GetPointer() : array, filtered,
    this->GenerateFlowArrays ? &fields : nullptr, written, aborted, reach, masked ? nullptr : target.layers);
  if (target.haloReach)
  {
    *target.haloReach = reach;
  }
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
  // Checks first, then every process agrees (before the exchange, a collective
  // step). A process without an input image (its input failed to update)
  // says so in the agreement.
  std::string notStarted;
  const bool ok = this->BeginExecution(&notStarted);
  const bool empty = !input || input->GetNumberOfPoints() == 0;
  int association = -1;
  vtkDataArray* array = ok && !empty ? this->GetArrayToFilter(inputVector, association) : nullptr;
  vtkDataObject* given = vtkDataObject::GetData(inputVector[0]);
  std::string error = !ok ? notStarted
    : !input              ? std::string("the input is ") + (given ? std::string("a ") + given->GetClassName() : "missing") +
      ", not image data"
    : !output             ? "the output is not image data"
    : (!empty && !array ? "no array to filter (see the message above)" : "");
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
  const std::string arrays = input ? ShockParallel::ArraysFingerprintText(input) : std::string();
  // The pieces fit together only as pieces of one grid (the halo exchange assumes it).
  const std::string grid = input ? GridText(inputVector[0]->GetInformationObject(0), input) : std::string();
  if (!ShockParallel::Agree(
        controller, error, this->ParametersText(), arrays.empty() ? arrays : arrays + selection, error, grid))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  // Each process asks for a piece of its own: two that ask for the same one
  // leave another piece to no process, and the halos on its side to no one.
  error = RepeatedPieceError(controller, outputVector->GetInformationObject(0));
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const bool hidden = array && AnyHidden(input, array, cellData);
  int whole[6];
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  const bool knowsWhole = inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  if (knowsWhole)
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  }
  // The piece this process owns: the one the source read with its halo
  // (RequestUpdateExtent), or else the input as it came.
  int own[6];
  std::copy(this->AskedPiece, this->AskedPiece + 6, own);
  const bool fromSource = !empty && this->AskedPieceFromSource && Contains(input->GetExtent(), own);
  if (!fromSource)
  {
    input->GetExtent(own);
  }
  // The pieces start with the halo the flow's stencil needs and two samples
  // more, and get more only when the flow lines of their own samples run
  // further (ShockParallel::MoreLayers), up to GhostLevels.
  const int stencil = this->HaloStencil();
  int layers = this->StartingHalo(input, array, controller, stencil);
  // A halo the sources read already is used whole (the same on every process).
  int held = empty ? std::numeric_limits<int>::max() : 0;
  if (fromSource && knowsWhole)
  {
    held = this->GhostLevels;
    for (int a = 0; a < 3; ++a)
    {
      const int* extent = input->GetExtent();
      if (whole[2 * a + 1] > whole[2 * a] && own[2 * a] > whole[2 * a])
      {
        held = std::min(held, own[2 * a] - extent[2 * a]);
      }
      if (whole[2 * a + 1] > whole[2 * a] && own[2 * a + 1] < whole[2 * a + 1])
      {
        held = std::min(held, extent[2 * a + 1] - own[2 * a + 1]);
      }
    }
  }
  int heldEverywhere = held;
  controller->AllReduce(&held, &heldEverywhere, 1, vtkCommunicator::MIN_OP);
  if (stencil >= 0 && heldEverywhere != std::numeric_limits<int>::max())
  {
    layers = std::max(layers, std::min(heldEverywhere, this->GhostLevels));
  }
  for (;;)
  {
    // Read in place when every piece came from its source with this halo
    // (collective: otherwise the halo is exchanged, on every process).
    int needs[6];
    GrowWithin(own, knowsWhole ? whole : input->GetExtent(), layers, needs);
    const bool holds = empty || (fromSource && knowsWhole && Contains(input->GetExtent(), needs));
    const bool inPlace = ShockParallel::Count(controller, !holds) == 0;
    vtkSmartPointer<vtkImageData> withHalo = input;
    // The advection of the values reads a piece where it lies and its halo in
    // layers of their own (shock::LayeredSignal), when the halo lies only
    // along the piece's last axis: no copy of the piece.
    ShockParallel::ImageLayers halo;
    const bool layered = this->ReadsHaloInLayers();
    if (!inPlace)
    {
      vtkLogScopeF(TRACE, "shock: image halo exchange");
      withHalo = ShockParallel::ImageWithHalo(
        controller, input, own, array, cellData, hidden, layers, layered ? &halo : nullptr);
    }
    this->LastGhostLevels = layers;
    this->LastHaloFromSource = inPlace && fromSource;
    this->LastHaloInLayers = halo.used;
    ++this->LastHaloAttempts;
    // The output is the piece (an empty piece of a parallel run is normal).
    vtkDataArray* replaced = array;
    if (fromSource && !std::equal(own, own + 6, input->GetExtent()))
    {
      replaced = PieceOfImage(input, own, array, output);
    }
    else
    {
      output->ShallowCopy(input);
    }
    bool done = true;
    int needed = -1;
    if (withHalo && !empty)
    {
      vtkDataArray* grownArray = inPlace || halo.used
        ? array
        : (cellData ? static_cast<vtkDataSetAttributes*>(withHalo->GetCellData())
                    : static_cast<vtkDataSetAttributes*>(withHalo->GetPointData()))
            ->GetScalars();
      // The kernel traces the piece's own samples only (the halo feeds their
      // flow and traces) and writes them straight into the piece's new array.
      std::array<std::int64_t, 6> reach{};
      ShockImageInternals::SampleTarget target{ output, replaced, own };
      target.wholeExtent = knowsWhole ? whole : nullptr;
      target.haloReach = &reach;
      target.layers = halo.used ? &halo : nullptr;
      vtkLogF(TRACE, "shock: the halo %s",
        inPlace ? "read with the piece" : (halo.used ? "in layers" : "copied with the piece"));
      done = this->FilterSamples(withHalo, grownArray, association, target) != 0;
      if (replaced != array)
      {
        // Aborted or failed before its results: the piece keeps its own values.
        KeepPieceValues(input, own, array, cellData, output, replaced);
      }
      needed = done && stencil >= 0
        ? HaloNeeded(withHalo, own, cellData, layers, knowsWhole ? whole : nullptr, reach, stencil)
        : -1;
      vtkLogF(TRACE, "shock: the own flow lines need a halo of %d of %d samples", needed, layers);
    }
    // Every process learns of a failure, and of a piece whose halo was too small.
    std::string error = "its kernel failed (see its message)";
    if (ShockParallel::AnyFailed(controller, !done, error))
    {
      if (done)
      {
        vtkErrorMacro(<< error);
      }
      return 0;
    }
    if (stencil < 0)
    {
      return 1; // GhostLevels, whatever the flow lines do
    }
    bool tooFew = false;
    const int more =
      ShockParallel::MoreLayers(controller, this->AbortExecute != 0, needed, layers, this->GhostLevels, tooFew);
    if (more > layers)
    {
      vtkLogF(TRACE, "shock: a flow line ran too far into a halo of %d samples: again with %d", layers, more);
      layers = more;
      continue;
    }
    // Kept for the next execution of the same input (a parameter changed).
    this->AgreedHalo = layers;
    this->AgreedInputStamp = ImageStamp(input, array);
    if (tooFew && this->GhostLevels > 0 && controller->GetLocalProcessId() == 0)
    {
      vtkWarningMacro("Flow lines of samples near the pieces' borders run further than the "
        << this->GhostLevels << " halo samples (Ghost Levels) make exact: those samples may differ from a "
        << "serial run. Raise Ghost Levels (up to 64) for the serial result.");
    }
    return 1;
  }
}

int vtkImageShockAdvectionFilter::HaloStencil()
{
  if (this->Method != ADVECTION || this->Domain != VALUES)
  {
    return -1;
  }
  shock::AdvectionParameters parameters = ShockFilterInternals::MakeParameters(this);
  parameters.hierarchyLevels = this->HierarchyLevels;
  return shock::GridStencilLayers(parameters);
}

bool vtkImageShockAdvectionFilter::ReadsHaloInLayers() const
{
  return this->Method == ADVECTION && this->Domain == VALUES && this->HierarchyLevels <= 1;
}

int vtkImageShockAdvectionFilter::StartingHalo(
  vtkImageData* input, vtkDataArray* array, vtkMultiProcessController* controller, int stencil)
{
  if (stencil < 0)
  {
    return this->GhostLevels;
  }
  // The halo the last execution of this same input agreed on (0 for another
  // input). A stale match costs samples, never the result: they only start higher.
  if (ImageStamp(input, array) != this->AgreedInputStamp)
  {
    this->AgreedHalo = 0;
  }
  const int mine = std::min(this->GhostLevels, std::max(stencil + 2, this->AgreedHalo));
  int layers = mine;
  controller->AllReduce(&mine, &layers, 1, vtkCommunicator::MAX_OP); // the same on every process
  return layers;
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
  /// With a piece's halo in layers: `signal` is the piece's own array (shock::LayeredSignal).
  const ShockParallel::ImageLayers* layers;
};
}

bool vtkImageShockAdvectionFilter::RunKernel(const shock::GridShape& grid, vtkDataArray* array,
  const ShockFilterInternals::KernelOutput& filtered, shock::GridFlowFields* fields,
  const std::array<std::int64_t, 6>& written, bool& aborted, std::array<std::int64_t, 6>& reach,
  const ShockParallel::ImageLayers* layers)
{
  // The phase a fraction belongs to (the gradient domain solves after 0.8).
  const bool gradients = this->Domain == GRADIENTS && this->Method == ADVECTION;
  const char* const tracing = this->Method == PDE ? "integrating the shock PDE" : "tracing the flow lines";
  const shock::ProgressFunction progress = [this, gradients, tracing](double fraction) {
    return this->ReportProgress(
      fraction, gradients && fraction >= 0.8 ? "integrating the advected gradients" : tracing);
  };
  ShockFilterInternals::GridRun run{ grid, array, ShockFilterInternals::SignalForKernel(array, this->NumberOfThreads),
    filtered.writer, fields, progress, written, layers };
  shock::Status status;
  if (this->Domain == GRADIENTS && this->Method != ADVECTION)
  {
    status.error = "Domain Gradients works with Method Advection only";
  }
  else if (this->Method == ADVECTION)
  {
    status = this->RunAdvection(run, aborted, reach);
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

shock::Status vtkImageShockAdvectionFilter::RunAdvection(
  const ShockFilterInternals::GridRun& run, bool& aborted, std::array<std::int64_t, 6>& reach)
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
    if (run.layers && this->Domain == VALUES)
    {
      // A piece read where it lies, its halo in layers below and above it.
      using T = std::remove_cv_t<std::remove_pointer_t<decltype(values)>>;
      const auto layer = [](vtkDataArray* a) { return a ? static_cast<const T*>(a->GetVoidPointer(0)) : nullptr; };
      shock::LayeredSignal<T> layered;
      layered.below = layer(run.layers->below);
      layered.piece = values;
      layered.above = layer(run.layers->above);
      layered.pieceFirst = run.layers->pieceFirst;
      layered.pieceEnd = run.layers->pieceEnd;
      return shock::AdvectGridSignal(grid, components, layered, output, parameters, &report, fields, progress);
    }
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
    reach = report.haloReach;
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
  this->LastGhostLevels = 0;
  this->LastHaloAttempts = 0;
  this->LastHaloFromSource = false;
  this->LastHaloInLayers = false;
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
  this->AskedPieceFromSource = false;
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
    // A piece of a distributed image. A source that cuts any extent reads the
    // piece with its halo, as one piece with no ghost levels (so no ghost marks
    // either), and the filter reads it in place; otherwise the piece comes as
    // the source cuts it and its halo from the other processes.
    int grown[6];
    this->AskedPieceFromSource = this->PieceFromSource(inInfo, outInfo, this->AskedPiece, grown);
    if (this->AskedPieceFromSource)
    {
      inInfo->Set(SDDP::UPDATE_EXTENT(), grown, 6);
      inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
      inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
      inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
    else if (outInfo->Has(SDDP::UPDATE_EXTENT()) && inInfo->Has(SDDP::WHOLE_EXTENT()))
    {
      // The request as it came, within the whole extent.
      int extent[6];
      int whole[6];
      outInfo->Get(SDDP::UPDATE_EXTENT(), extent);
      inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
      KeepWithinWhole(extent, whole);
      inInfo->Set(SDDP::UPDATE_EXTENT(), extent, 6);
    }
    return 1;
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

bool vtkImageShockAdvectionFilter::PieceFromSource(
  vtkInformation* inInfo, vtkInformation* outInfo, int own[6], int grown[6])
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!inInfo || !outInfo || !inInfo->Has(SDDP::WHOLE_EXTENT()) || UpdatePieces(outInfo) < 2 ||
    UpdateGhostLevels(outInfo) != 0 || this->Domain == GRADIENTS || ShockParallel::UpstreamIsComposite(this) ||
    !SourceCutsExtents(this))
  {
    return false; // ghost layers asked downstream: the source marks them, as before
  }
  int whole[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  // The pieces of what is asked of this filter, cut as the pipeline cuts a
  // source's (vtkExtentTranslator, the request's split mode).
  int asked[6];
  std::copy(whole, whole + 6, asked);
  if (outInfo->Has(SDDP::UPDATE_EXTENT()))
  {
    outInfo->Get(SDDP::UPDATE_EXTENT(), asked);
    KeepWithinWhole(asked, whole); // the pieces are cut from what exists
  }
  // Every process must take the same way (a reader may read collectively),
  // and every piece needs samples on each axis the image spans (one point
  // thick, a piece has no cells there): else all exchange, as before.
  const int mode = outInfo->Has(vtkExtentTranslator::UPDATE_SPLIT_MODE())
    ? outInfo->Get(vtkExtentTranslator::UPDATE_SPLIT_MODE())
    : vtkExtentTranslator::BLOCK_MODE;
  vtkNew<vtkExtentTranslator> translator;
  // Memory: a piece read with its halo holds every array over the halo, and
  // its output copies the arrays the filter does not change; exchanged, it
  // copies only the filtered array with its halo. Read with the halo when that
  // holds fewer bytes on every piece: the other arrays' bytes per sample times
  // the grown samples below the filtered array's times the piece's (the
  // arrays as the input last came: ParaView executes a source before its
  // filters; unknown before the input's first execution, when the halo is
  // exchanged).
  vtkImageData* last = vtkImageData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT()));
  const double filtered = last ? SelectedBytesPerSample(this, last) : 0.0;
  if (filtered <= 0.0)
  {
    return false;
  }
  const double others = BytesPerSample(last) - filtered;
  const int stencil = this->HaloStencil();
  const int layers =
    stencil < 0 ? this->GhostLevels : std::min(this->GhostLevels, std::max(stencil + 2, this->AgreedHalo));
  const int pieces = UpdatePieces(outInfo);
  const int me = outInfo->Get(SDDP::UPDATE_PIECE_NUMBER());
  // The advection of a float, double or 8-bit array reads a piece where it
  // lies and a halo along the piece's last axis in layers of their own
  // (ShockParallel::ImageLayers): no copy of the piece, and no second
  // execution of the source with the halo. Exchanged then, when every piece's
  // halo lies so.
  bool inLayers = layers > 0 && this->ReadsHaloInLayers() &&
    ShockParallel::ReadableInLayers(vtkDataArray::SafeDownCast(SelectedArray(this, last)));
  for (int p = 0; p < pieces && inLayers; ++p)
  {
    int piece[6];
    int halo[6];
    inLayers = translator->PieceToExtentThreadSafe(p, pieces, 0, asked, piece, mode, 0) != 0;
    GrowWithin(piece, whole, layers, halo);
    inLayers = inLayers && ShockParallel::HaloLayersAxis(piece, halo) >= 0;
  }
  if (inLayers)
  {
    return false;
  }
  for (int p = 0; p < pieces; ++p)
  {
    int piece[6];
    int halo[6];
    if (!translator->PieceToExtentThreadSafe(p, pieces, 0, asked, piece, mode, 0))
    {
      return false;
    }
    GrowWithin(piece, whole, layers, halo);
    double samples[2] = { 1.0, 1.0 };
    for (int a = 0; a < 3; ++a)
    {
      if (piece[2 * a] > piece[2 * a + 1] || (whole[2 * a + 1] > whole[2 * a] && piece[2 * a] == piece[2 * a + 1]))
      {
        return false;
      }
      samples[0] *= piece[2 * a + 1] - piece[2 * a] + 1;
      samples[1] *= halo[2 * a + 1] - halo[2 * a] + 1;
    }
    if (!(others * samples[1] < filtered * samples[0]))
    {
      return false;
    }
    if (p == me)
    {
      std::copy(piece, piece + 6, own);
      std::copy(halo, halo + 6, grown);
    }
  }
  return true;
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
  os << indent << "LastGhostLevels: " << this->LastGhostLevels << "\n";
  os << indent << "LastHaloAttempts: " << this->LastHaloAttempts << "\n";
  os << indent << "LastHaloFromSource: " << (this->LastHaloFromSource ? "true" : "false") << "\n";
  os << indent << "LastHaloInLayers: " << (this->LastHaloInLayers ? "true" : "false") << "\n";
}
