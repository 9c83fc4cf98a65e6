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

void vtkPVShockCompositeDataPipeline::CopyDefaultInformation(
  vtkInformation* request, int direction, vtkInformationVector** inInfoVec, vtkInformationVector* outInfoVec)
{
  if (!vtkShockCompositeDataPipeline::SkipsDefaultInformation(this, request, direction))
  {
    this->Superclass::CopyDefaultInformation(request, direction, inInfoVec, outInfoVec);
  }
}

int vtkPVShockCompositeDataPipeline::InputTypeIsValid(int port, int index, vtkInformationVector** inInfoVec)
{
  return vtkShockCompositeDataPipeline::InputMissingAfterFailure(this, port, index, inInfoVec)
    ? 1
    : vtkShockCompositeDataPipeline::ValidatedInput(this, this->Superclass::InputTypeIsValid(port, index, inInfoVec));
}

int vtkPVShockCompositeDataPipeline::InputFieldsAreValid(int port, int index, vtkInformationVector** inInfoVec)
{
  return vtkShockCompositeDataPipeline::InputMissingAfterFailure(this, port, index, inInfoVec)
    ? 1
    : vtkShockCompositeDataPipeline::ValidatedInput(
        this, this->Superclass::InputFieldsAreValid(port, index, inInfoVec));
}

void vtkPVShockCompositeDataPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
