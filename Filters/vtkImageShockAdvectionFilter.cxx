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
shock::GridShape SampleGrid(vtkImageData* image, bool cellData);

/// Domain Gradients on a piece of an image (MPI, or serial streaming).
const char* const GradientPiecesError =
  "Domain Gradients solves one Poisson problem over the whole image and does not run on pieces; "
  "filter the image in one piece (one process), or use Domain Values";

/// The length of column `a` of the image's direction matrix: the scale it gives axis a.
double AxisScale(vtkImageData* image, int a)
{
  const vtkMatrix3x3* d = image->GetDirectionMatrix();
  return std::sqrt(d->GetElement(0, a) * d->GetElement(0, a) + d->GetElement(1, a) * d->GetElement(1, a) +
    d->GetElement(2, a) * d->GetElement(2, a));
}

/**
 * "" when the direction matrix is finite with orthogonal, non-zero columns
 * (a rotation or reflection of the axes, each scaled: the scales count as
 * spacing), else the message. A shear has no grid of the paper.
 */
std::string CheckDirection(vtkImageData* image)
{
  const vtkMatrix3x3* d = image->GetDirectionMatrix();
  double scale[3];
  for (int a = 0; a < 3; ++a)
  {
    for (int r = 0; r < 3; ++r)
    {
      if (!std::isfinite(d->GetElement(r, a)))
      {
        return "The image direction matrix has a non-finite entry: set a rotation (e.g. the identity).";
      }
    }
    scale[a] = AxisScale(image, a);
    if (!(scale[a] > 0.0))
    {
      return "The image direction matrix is singular (column " + std::to_string(a) +
        " is zero): set a rotation (e.g. the identity).";
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    for (int b = a + 1; b < 3; ++b)
    {
      double dot = 0.0;
      for (int r = 0; r < 3; ++r)
      {
        dot += d->GetElement(r, a) * d->GetElement(r, b);
      }
      if (std::abs(dot) > 1e-4 * scale[a] * scale[b]) // orientations written with 4-6 decimals pass
      {
        return "The image direction matrix shears the axes (columns " + std::to_string(a) + " and " +
          std::to_string(b) + " are not orthogonal): the filter needs a rotation, scaled per axis at most; "
          "resample the image onto such a grid first.";
      }
    }
  }
  return "";
}
bool CropByRows(vtkImageData* image, const int target[6]);

/// The blanking mark of samples: HIDDENCELL for cell data, HIDDENPOINT for point data.
unsigned char HiddenMark(bool cellData)
{
  return static_cast<unsigned char>(
    cellData ? static_cast<int>(vtkDataSetAttributes::HIDDENCELL) : static_cast<int>(vtkDataSetAttributes::HIDDENPOINT));
}

/// Whether sample `t` of `image` (points, or cells for cell data) is blanked.
bool IsHidden(vtkImageData* image, bool cellData, vtkIdType t)
{
  vtkUnsignedCharArray* ghosts = cellData ? image->GetCellGhostArray() : image->GetPointGhostArray();
  return ghosts && t < ghosts->GetNumberOfTuples() && (ghosts->GetValue(t) & HiddenMark(cellData));
}

/// Whether any sample of `array` on `image` is blanked (a scan of the marks only).
bool AnyHidden(vtkImageData* image, vtkDataArray* array, bool cellData)
{
  vtkUnsignedCharArray* ghosts = cellData ? image->GetCellGhostArray() : image->GetPointGhostArray();
  if (!array || !ghosts || ghosts->GetNumberOfTuples() != array->GetNumberOfTuples())
  {
    return false;
  }
  const unsigned char mark = HiddenMark(cellData);
  for (vtkIdType t = 0; t < ghosts->GetNumberOfTuples(); ++t)
  {
    if (ghosts->GetValue(t) & mark)
    {
      return true;
    }
  }
  return false;
}

/**
 * A double copy of `array` whose blanked samples (the ghost array's
 * HIDDENPOINT, or HIDDENCELL for cell data) are NaN, or nullptr when none is
 * blanked.
 */
vtkSmartPointer<vtkDataArray> MaskHiddenSamples(vtkImageData* image, vtkDataArray* array, bool cellData)
{
  if (!AnyHidden(image, array, cellData))
  {
    return nullptr;
  }
  vtkSmartPointer<vtkDoubleArray> masked;
  for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
  {
    if (!IsHidden(image, cellData, t))
    {
      continue;
    }
    if (!masked)
    {
      masked = vtkSmartPointer<vtkDoubleArray>::New();
      masked->DeepCopy(array); // as doubles
      masked->SetName(array->GetName());
    }
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      masked->SetComponent(t, c, std::numeric_limits<double>::quiet_NaN());
    }
  }
  return masked;
}

/// "" when `array` (of `association`) can be filtered on `image`, else the message.
std::string CheckImageArray(vtkImageData* image, vtkDataArray* array, int association)
{
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const std::string direction = CheckDirection(image);
  if (!direction.empty())
  {
    return direction;
  }
  const shock::GridShape grid = SampleGrid(image, cellData);
  std::ostringstream error;
  if (array->GetNumberOfTuples() != grid.NumberOfSamples())
  {
    error << "Array '" << (array->GetName() ? array->GetName() : "(unnamed)") << "' has "
          << array->GetNumberOfTuples() << " tuples, the image has " << grid.NumberOfSamples()
          << (cellData ? " cells." : " points.");
    return error.str();
  }
  for (int a = 0; a < 3; ++a)
  {
    if (grid.dimensions[a] > 1 && !(grid.spacing[a] > 0.0 && std::isfinite(grid.spacing[a])))
    {
      error << "The image spacing must be finite and non-zero along every axis with more "
               "than one sample; axis "
            << a << " has spacing " << image->GetSpacing()[a] << ".";
      return error.str();
    }
  }
  return "";
}

/**
 * The grid of the processed samples: points, or cell centres for cell data;
 * the physical distance between samples along each axis (|spacing| times the
 * direction matrix's scale of that axis: diag(4,1,1) is spacing 4 along x).
 */
shock::GridShape SampleGrid(vtkImageData* image, bool cellData)
{
  shock::GridShape shape;
  int dims[3];
  image->GetDimensions(dims);
  const double* spacing = image->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    shape.dimensions[a] = cellData ? std::max(dims[a] - 1, 1) : dims[a];
    shape.spacing[a] = std::abs(spacing[a]) * AxisScale(image, a);
  }
  return shape;
}

/// Flow of the kernel (grid axes, physical lengths) in world axes: axis flips,
/// then the direction matrix's unit columns.
void ToWorldAxes(vtkImageData* image, const double* gridVector, double* world)
{
  const double* spacing = image->GetSpacing();
  double flipped[3];
  for (int a = 0; a < 3; ++a)
  {
    const double scale = AxisScale(image, a);
    flipped[a] = (spacing[a] < 0.0 ? -gridVector[a] : gridVector[a]) / (scale > 0.0 ? scale : 1.0);
  }
  image->GetDirectionMatrix()->MultiplyPoint(flipped, world);
}

/// Attach ShockPotential and ShockFlow to the output (see the class documentation).
/**
 * The arrays of `filtered` (a piece's result, cropped to it) into `output`:
 * its scalars (the filtered array) in place of `array`, the flow arrays added.
 */
void TakeResultArrays(vtkImageData* filtered, vtkImageData* output, vtkDataArray* array)
{
  for (int which = 0; which < 2; ++which)
  {
    vtkDataSetAttributes* from = which == 0 ? static_cast<vtkDataSetAttributes*>(filtered->GetPointData())
                                            : static_cast<vtkDataSetAttributes*>(filtered->GetCellData());
    vtkDataSetAttributes* to = which == 0 ? static_cast<vtkDataSetAttributes*>(output->GetPointData())
                                          : static_cast<vtkDataSetAttributes*>(output->GetCellData());
    for (int k = 0; k < from->GetNumberOfArrays(); ++k)
    {
      vtkAbstractArray* result = from->GetAbstractArray(k);
      if (result == from->GetScalars() && result != nullptr)
      {
        ShockFilterInternals::ReplaceArray(to, array, vtkDataArray::SafeDownCast(result));
      }
      else if (result)
      {
        to->AddArray(result);
      }
    }
  }
}

void AttachFlowArrays(vtkImageData* output, bool cellData, const shock::GridShape& grid,
  const shock::GridFlowFields& fields)
{
  vtkNew<vtkDoubleArray> potential;
  potential->SetName(vtkShockAdvectionFilter::PotentialArrayName());
  potential->SetNumberOfTuples(static_cast<vtkIdType>(fields.potential.size()));
  std::copy(fields.potential.begin(), fields.potential.end(), potential->GetPointer(0));

  vtkNew<vtkDoubleArray> flow;
  flow->SetName(vtkShockAdvectionFilter::FlowArrayName());
  flow->SetNumberOfComponents(3);
  // Faces of the sample grid: the image cells (point data) or the points between
  // cell centres (cell data).
  int dims[3];
  output->GetDimensions(dims);
  const vtkIdType tuples = cellData ? output->GetNumberOfPoints() : output->GetNumberOfCells();
  flow->SetNumberOfTuples(tuples);
  flow->Fill(0.0);
  std::array<std::int64_t, 3> faces;
  for (int a = 0; a < 3; ++a)
  {
    faces[a] = std::max(grid.dimensions[a] - 1, 1);
  }
  double world[3];
  if (!cellData)
  {
    for (vtkIdType f = 0; f < tuples; ++f)
    {
      ToWorldAxes(output, &fields.flow[3 * f], world);
      flow->SetTypedTuple(f, world);
    }
  }
  else
  {
    for (int k = 0; k < dims[2]; ++k)
    {
      for (int j = 0; j < dims[1]; ++j)
      {
        for (int i = 0; i < dims[0]; ++i)
        {
          int ijk[3] = { i, j, k };
          std::int64_t face = 0;
          std::int64_t stride = 1;
          bool interior = true;
          for (int a = 0; a < 3 && interior; ++a)
          {
            // A point is interior along an axis the cell grid spans; flat axes map to 0.
            const std::int64_t c = grid.dimensions[a] > 1 ? ijk[a] - 1 : 0;
            interior = c >= 0 && c < faces[a];
            face += c * stride;
            stride *= faces[a];
          }
          if (interior)
          {
            ToWorldAxes(output, &fields.flow[3 * face], world);
            flow->SetTypedTuple(output->ComputePointId(ijk), world);
          }
        }
      }
    }
  }
  vtkDataSetAttributes* sampleData =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetCellData()) : output->GetPointData();
  vtkDataSetAttributes* faceData =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetPointData()) : output->GetCellData();
  sampleData->AddArray(potential);
  faceData->AddArray(flow);
}
}

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
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const shock::GridShape grid = SampleGrid(input, cellData);
  // Everything checked: the output starts as the input, arrays shared. The
  // kernel reads the array in place when it is float or double, and writes its
  // results straight into a new array of the input's type.
  output->ShallowCopy(input);
  ShockFilterInternals::KernelOutput filtered = ShockFilterInternals::OutputForKernel(array);
  // Blanked samples (vtkGhostType HIDDENPOINT, or HIDDENCELL for cell data)
  // neither feed nor receive values: the kernel sees them as NaN (a sample
  // that carries no flow and is never interpolated) and they keep their own.
  vtkSmartPointer<vtkDataArray> masked = MaskHiddenSamples(input, array, cellData);
  if (masked)
  {
    // The blanked samples' own values, read here once (the writer runs on
    // several threads at once: it reads only these plain vectors).
    const int C = array->GetNumberOfComponents();
    auto hiddenAt = std::make_shared<std::vector<std::int64_t>>(); // sorted sample indices
    auto hiddenValues = std::make_shared<std::vector<double>>();
    for (vtkIdType t = 0; t < masked->GetNumberOfTuples(); ++t)
    {
      if (IsHidden(input, cellData, t))
      {
        hiddenAt->push_back(t);
        for (int c = 0; c < C; ++c)
        {
          hiddenValues->push_back(array->GetComponent(t, c));
        }
      }
    }
    const shock::SampleWriter typed = filtered.writer;
    filtered.writer = [typed, C, hiddenAt, hiddenValues](std::int64_t first, std::int64_t count, const double* in) {
      auto k = std::lower_bound(hiddenAt->begin(), hiddenAt->end(), first);
      if (k == hiddenAt->end() || *k >= first + count)
      {
        typed(first, count, in); // no blanked sample in this run
        return;
      }
      std::vector<double> values(in, in + count * C);
      for (; k != hiddenAt->end() && *k < first + count; ++k)
      {
        const size_t which = static_cast<size_t>(k - hiddenAt->begin());
        std::copy(hiddenValues->begin() + static_cast<long>(which * C),
          hiddenValues->begin() + static_cast<long>((which + 1) * C), values.begin() + (*k - first) * C);
      }
      typed(first, count, values.data());
    };
  }
  shock::GridFlowFields fields;
  bool aborted = false;
  const bool ran = this->RunKernel(
    grid, masked ? masked.GetPointer() : array, filtered, this->GenerateFlowArrays ? &fields : nullptr, aborted);
  if (!ran)
  {
    return 0;
  }
  if (aborted)
  {
    return 1; // aborted: the output holds the unfiltered input
  }

  vtkDataSetAttributes* attributes =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetCellData()) : output->GetPointData();
  ShockFilterInternals::ReplaceArray(attributes, array, filtered.array);
  if (this->GenerateFlowArrays)
  {
    AttachFlowArrays(output, cellData, grid, fields);
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
  vtkNew<vtkImageData> filtered;
  vtkDataArray* grownArray = (cellData ? static_cast<vtkDataSetAttributes*>(withHalo->GetCellData())
                                        : static_cast<vtkDataSetAttributes*>(withHalo->GetPointData()))
                               ->GetScalars();
  if (!this->FilterImageArray(withHalo, grownArray, association, filtered))
  {
    return 0;
  }
  // Back to the piece: its rows of the filtered array and of the flow arrays.
  int crop[6];
  input->GetExtent(crop);
  if (!CropByRows(filtered, crop))
  {
    filtered->Crop(crop);
  }
  output->ShallowCopy(input);
  TakeResultArrays(filtered, output, array);
  return 1;
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
};
}

bool vtkImageShockAdvectionFilter::RunKernel(const shock::GridShape& grid, vtkDataArray* array,
  const ShockFilterInternals::KernelOutput& filtered, shock::GridFlowFields* fields,
  bool& aborted)
{
  // The phase a fraction belongs to (the gradient domain solves after 0.8).
  const bool gradients = this->Domain == GRADIENTS && this->Method == ADVECTION;
  const char* const tracing = this->Method == PDE ? "integrating the shock PDE" : "tracing the flow lines";
  const shock::ProgressFunction progress = [this, gradients, tracing](double fraction) {
    return this->ReportProgress(
      fraction, gradients && fraction >= 0.8 ? "integrating the advected gradients" : tracing);
  };
  ShockFilterInternals::GridRun run{ grid, array, ShockFilterInternals::SignalForKernel(array, this->NumberOfThreads),
    filtered.writer, fields, progress };
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

namespace
{
int UpdatePieces(vtkInformation* info)
{
  return info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
}

int UpdateGhostLevels(vtkInformation* info)
{
  return info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS())
    ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS())
    : 0;
}

/**
 * Crop `image` to `target` (within its extent) as vtkImageData::Crop does, but
 * a row at a time: each point and cell array is copied with memcpy instead of
 * one vtkDataSetAttributes::CopyData call per tuple. Returns false, changing nothing, when an
 * array is not a plain named vtkDataArray or an axis the image spans would be
 * left with a single point (vtkImageData::Crop then does it).
 */
bool CropByRows(vtkImageData* image, const int target[6])
{
  const int* extent = image->GetExtent();
  int crop[6];
  for (int a = 0; a < 3; ++a)
  {
    crop[2 * a] = std::max(target[2 * a], extent[2 * a]);
    crop[2 * a + 1] = std::min(target[2 * a + 1], extent[2 * a + 1]);
    const bool spans = extent[2 * a + 1] > extent[2 * a];
    if (crop[2 * a] > crop[2 * a + 1] || (spans && crop[2 * a] == crop[2 * a + 1]))
    {
      return false;
    }
  }
  // Sample boxes of points and cells: first index, count, and the input's count per axis.
  struct Box
  {
    vtkIdType first[3], count[3], dims[3];
  } points{}, cells{};
  for (int a = 0; a < 3; ++a)
  {
    const bool spans = extent[2 * a + 1] > extent[2 * a];
    points.first[a] = crop[2 * a] - extent[2 * a];
    points.count[a] = crop[2 * a + 1] - crop[2 * a] + 1;
    points.dims[a] = extent[2 * a + 1] - extent[2 * a] + 1;
    cells.first[a] = spans ? points.first[a] : 0;
    cells.count[a] = spans ? points.count[a] - 1 : 1;
    cells.dims[a] = spans ? points.dims[a] - 1 : 1;
  }
  vtkDataSetAttributes* attributes[2] = { image->GetPointData(), image->GetCellData() };
  for (vtkDataSetAttributes* data : attributes)
  {
    for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    {
      vtkDataArray* array = data->GetArray(k);
      if (!array || !array->GetName() || !array->HasStandardMemoryLayout())
      {
        return false;
      }
    }
  }
  for (int which = 0; which < 2; ++which)
  {
    const Box& box = which == 0 ? points : cells;
    vtkDataSetAttributes* data = attributes[which];
    for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    {
      vtkDataArray* array = data->GetArray(k);
      const size_t tupleBytes = static_cast<size_t>(array->GetDataTypeSize()) * array->GetNumberOfComponents();
      if (array->GetNumberOfTuples() != box.dims[0] * box.dims[1] * box.dims[2])
      {
        continue; // not one tuple per sample: vtkImageData::Crop would not know it either
      }
      vtkSmartPointer<vtkDataArray> cropped = vtk::TakeSmartPointer(array->NewInstance());
      cropped->SetName(array->GetName());
      cropped->SetNumberOfComponents(array->GetNumberOfComponents());
      cropped->CopyComponentNames(array);
      cropped->SetNumberOfTuples(box.count[0] * box.count[1] * box.count[2]);
      const char* from = static_cast<const char*>(array->GetVoidPointer(0));
      char* to = static_cast<char*>(cropped->GetVoidPointer(0));
      for (vtkIdType z = 0; z < box.count[2]; ++z)
      {
        for (vtkIdType y = 0; y < box.count[1]; ++y)
        {
          const vtkIdType row = ((box.first[2] + z) * box.dims[1] + box.first[1] + y) * box.dims[0] + box.first[0];
          std::memcpy(to, from + static_cast<size_t>(row) * tupleBytes, static_cast<size_t>(box.count[0]) * tupleBytes);
          to += static_cast<size_t>(box.count[0]) * tupleBytes;
        }
      }
      data->AddArray(cropped); // same name: replaces the array at its index (attributes kept)
    }
  }
  image->SetExtent(crop);
  return true;
}

/// The extent of one piece of `extent` with `ghost` layers, split as the source splits it.
void PieceExtent(vtkInformation* info, const int extent[6], int ghost, int piece[6])
{
  const int mode = info->Has(vtkExtentTranslator::UPDATE_SPLIT_MODE())
    ? info->Get(vtkExtentTranslator::UPDATE_SPLIT_MODE())
    : vtkExtentTranslator::BLOCK_MODE;
  vtkNew<vtkExtentTranslator> translator;
  int whole[6];
  std::copy(extent, extent + 6, whole);
  translator->PieceToExtentThreadSafe(info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()),
    UpdatePieces(info), ghost, whole, piece, mode, 0);
}
}

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
