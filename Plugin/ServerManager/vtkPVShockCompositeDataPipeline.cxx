#include "vtkPVShockCompositeDataPipeline.h"

#include "vtkObjectFactory.h"
#include "vtkShockCompositeDataPipeline.h"

vtkStandardNewMacro(vtkPVShockCompositeDataPipeline);

vtkPVShockCompositeDataPipeline::vtkPVShockCompositeDataPipeline() = default;

vtkPVShockCompositeDataPipeline::~vtkPVShockCompositeDataPipeline() = default;

int vtkPVShockCompositeDataPipeline::ForwardUpstream(vtkInformation* request)
{
  int result = 0;
  if (!vtkShockCompositeDataPipeline::SkipsUpstream(this, request, result))
  {
    result = this->Superclass::ForwardUpstream(request);
  }
  return vtkShockCompositeDataPipeline::ForwardedUpstream(this, request, result);
}

void vtkPVShockCompositeDataPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
