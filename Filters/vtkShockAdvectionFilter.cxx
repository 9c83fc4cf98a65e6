#include "vtkShockAdvectionFilter.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkInformationKey.h"
#include "vtkInformationKeyLookup.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkPointData.h"
#include "vtkCellData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#if VTK_MODULE_ENABLE_VTK_ParallelCore
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

vtkShockAdvectionFilter::vtkShockAdvectionFilter()
{
  // Default array: the active point scalars.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
}

bool vtkShockAdvectionFilter::ValidateParameters()
{
  if (!(this->FlowTime >= 0.0) || !std::isfinite(this->FlowTime))
  {
    vtkErrorMacro("FlowTime must be a finite number >= 0, got " << this->FlowTime << ".");
    return false;
  }
  return true;
}

void vtkShockAdvectionFilter::ResetMeasurements()
{
  this->LastSetupSeconds = this->LastFlowSeconds = this->LastAdvectionSeconds = 0.0;
  this->LastTraceSteps = 0;
}

bool vtkShockAdvectionFilter::BeginExecution()
{
  this->ResetMeasurements();
  return this->ValidateParameters();
}

bool vtkShockAdvectionFilter::ReportProgress(double fraction)
{
  this->UpdateProgress(fraction);
  return !this->GetAbortExecute();
}

vtkAbstractArray* vtkShockAdvectionFilter::GetActiveScalarsToFilter(
  vtkInformationVector** inputVector, int& association)
{
  // ParaView hands an empty name when the input had no arrays yet when the
  // filter was created (pvpython builds filters before their input ran);
  // VTK users who never select an array get the SCALARS attribute. Both mean
  // "the active scalars": those of the points, else those of the cells.
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkDataArray* scalars = nullptr;
  const char* where = "point";
  if (input)
  {
    association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
    scalars = input->GetPointData()->GetScalars();
    if (!scalars)
    {
      association = vtkDataObject::FIELD_ASSOCIATION_CELLS;
      scalars = input->GetCellData()->GetScalars();
      where = "cell";
    }
  }
  if (!scalars)
  {
    vtkErrorMacro("No array to process: none was selected and the input has no active point or "
                  "cell scalars; select an array with SetInputArrayToProcess (InputArray in "
                  "ParaView).");
    return nullptr;
  }
  vtkLogF(INFO, "%s: no input array selected: filtering the active %s scalars '%s'.",
    this->GetClassName(), where, scalars->GetName() ? scalars->GetName() : "(unnamed)");
  return scalars;
}

vtkDataArray* vtkShockAdvectionFilter::GetArrayToFilter(
  vtkInformationVector** inputVector, int& association)
{
  association = -1;
  vtkInformation* selection = this->GetInputArrayInformation(0);
  const bool named =
    selection->Has(vtkDataObject::FIELD_NAME()) && *selection->Get(vtkDataObject::FIELD_NAME());
  vtkAbstractArray* selected = named
    ? this->GetInputAbstractArrayToProcess(0, inputVector, association)
    : this->GetActiveScalarsToFilter(inputVector, association);
  if (!selected)
  {
    if (named)
    {
      vtkErrorMacro("No array to process: the input has no point or cell array named '"
        << selection->Get(vtkDataObject::FIELD_NAME()) << "'.");
    }
    return nullptr;
  }
  const char* name = selected->GetName() ? selected->GetName() : "(unnamed)";
  vtkDataArray* array = vtkDataArray::SafeDownCast(selected);
  if (!array)
  {
    vtkErrorMacro("Array '" << name << "' is a " << selected->GetClassName()
                            << ", not a numeric array: it cannot be filtered.");
    return nullptr;
  }
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    vtkErrorMacro("Array '" << name << "' must be point or cell data.");
    return nullptr;
  }
  return array;
}

vtkTypeBool vtkShockAdvectionFilter::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    // vtkCompositeDataPipeline runs a simple algorithm block by block and marks
    // each block's REQUEST_DATA_OBJECT with its (protected) SUPPRESS_RESET_PI key.
    static vtkInformationKey* const blockKey =
      vtkInformationKeyLookup::Find("SUPPRESS_RESET_PI", "vtkCompositeDataPipeline");
    this->ExecutingBlock = blockKey && outInfo && outInfo->Has(blockKey);
  }
  const bool data = request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()) != 0;
  if (data)
  {
    this->PrepareParallelExecution(inputVector, outputVector);
  }
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  if (data)
  {
    this->ExecutingBlock = false;
  }
  return result;
}

bool vtkShockAdvectionFilter::LocalValueRange(vtkInformationVector** inputVector, double range[2])
{
  range[0] = std::numeric_limits<double>::infinity();
  range[1] = -range[0];
  int association = -1;
  vtkDataArray* array =
    vtkDataArray::SafeDownCast(this->GetInputAbstractArrayToProcess(0, inputVector, association));
  if (!array)
  {
    return false;
  }
  const int components = array->GetNumberOfComponents();
  std::vector<double> tuple(static_cast<size_t>(components));
  for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
  {
    array->GetTuple(t, tuple.data());
    bool finite = true;
    for (int c = 0; c < components && finite; ++c)
    {
      finite = std::isfinite(tuple[static_cast<size_t>(c)]);
    }
    for (int c = 0; c < components && finite; ++c)
    {
      range[0] = std::min(range[0], tuple[static_cast<size_t>(c)]);
      range[1] = std::max(range[1], tuple[static_cast<size_t>(c)]);
    }
  }
  return range[0] <= range[1];
}

bool vtkShockAdvectionFilter::LocalEdgeLengthSum(vtkInformationVector**, double&, double&)
{
  return false;
}

void vtkShockAdvectionFilter::PrepareParallelExecution(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->ParallelValueScale = 0.0;
  this->ParallelLengthScale = 0.0;
  this->ParallelPiecesWithData = NOT_A_PIECE;
  if (this->ExecutingBlock)
  {
    // A block of a composite input: the number of blocks differs between
    // processes, so no collective here; each block keeps its own range.
    return;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int pieces = outInfo && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  if (pieces <= 1)
  {
    return;
  }
  this->ParallelPiecesWithData = UNKNOWN_PIECES;
#if VTK_MODULE_ENABLE_VTK_ParallelCore
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() != pieces)
  {
    return;
  }
  // Collective from here on: no early return.
  vtkDataSet* input = inputVector[0]->GetNumberOfInformationObjects() > 0
    ? vtkDataSet::GetData(inputVector[0], 0)
    : nullptr;
  double range[2];
  const bool hasRange = this->UsesParallelValueScale() && input &&
    input->GetNumberOfPoints() > 0 && this->LocalValueRange(inputVector, range);
  double local[2] = { hasRange ? -range[0] : -std::numeric_limits<double>::max(),
    hasRange ? range[1] : -std::numeric_limits<double>::max() };
  double global[2] = { 0.0, 0.0 };
  controller->AllReduce(local, global, 2, vtkCommunicator::MAX_OP);
  const int withData = input && input->GetNumberOfPoints() > 0 ? 1 : 0;
  int count = 0;
  controller->AllReduce(&withData, &count, 1, vtkCommunicator::SUM_OP);
  this->ParallelPiecesWithData = count;
  const double scale = global[1] + global[0]; // high - low
  if (this->UsesParallelValueScale() && std::isfinite(scale) && scale > 0.0)
  {
    this->ParallelValueScale = scale;
  }
  double lengths[2] = { 0.0, 0.0 }; // sum, count
  const bool hasLengths = input && input->GetNumberOfPoints() > 0 &&
    this->LocalEdgeLengthSum(inputVector, lengths[0], lengths[1]);
  double globalLengths[2] = { 0.0, 0.0 };
  controller->AllReduce(lengths, globalLengths, 2, vtkCommunicator::SUM_OP);
  if (hasLengths && globalLengths[1] > 0.0 && globalLengths[0] > 0.0)
  {
    this->ParallelLengthScale = globalLengths[0] / globalLengths[1];
  }
#else
  (void)inputVector;
#endif
}

void vtkShockAdvectionFilter::RecordRun(double flowSeconds, double advectionSeconds,
  vtkTypeUInt64 traceSteps, vtkTypeUInt64 truncatedTraces)
{
  this->LastFlowSeconds = flowSeconds;
  this->LastAdvectionSeconds = advectionSeconds;
  this->LastTraceSteps = traceSteps;
  if (truncatedTraces > 0)
  {
    vtkWarningMacro(<< truncatedTraces
                    << " flow lines were cut at the step limit (a cycle of the discrete flow).");
  }
}

void vtkShockAdvectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* flowNames[] = { "Fixed", "Composed", "Naive" };
  os << indent << "FlowTime: " << this->FlowTime << "\n";
  os << indent << "SmoothingPasses: " << this->SmoothingPasses << "\n";
  os << indent << "StepFraction: " << this->StepFraction << "\n";
  os << indent << "FlowMode: " << flowNames[this->FlowMode] << "\n";
  os << indent << "NumberOfFlowUpdates: " << this->NumberOfFlowUpdates << "\n";
  os << indent << "Sampling: " << (this->Sampling == LINEAR ? "Linear" : "Nearest") << "\n";
  os << indent << "TracingMode: " << (this->TracingMode == FACE_CROSSING ? "FaceCrossing" : "Stepped")
     << "\n";
  os << indent << "GenerateFlowArrays: " << (this->GenerateFlowArrays ? "On" : "Off") << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "GhostLevels: " << this->GhostLevels << "\n";
  os << indent << "ParallelValueScale: " << this->ParallelValueScale << "\n";
  os << indent << "ParallelLengthScale: " << this->ParallelLengthScale << "\n";
  os << indent << "LastSetupSeconds: " << this->LastSetupSeconds << "\n";
  os << indent << "LastFlowSeconds: " << this->LastFlowSeconds << "\n";
  os << indent << "LastAdvectionSeconds: " << this->LastAdvectionSeconds << "\n";
  os << indent << "LastTraceSteps: " << this->LastTraceSteps << "\n";
}
