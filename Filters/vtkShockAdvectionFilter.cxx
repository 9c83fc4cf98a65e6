#include "vtkShockAdvectionFilter.h"

#include "vtkDataObjectTypes.h"

#include <sstream>

#include "vtkAlgorithm.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDataSet.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkCellData.h"
#include "vtkMultiProcessController.h"
#include "ShockParallel.h"
#include "vtkSmartPointer.h"
#include "vtkShockCompositeDataPipeline.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

vtkShockAdvectionFilter::vtkShockAdvectionFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
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

bool vtkShockAdvectionFilter::BeginExecution(std::string* reason)
{
  this->SetProgressText(nullptr);
  this->ResetMeasurements();
  if (this->InputFailed)
  {
    if (reason)
    {
      *reason = "its input failed to update (see the error of the filter before this one on that process)";
    }
    return false;
  }
  if (!this->ValidateParameters())
  {
    if (reason)
    {
      *reason = "the filter's parameters are invalid (see the message above)";
    }
    return false;
  }
  return true;
}

vtkExecutive* vtkShockAdvectionFilter::CreateDefaultExecutive()
{
  return vtkShockCompositeDataPipeline::New();
}

bool vtkShockAdvectionFilter::ExecutesAfterInputFailure(bool updated)
{
  bool unknown = false;
  vtkExecutive* executive = this->GetExecutive();
  this->InputFailed = !updated && executive &&
    this->PieceController(executive->GetOutputInformation(), unknown) != nullptr;
  return this->InputFailed;
}

bool vtkShockAdvectionFilter::ContinuesAfterInformationFailure(bool updated)
{
  // The output's piece request is not known in this pass (VTK sets it after
  // the information): any run that may be parallel goes on to its data pass.
  this->InformationFailed = !updated && this->MayRunInParallel();
  return this->InformationFailed;
}

bool vtkShockAdvectionFilter::ContinuesAfterDataObjectFailure(bool updated)
{
  // As in the information pass: the pieces are not known yet.
  this->DataObjectFailed = !updated && this->MayRunInParallel();
  return this->DataObjectFailed;
}

bool vtkShockAdvectionFilter::MayRunInParallel() const
{
  return this->Controller && this->Controller->GetNumberOfProcesses() > 1;
}

bool vtkShockAdvectionFilter::ContinuesAfterInvalidInput() const
{
  return this->MayRunInParallel();
}

namespace
{
/// Whether `input` is of a type the port takes (INPUT_REQUIRED_DATA_TYPE); a composite data set counts as taken.
bool TakesType(vtkAlgorithm* algorithm, vtkDataObject* input)
{
  vtkInformation* port = algorithm->GetInputPortInformation(0);
  if (!input || vtkCompositeDataSet::SafeDownCast(input) || !port ||
    !port->Has(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE()))
  {
    return true;
  }
  for (int k = 0; k < port->Length(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE()); ++k)
  {
    if (input->IsA(port->Get(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), k)))
    {
      return true;
    }
  }
  return false;
}
}

vtkTypeBool vtkShockAdvectionFilter::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector && this->GetNumberOfInputPorts() > 0 && inputVector[0]
    ? inputVector[0]->GetInformationObject(0)
    : nullptr;
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(inInfo ? inInfo->Get(vtkDataObject::DATA_OBJECT()) : nullptr))
  {
    this->CompositeInput = composite;
  }
  vtkDataObject* given = inInfo ? inInfo->Get(vtkDataObject::DATA_OBJECT()) : nullptr;
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()) &&
    ((this->DataObjectFailed && !given) || (given && this->ContinuesAfterInvalidInput() && !TakesType(this, given))))
  {
    // The input has no data object on this process, or one of a type the
    // filter does not take: the output of a data-set input, so that the
    // pipeline reaches the data pass, where the filter tells the other
    // processes (ExecutesAfterInputFailure; the input's type).
    vtkInformation* outInfo = outputVector->GetInformationObject(0);
    vtkDataObject* output = outInfo->Get(vtkDataObject::DATA_OBJECT());
    if (!output || !output->IsA(this->PieceOutputType()))
    {
      outInfo->Set(vtkDataObject::DATA_OBJECT(),
        vtkSmartPointer<vtkDataObject>::Take(vtkDataObjectTypes::NewDataObject(this->PieceOutputType())));
    }
    return 1;
  }
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    this->SetProgressText(nullptr); // the phases were this execution's
    this->InputFailed = false;      // this execution's (the executive says it anew for the next)
  }
  if (!result && request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    // A failed execution leaves nothing that looks like a result (the output
    // object is reused: a failed block of a composite would otherwise carry
    // the arrays of the block before it).
    if (vtkDataObject* output = vtkDataObject::GetData(outputVector, 0))
    {
      output->Initialize();
    }
  }
  return result;
}

bool vtkShockAdvectionFilter::IsBlockOfCompositeInput(vtkDataObject* data)
{
  if (!data || !this->CompositeInput)
  {
    return false;
  }
  auto iterator = vtk::TakeSmartPointer(this->CompositeInput->NewIterator());
  for (iterator->InitTraversal(); !iterator->IsDoneWithTraversal(); iterator->GoToNextItem())
  {
    if (iterator->GetCurrentDataObject() == data)
    {
      return true;
    }
  }
  return false;
}

bool vtkShockAdvectionFilter::PassForeignBlock(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  if (!input || !output || this->FiltersType(input) || !output->IsA(input->GetClassName()) ||
    !this->IsBlockOfCompositeInput(input))
  {
    return false;
  }
  output->ShallowCopy(input);
  vtkLogF(1, "%s: a %s block of the composite input is not filtered by this filter: passed through.",
    this->GetClassName(), input->GetClassName());
  return true;
}

bool vtkShockAdvectionFilter::ReportProgress(double fraction, const char* phase)
{
  // The phase, for ParaView's progress bar ("<filter>: <phase>"); set only when it changes.
  if (phase && (!this->GetProgressText() || std::strcmp(this->GetProgressText(), phase) != 0))
  {
    this->SetProgressText(phase);
  }
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
  vtkLogF(1, "%s: no input array selected: filtering the active %s scalars '%s'.",
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
  if (!selected && named && this->IsBlockOfCompositeInput(vtkDataSet::GetData(inputVector[0], 0)))
  {
    // ParaView names one array for all blocks: a block without it filters its own active scalars.
    selected = this->GetActiveScalarsToFilter(inputVector, association);
    if (selected)
    {
      // Said as a warning: another array than the one named is filtered.
      vtkWarningMacro("A block of the composite input has no array '"
        << selection->Get(vtkDataObject::FIELD_NAME()) << "': its active scalars '"
        << (selected->GetName() ? selected->GetName() : "(unnamed)") << "' are filtered instead.");
    }
  }
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

vtkDataArray* vtkShockAdvectionFilter::FindArrayToFilter(
  vtkInformationVector** inputVector, int& association)
{
  vtkInformation* selection = this->GetInputArrayInformation(0);
  if (selection->Has(vtkDataObject::FIELD_NAME()) && *selection->Get(vtkDataObject::FIELD_NAME()))
  {
    vtkAbstractArray* named = this->GetInputAbstractArrayToProcess(0, inputVector, association);
    if (named || !this->IsBlockOfCompositeInput(vtkDataSet::GetData(inputVector[0], 0)))
    {
      return vtkDataArray::SafeDownCast(named);
    }
  }
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  if (!input)
  {
    return nullptr;
  }
  association = input->GetPointData()->GetScalars() ? vtkDataObject::FIELD_ASSOCIATION_POINTS
                                                    : vtkDataObject::FIELD_ASSOCIATION_CELLS;
  return input->GetPointData()->GetScalars() ? input->GetPointData()->GetScalars()
                                             : input->GetCellData()->GetScalars();
}

vtkShockAdvectionFilter::~vtkShockAdvectionFilter()
{
  this->SetController(nullptr);
}

void vtkShockAdvectionFilter::SetController(vtkMultiProcessController* controller)
{
  vtkSetObjectBodyMacro(Controller, vtkMultiProcessController, controller);
}

vtkMultiProcessController* vtkShockAdvectionFilter::PieceController(
  vtkInformationVector* outputVector, bool& unknown)
{
  return ShockParallel::PieceController(
    this, this->Controller, outputVector->GetInformationObject(0), unknown);
}

double vtkShockAdvectionFilter::GlobalValueScale(
  vtkMultiProcessController* controller, vtkInformationVector** inputVector)
{
  if (!controller)
  {
    return 0.0;
  }
  vtkDataSet* input = inputVector[0]->GetNumberOfInformationObjects() > 0
    ? vtkDataSet::GetData(inputVector[0], 0)
    : nullptr;
  double range[2] = { 0.0, 0.0 };
  const bool has =
    !this->InputFailed && input && input->GetNumberOfPoints() > 0 && this->LocalValueRange(inputVector, range);
  return ShockParallel::GlobalRangeWidth(controller, has, range);
}

namespace
{
/// Component value of tuple t: read in place from a contiguous array, or through vtkDataArray.
template <typename T>
double ComponentOf(const T* values, vtkIdType t, int c, int components)
{
  return static_cast<double>(values[t * components + c]);
}
double ComponentOf(vtkDataArray* array, vtkIdType t, int c, int)
{
  return array->GetComponent(t, c);
}

/**
 * The smallest and largest component of the tuples whose components are all
 * finite, leaving out the tuples `marks` flags with `hidden`.
 */
template <typename Values>
void TupleRange(Values values, vtkIdType tuples, int components, const unsigned char* marks, unsigned char hidden,
  double range[2])
{
  for (vtkIdType t = 0; t < tuples; ++t)
  {
    if (marks && (marks[t] & hidden))
    {
      continue;
    }
    bool finite = true;
    for (int c = 0; c < components && finite; ++c)
    {
      finite = std::isfinite(ComponentOf(values, t, c, components));
    }
    for (int c = 0; c < components && finite; ++c)
    {
      const double v = ComponentOf(values, t, c, components);
      range[0] = std::min(range[0], v);
      range[1] = std::max(range[1], v);
    }
  }
}
}

bool vtkShockAdvectionFilter::LocalValueRange(vtkInformationVector** inputVector, double range[2])
{
  range[0] = std::numeric_limits<double>::infinity();
  range[1] = -range[0];
  int association = -1;
  vtkDataArray* array = this->FindArrayToFilter(inputVector, association);
  if (!array)
  {
    return false;
  }
  // Blanked samples (HIDDENPOINT / HIDDENCELL) take no part, as in the kernels.
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  const bool cells = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  vtkUnsignedCharArray* ghosts = input ? (cells ? input->GetCellGhostArray() : input->GetPointGhostArray()) : nullptr;
  ghosts = ghosts && ghosts->GetNumberOfTuples() == array->GetNumberOfTuples() ? ghosts : nullptr;
  const unsigned char hidden = cells ? static_cast<unsigned char>(vtkDataSetAttributes::HIDDENCELL)
                                     : static_cast<unsigned char>(vtkDataSetAttributes::HIDDENPOINT);
  const unsigned char* marks = ghosts ? ghosts->GetPointer(0) : nullptr;
  if (array->HasStandardMemoryLayout())
  {
    switch (array->GetDataType())
    {
      vtkTemplateMacro(TupleRange(static_cast<const VTK_TT*>(array->GetVoidPointer(0)), array->GetNumberOfTuples(),
        array->GetNumberOfComponents(), marks, hidden, range));
      default:
        TupleRange(array, array->GetNumberOfTuples(), array->GetNumberOfComponents(), marks, hidden, range);
    }
  }
  else
  {
    TupleRange(array, array->GetNumberOfTuples(), array->GetNumberOfComponents(), marks, hidden, range);
  }
  return range[0] <= range[1];
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

std::string vtkShockAdvectionFilter::ParametersText()
{
  std::ostringstream text;
  text.precision(17);
  text << "class=" << this->GetClassName() << ";FlowTime=" << this->FlowTime
       << ";SmoothingPasses=" << this->SmoothingPasses << ";StepFraction=" << this->StepFraction
       << ";FlowMode=" << this->FlowMode << ";NumberOfFlowUpdates=" << this->NumberOfFlowUpdates
       << ";Sampling=" << this->Sampling << ";TracingMode=" << this->TracingMode
       << ";GenerateFlowArrays=" << this->GenerateFlowArrays << ";GhostLevels=" << this->GhostLevels << ";";
  return text.str();
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
  os << indent << "Controller: " << static_cast<void*>(this->Controller) << "\n";
  os << indent << "ParallelValueScale: " << this->ParallelValueScale << "\n";
  os << indent << "ParallelLengthScale: " << this->ParallelLengthScale << "\n";
  os << indent << "LastSetupSeconds: " << this->LastSetupSeconds << "\n";
  os << indent << "LastFlowSeconds: " << this->LastFlowSeconds << "\n";
  os << indent << "LastAdvectionSeconds: " << this->LastAdvectionSeconds << "\n";
  os << indent << "LastTraceSteps: " << this->LastTraceSteps << "\n";
}
