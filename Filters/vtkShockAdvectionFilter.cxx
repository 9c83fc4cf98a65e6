#include "vtkShockAdvectionFilter.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkInformation.h"

#include <cmath>

vtkShockAdvectionFilter::vtkShockAdvectionFilter()
{
  // Default array: the active point scalars.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
}

bool vtkShockAdvectionFilter::ValidateParameters()
{
  if (!(this->TimeStep >= 0.0) || !std::isfinite(this->TimeStep))
  {
    vtkErrorMacro("TimeStep must be a finite number >= 0, got " << this->TimeStep << ".");
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

vtkDataArray* vtkShockAdvectionFilter::GetArrayToFilter(
  vtkInformationVector** inputVector, int& association)
{
  association = -1;
  vtkAbstractArray* selected = this->GetInputAbstractArrayToProcess(0, inputVector, association);
  if (!selected)
  {
    vtkInformation* selection = this->GetInputArrayInformation(0);
    if (selection->Has(vtkDataObject::FIELD_NAME()))
    {
      vtkErrorMacro("No array to process: the input has no point or cell array named '"
        << selection->Get(vtkDataObject::FIELD_NAME()) << "'.");
    }
    else
    {
      vtkErrorMacro("No array to process: the input has no active point scalars; select an "
                    "array with SetInputArrayToProcess.");
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
  os << indent << "TimeStep: " << this->TimeStep << "\n";
  os << indent << "SmoothingPasses: " << this->SmoothingPasses << "\n";
  os << indent << "StepFraction: " << this->StepFraction << "\n";
  os << indent << "FlowMode: " << flowNames[this->FlowMode] << "\n";
  os << indent << "NumberOfFlowUpdates: " << this->NumberOfFlowUpdates << "\n";
  os << indent << "Sampling: " << (this->Sampling == LINEAR ? "Linear" : "Nearest") << "\n";
  os << indent << "TracingMode: " << (this->TracingMode == FACE_CROSSING ? "FaceCrossing" : "Stepped")
     << "\n";
  os << indent << "GenerateFlowArrays: " << (this->GenerateFlowArrays ? "On" : "Off") << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "LastSetupSeconds: " << this->LastSetupSeconds << "\n";
  os << indent << "LastFlowSeconds: " << this->LastFlowSeconds << "\n";
  os << indent << "LastAdvectionSeconds: " << this->LastAdvectionSeconds << "\n";
  os << indent << "LastTraceSteps: " << this->LastTraceSteps << "\n";
}
