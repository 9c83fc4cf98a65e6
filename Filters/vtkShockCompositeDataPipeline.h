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
 * whose input failed.
 *
 * The same holds for a filter upstream that fails in the information pass on
 * one process (e.g. a reader whose file is missing on one node): in a run
 * that may be parallel (the filter's controller has more than one process;
 * the pieces are not known yet in that pass) the pipeline goes on to the data
 * pass without asking that input anything more until its information is asked
 * again (SkipsUpstream), and the filter stops every process as above, or,
 * when the data request is not for pieces, is not executed. A filter upstream
 * that fails in the data-object pass on one process (a reader that cannot
 * tell its output's type there) is treated alike: its information is not
 * asked either, the missing input is taken as valid
 * (InputMissingAfterFailure), no update extent is copied to it
 * (SkipsDefaultInformation), and the filter makes its own output. In serial
 * (no such controller), nothing differs from vtkCompositeDataPipeline.
 *
 * The shock filters create it as their default executive. ParaView replaces a
 * filter's executive by vtkPVCompositeDataPipeline unless the proxy names
 * another: the plugin's proxies name vtkPVShockCompositeDataPipeline, which
 * does the same through SkipsUpstream and ForwardedUpstream.
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
   * request that failed upstream while the filter may run in parallel: then
   * 1, so that the pipeline goes on and the filter tells the other processes
   * (an information request: vtkShockAdvectionFilter::ContinuesAfterInformationFailure;
   * a data request: vtkShockAdvectionFilter::ExecutesAfterInputFailure).
   * For executives of other bases (ParaView's).
   */
  static int ForwardedUpstream(vtkExecutive* executive, vtkInformation* request, int forwarded);

  /**
   * Whether an executive of a shock filter must not forward `request`
   * upstream: after the input's information failed in a parallel run, the
   * input is asked for no update extent and no data until its information is
   * asked again; after its data object failed, not for its information
   * either. Then `result` receives what forwarding gives instead (0 for a
   * data or information request, to be passed to ForwardedUpstream; else 1).
   */
  static bool SkipsUpstream(vtkExecutive* executive, vtkInformation* request, int& result);

  /**
   * Whether the input `index` of `port` of an executive of a shock filter
   * has no data object because its data-object pass failed in a parallel run
   * (vtkShockAdvectionFilter::ContinuesAfterDataObjectFailure): the
   * executive then takes that missing input as valid, so that the filter
   * reaches its data pass and stops every process.
   */
  static bool InputMissingAfterFailure(vtkExecutive* executive, int port, int index, vtkInformationVector** inInfoVec);

  /**
   * What an executive of a shock filter returns from InputTypeIsValid and
   * InputFieldsAreValid: `valid`, except for an invalid input while the
   * filter may run in parallel (vtkShockAdvectionFilter::ContinuesAfterInvalidInput):
   * then 1, so that the filter tells the other processes instead of stopping alone.
   */
  static int ValidatedInput(vtkExecutive* executive, int valid);

  /**
   * Whether an executive of a shock filter must not copy `request`'s default
   * information in `direction`: the update extent of a request to an input
   * whose data-object pass failed in a parallel run (it has no data object to
   * hold it, and is asked nothing in this pass).
   */
  static bool SkipsDefaultInformation(vtkExecutive* executive, vtkInformation* request, int direction);

protected:
  vtkShockCompositeDataPipeline();
  ~vtkShockCompositeDataPipeline() override;

  int ForwardUpstream(vtkInformation* request) override;
  void CopyDefaultInformation(vtkInformation* request, int direction, vtkInformationVector** inInfoVec,
    vtkInformationVector* outInfoVec) override;
  int InputTypeIsValid(int port, int index, vtkInformationVector** inInfoVec) override;
  int InputFieldsAreValid(int port, int index, vtkInformationVector** inInfoVec) override;

private:
  vtkShockCompositeDataPipeline(const vtkShockCompositeDataPipeline&) = delete;
  void operator=(const vtkShockCompositeDataPipeline&) = delete;
};

#endif
