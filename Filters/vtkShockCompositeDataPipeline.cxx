#include "vtkShockCompositeDataPipeline.h"

#include "vtkInformation.h"
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
  if (!filter || !request || !filter->InputInformationFailed() ||
    request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()) ||
    request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
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

void vtkShockCompositeDataPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
