/**
 * @class   vtkSMShockInputArrayInitializationHelper
 * @brief   gives a new shock advection proxy its own input's array
 *
 * ParaView picks the default of an array property from the data information
 * of the filter's input. pvpython and pvbatch create a filter before its
 * input has run, so that information is empty and the property stays
 * `[None, '']`. paraview.simple also assigns the active source as input before
 * the `Input=` argument, and fills the array from that other source; as the
 * property then looks user-set, ParaView keeps the foreign array.
 *
 * Named in a proxy's `<Hints><InitializationHelper class="..."/>`, this helper
 * runs in vtkSMParaViewPipelineController::PostInitializeProxy. When the
 * array property is empty, or was set before the current input was chosen
 * and names an array that input does not offer, it runs the input once (as
 * the GUI's Apply does), updates the array domain and resets the property to
 * the domain default: the input's active scalars. An array chosen after the
 * input (`InputArray=` or a later assignment) is left alone.
 *
 * The XML attribute `property` names the array property (default
 * "SelectInputArray").
 */
#ifndef vtkSMShockInputArrayInitializationHelper_h
#define vtkSMShockInputArrayInitializationHelper_h

#include "vtkSMProxyInitializationHelper.h"
#include "vtkShockFiltersServerManagerModule.h" // for export macro

class VTKSHOCKFILTERSSERVERMANAGER_EXPORT vtkSMShockInputArrayInitializationHelper
  : public vtkSMProxyInitializationHelper
{
public:
  static vtkSMShockInputArrayInitializationHelper* New();
  vtkTypeMacro(vtkSMShockInputArrayInitializationHelper, vtkSMProxyInitializationHelper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void PostInitializeProxy(
    vtkSMProxy* proxy, vtkPVXMLElement* xml, vtkMTimeType initializationTimeStamp) override;

protected:
  vtkSMShockInputArrayInitializationHelper() = default;
  ~vtkSMShockInputArrayInitializationHelper() override = default;

private:
  vtkSMShockInputArrayInitializationHelper(const vtkSMShockInputArrayInitializationHelper&) = delete;
  void operator=(const vtkSMShockInputArrayInitializationHelper&) = delete;
};

#endif
