#include "vtkPVShockCompositeDataPipeline.h"

#include "vtkObjectFactory.h"
#include "vtkShockCompositeDataPipeline.h"

vtkStandardNewMacro(vtkPVShockCompositeDataPipeline);

vtkPVShockCompositeDataPipeline::vtkPVShockCompositeDataPipeline() = default;

vtkPVShockCompositeDataPipeline::~vtkPVShockCompositeDataPipeline() = default;

int vtkPVShockCompositeDataPipeline::ForwardUpstream(vtkInformation* request)
{
  return vtkShockCompositeDataPipeline::ForwardedUpstream(this, request, this->Superclass::ForwardUpstream(request));
}

void vtkPVShockCompositeDataPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
