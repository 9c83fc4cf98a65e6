/**
 * @class   vtkPVShockCompositeDataPipeline
 * @brief   ParaView's executive for the shock filters: a failed input still joins a parallel run
 *
 * ParaView gives every filter a vtkPVCompositeDataPipeline (which passes the
 * derived-array selections, e.g. "Magnitude", to the filter before it),
 * unless the proxy's XML names another executive: the shock filters' proxies
 * name this one. It is vtkPVCompositeDataPipeline with the one addition of
 * vtkShockCompositeDataPipeline: when a filter before a shock filter fails on
 * one process of pvbatch or pvserver (e.g. vtkLoopSubdivisionFilter on a
 * process whose piece is empty), the shock filter still executes there, so
 * that every process stops with the same one-line error instead of the
 * others waiting for it for ever.
 *
 * @sa vtkShockCompositeDataPipeline vtkPVCompositeDataPipeline
 */
#ifndef vtkPVShockCompositeDataPipeline_h
#define vtkPVShockCompositeDataPipeline_h

#include "vtkPVCompositeDataPipeline.h"
#include "vtkShockFiltersServerManagerModule.h" // for export macro

class VTKSHOCKFILTERSSERVERMANAGER_EXPORT vtkPVShockCompositeDataPipeline : public vtkPVCompositeDataPipeline
{
public:
  static vtkPVShockCompositeDataPipeline* New();
  vtkTypeMacro(vtkPVShockCompositeDataPipeline, vtkPVCompositeDataPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkPVShockCompositeDataPipeline();
  ~vtkPVShockCompositeDataPipeline() override;

  /// vtkPVCompositeDataPipeline's, then vtkShockCompositeDataPipeline::ForwardedUpstream.
  int ForwardUpstream(vtkInformation* request) override;
  /// vtkPVCompositeDataPipeline's, unless vtkShockCompositeDataPipeline::SkipsDefaultInformation.
  void CopyDefaultInformation(vtkInformation* request, int direction, vtkInformationVector** inInfoVec,
    vtkInformationVector* outInfoVec) override;
  /// vtkPVCompositeDataPipeline's, unless vtkShockCompositeDataPipeline::InputMissingAfterFailure,
  /// through vtkShockCompositeDataPipeline::ValidatedInput.
  int InputTypeIsValid(int port, int index, vtkInformationVector** inInfoVec) override;
  int InputFieldsAreValid(int port, int index, vtkInformationVector** inInfoVec) override;

private:
  vtkPVShockCompositeDataPipeline(const vtkPVShockCompositeDataPipeline&) = delete;
  void operator=(const vtkPVShockCompositeDataPipeline&) = delete;
};

#endif
