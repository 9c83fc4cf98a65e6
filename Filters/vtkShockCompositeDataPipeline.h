/**
 * @class   vtkShockCompositeDataPipeline
 * @brief   the shock filters' executive: a failed input still joins a parallel run
 *
 * In a parallel run (pvbatch or pvserver under mpirun, or a VTK pipeline whose
 * filter is given a vtkMultiProcessController), every process executes the
 * shock filter on its piece, and the pieces agree with each other in
 * collective steps. When a filter upstream fails on one process only (e.g.
 * vtkLoopSubdivisionFilter on a process whose piece is empty), VTK's
 * executives do not execute the filters after it on that process: the other
 * processes would then wait for it in their first collective step for ever.
 *
 * This executive forwards a data request upstream as vtkCompositeDataPipeline
 * does. When the input fails to update and the filter runs in parallel
 * (vtkShockAdvectionFilter::ExecutesAfterInputFailure), it still executes the
 * filter: the filter takes part in the agreement of its first collective step
 * and every process stops with the same one-line error, naming the process
 * whose input failed. In serial, or for a request that is not for data,
 * nothing differs from vtkCompositeDataPipeline.
 *
 * The shock filters create it as their default executive. ParaView replaces a
 * filter's executive by vtkPVCompositeDataPipeline unless the proxy names
 * another: the plugin's proxies name vtkPVShockCompositeDataPipeline, which
 * does the same through ForwardedUpstream.
 *
 * @sa vtkShockAdvectionFilter vtkCompositeDataPipeline
 */
#ifndef vtkShockCompositeDataPipeline_h
#define vtkShockCompositeDataPipeline_h

#include "vtkCompositeDataPipeline.h"
#include "vtkFiltersShockModule.h" // for export macro

class VTKFILTERSSHOCK_EXPORT vtkShockCompositeDataPipeline : public vtkCompositeDataPipeline
{
public:
  static vtkShockCompositeDataPipeline* New();
  vtkTypeMacro(vtkShockCompositeDataPipeline, vtkCompositeDataPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * What an executive of a shock filter returns from ForwardUpstream:
   * `forwarded`, the result of forwarding `request` upstream, except for a
   * data request that failed upstream while the filter runs in parallel:
   * then 1, so that the filter executes and tells the other processes.
   * For executives of other bases (ParaView's).
   */
  static int ForwardedUpstream(vtkExecutive* executive, vtkInformation* request, int forwarded);

protected:
  vtkShockCompositeDataPipeline();
  ~vtkShockCompositeDataPipeline() override;

  int ForwardUpstream(vtkInformation* request) override;

private:
  vtkShockCompositeDataPipeline(const vtkShockCompositeDataPipeline&) = delete;
  void operator=(const vtkShockCompositeDataPipeline&) = delete;
};

#endif
