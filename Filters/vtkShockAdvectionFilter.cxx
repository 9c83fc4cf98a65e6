#include "vtkShockAdvectionFilter.h"

#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"

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

bool vtkShockAdvectionFilter::ReportProgress(double fraction)
{
  this->UpdateProgress(fraction);
  return !this->GetAbortExecute();
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
  os << indent << "LastFlowSeconds: " << this->LastFlowSeconds << "\n";
  os << indent << "LastAdvectionSeconds: " << this->LastAdvectionSeconds << "\n";
  os << indent << "LastTraceSteps: " << this->LastTraceSteps << "\n";
}
