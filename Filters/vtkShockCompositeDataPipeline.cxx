#include "vtkShockCompositeDataPipeline.h"

#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkShockAdvectionFilter.h"

vtkStandardNewMacro(vtkShockCompositeDataPipeline);

vtkShockCompositeDataPipeline::vtkShockCompositeDataPipeline() = default;

vtkShockCompositeDataPipeline::~vtkShockCompositeDataPipeline() = default;

int vtkShockCompositeDataPipeline::ForwardedUpstream(vtkExecutive* executive, vtkInformation* request, int forwarded)
{
  auto* filter = vtkShockAdvectionFilter::SafeDownCast(executive ? executive->GetAlgorithm() : nullptr);
  if (!filter || !request || !request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return forwarded;
  }
  return filter->ExecutesAfterInputFailure(forwarded != 0) ? 1 : forwarded;
}

int vtkShockCompositeDataPipeline::ForwardUpstream(vtkInformation* request)
{
  return ForwardedUpstream(this, request, this->Superclass::ForwardUpstream(request));
}

void vtkShockCompositeDataPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
