#include "vtkShockCompositeDataPipeline.h"

#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkShockAdvectionFilter.h"

vtkStandardNewMacro(vtkShockCompositeDataPipeline);

vtkShockCompositeDataPipeline::vtkShockCompositeDataPipeline() = default;

vtkShockCompositeDataPipeline::~vtkShockCompositeDataPipeline() = default;

namespace
{
vtkShockAdvectionFilter* FilterOf(vtkExecutive* executive)
{
  return vtkShockAdvectionFilter::SafeDownCast(executive ? executive->GetAlgorithm() : nullptr);
}
}

bool vtkShockCompositeDataPipeline::SkipsUpstream(vtkExecutive* executive, vtkInformation* request, int& result)
{
  vtkShockAdvectionFilter* filter = FilterOf(executive);
  if (!filter || !request || request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    return false; // a new data-object pass asks the input anew
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    if (!filter->InputDataObjectFailed())
    {
      return false;
    }
    // The input has no data object of this pass: its information is not
    // asked either; ForwardedUpstream goes on as after a failed information pass.
    result = 0;
    return true;
  }
  if (!filter->InputInformationFailed())
  {
    return false;
  }
  // After a failed information pass the input is asked nothing more: its
  // data request fails (and ForwardedUpstream decides whether the filter
  // executes), every other request has nothing to do.
  result = request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()) ? 0 : 1;
  return true;
}

int vtkShockCompositeDataPipeline::ForwardedUpstream(vtkExecutive* executive, vtkInformation* request, int forwarded)
{
  vtkShockAdvectionFilter* filter = FilterOf(executive);
  if (!filter || !request)
  {
    return forwarded;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    return filter->ContinuesAfterDataObjectFailure(forwarded != 0) ? 1 : forwarded;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return filter->ContinuesAfterInformationFailure(forwarded != 0) ? 1 : forwarded;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return filter->ExecutesAfterInputFailure(forwarded != 0) ? 1 : forwarded;
  }
  return forwarded;
}

int vtkShockCompositeDataPipeline::ForwardUpstream(vtkInformation* request)
{
  int result = 0;
  if (!SkipsUpstream(this, request, result))
  {
    result = this->Superclass::ForwardUpstream(request);
  }
  return ForwardedUpstream(this, request, result);
}

bool vtkShockCompositeDataPipeline::InputMissingAfterFailure(
  vtkExecutive* executive, int port, int index, vtkInformationVector** inInfoVec)
{
  vtkShockAdvectionFilter* filter = FilterOf(executive);
  if (!filter || !filter->InputDataObjectFailed() || !inInfoVec || !inInfoVec[port])
  {
    return false;
  }
  vtkInformation* info = inInfoVec[port]->GetInformationObject(index);
  return info && !info->Get(vtkDataObject::DATA_OBJECT());
}

bool vtkShockCompositeDataPipeline::SkipsDefaultInformation(
  vtkExecutive* executive, vtkInformation* request, int direction)
{
  vtkShockAdvectionFilter* filter = FilterOf(executive);
  return filter && request && filter->InputDataObjectFailed() && direction == vtkExecutive::RequestUpstream &&
    request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT());
}

void vtkShockCompositeDataPipeline::CopyDefaultInformation(
  vtkInformation* request, int direction, vtkInformationVector** inInfoVec, vtkInformationVector* outInfoVec)
{
  if (!SkipsDefaultInformation(this, request, direction))
  {
    this->Superclass::CopyDefaultInformation(request, direction, inInfoVec, outInfoVec);
  }
}

int vtkShockCompositeDataPipeline::ValidatedInput(vtkExecutive* executive, int valid)
{
  vtkShockAdvectionFilter* filter = FilterOf(executive);
  return !valid && filter && filter->ContinuesAfterInvalidInput() ? 1 : valid;
}

int vtkShockCompositeDataPipeline::InputTypeIsValid(int port, int index, vtkInformationVector** inInfoVec)
{
  return InputMissingAfterFailure(this, port, index, inInfoVec)
    ? 1
    : ValidatedInput(this, this->Superclass::InputTypeIsValid(port, index, inInfoVec));
}

int vtkShockCompositeDataPipeline::InputFieldsAreValid(int port, int index, vtkInformationVector** inInfoVec)
{
  return InputMissingAfterFailure(this, port, index, inInfoVec)
    ? 1
    : ValidatedInput(this, this->Superclass::InputFieldsAreValid(port, index, inInfoVec));
}

void vtkShockCompositeDataPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
