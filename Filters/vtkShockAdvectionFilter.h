/**
 * @class   vtkShockAdvectionFilter
 * @brief   abstract base of the unconditionally stable shock filters
 *
 * Shock filters (Osher and Rudin 1990) sharpen a signal: values flow away from
 * where the gradient is small towards where it is large, so that blurred edges
 * become sharp discontinuities while extrema keep their values. Following
 * F. Prada and M. Kazhdan, "Unconditionally Stable Shock Filters for Image and
 * Geometry Processing" (Computer Graphics Forum 34(5), 2015), the filter is
 * computed as the advection of the signal along the flow u = 1/2 grad |grad I|^2:
 * every sample is traced back along -u for the flow time t and the input is
 * resampled there. Because values are only ever resampled, the result is stable
 * for any t, and the cost grows sub-linearly with t (flow lines stop at ridges of
 * the potential).
 *
 * This class holds what every shock filter shares: the flow time, the smoothing
 * of the flow, the tracing and sampling rules, the multi-step flow modes and the
 * thread count. Parameters are made scale-free: intensities are divided by the
 * data range of the processed array and lengths by the mean edge length of the
 * domain, so a FlowTime means the same on 8-bit and floating-point data, and on
 * any uniform scaling of the domain.
 *
 * Subclasses: vtkImageShockAdvectionFilter (images and volumes),
 * vtkPolyDataShockAdvectionFilter (signals on triangle meshes).
 *
 * @warning The filter is multi-threaded with OpenMP (NumberOfThreads), not with
 * vtkSMPTools; results do not depend on the number of threads.
 *
 * @sa vtkImageShockAdvectionFilter vtkPolyDataShockAdvectionFilter
 */
#ifndef vtkShockAdvectionFilter_h
#define vtkShockAdvectionFilter_h

#include "vtkPassInputTypeAlgorithm.h"
#include "vtkWeakPointer.h" // for CompositeInput

#include <string>
#include "vtkFiltersShockModule.h" // for export macro

class vtkDataArray;
class vtkAbstractArray;
class vtkMultiProcessController;

class vtkCompositeDataSet;
class vtkExecutive;

class VTKFILTERSSHOCK_EXPORT vtkShockAdvectionFilter : public vtkPassInputTypeAlgorithm
{
public:
  vtkTypeMacro(vtkShockAdvectionFilter, vtkPassInputTypeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Flow modes of paper section 3.3.
  enum FlowModes
  {
    FIXED = 0,    ///< one flow, computed from the input (the paper's choice, sub-linear cost in t)
    COMPOSED = 1, ///< flow recomputed NumberOfFlowUpdates times, back-traces composed
    NAIVE = 2     ///< flow recomputed NumberOfFlowUpdates times, signal resampled after each step
  };

  /// Rules for reading the signal at a back-traced position.
  enum SamplingModes
  {
    LINEAR = 0, ///< multilinear (images) or barycentric (meshes) interpolation
    NEAREST = 1 ///< nearest sample
  };

  /// Rules for following a flow line.
  enum TracingModes
  {
    FACE_CROSSING = 0, ///< exact: straight from face boundary to face boundary (flow is constant per face)
    STEPPED = 1        ///< the paper's Appendix A: steps of at most StepFraction mean edge lengths
  };

  ///@{
  /**
   * Flow time t, in normalised units (intensities divided by the data range of
   * the processed array, lengths by the mean edge length). Must be finite and
   * >= 0; a negative or non-finite value makes RequestData fail with an error.
   * t = 0 returns the input exactly. Typical values 1 to 4096; the result
   * converges to a steady state as t grows. Default 64 (vtkPolyDataShockSharpenFilter: 256).
   */
  vtkSetMacro(FlowTime, double);
  vtkGetMacro(FlowTime, double);
  ///@}

  ///@{
  /**
   * Umbrella-smoothing passes (Gaussian weights exp(-|(v-w)/l|^2), l the mean
   * edge length) applied to the signal before computing the potential and to the
   * potential before computing the flow. More passes suppress noise and small
   * features in the flow. Range [0, 100], default 1 (the paper's setting).
   */
  vtkSetClampMacro(SmoothingPasses, int, 0, 100);
  vtkGetMacro(SmoothingPasses, int);
  ///@}

  ///@{
  /**
   * Tracing step delta as a fraction of the mean edge length, used by the
   * STEPPED tracing mode (the paper uses 0.1). Range [0.001, 1], default 0.1.
   */
  vtkSetClampMacro(StepFraction, double, 0.001, 1.0);
  vtkGetMacro(StepFraction, double);
  ///@}

  ///@{
  /**
   * How the flow evolves: FIXED (default), COMPOSED or NAIVE (see FlowModes).
   * The multi-step modes cost NumberOfFlowUpdates flow computations and have a
   * run time linear in t.
   */
  vtkSetClampMacro(FlowMode, int, FIXED, NAIVE);
  vtkGetMacro(FlowMode, int);
  void SetFlowModeToFixed() { this->SetFlowMode(FIXED); }
  void SetFlowModeToComposed() { this->SetFlowMode(COMPOSED); }
  void SetFlowModeToNaive() { this->SetFlowMode(NAIVE); }
  ///@}

  ///@{
  /**
   * Number of flow computations K for the COMPOSED and NAIVE modes; each
   * advection step lasts FlowTime / K. Ignored by FIXED. Range [1, 1024], default 8.
   */
  vtkSetClampMacro(NumberOfFlowUpdates, int, 1, 1024);
  vtkGetMacro(NumberOfFlowUpdates, int);
  ///@}

  ///@{
  /**
   * How the signal is read at back-traced positions: LINEAR (default) or NEAREST.
   */
  vtkSetClampMacro(Sampling, int, LINEAR, NEAREST);
  vtkGetMacro(Sampling, int);
  void SetSamplingToLinear() { this->SetSampling(LINEAR); }
  void SetSamplingToNearest() { this->SetSampling(NEAREST); }
  ///@}

  ///@{
  /**
   * How flow lines are traced: FACE_CROSSING (default; exact, the limit of the
   * paper's stepping as delta goes to 0, and much faster) or STEPPED (the paper's
   * Appendix A loop with steps of StepFraction mean edge lengths).
   */
  vtkSetClampMacro(TracingMode, int, FACE_CROSSING, STEPPED);
  vtkGetMacro(TracingMode, int);
  void SetTracingModeToFaceCrossing() { this->SetTracingMode(FACE_CROSSING); }
  void SetTracingModeToStepped() { this->SetTracingMode(STEPPED); }
  ///@}

  ///@{
  /**
   * When on, the output also carries the point array "ShockPotential" (the
   * smoothed potential P, in (range-normalised intensity / mean edge length)^2)
   * and the cell array "ShockFlow" (the flow u = 1/2 grad P, 3 components, in
   * mean edge lengths per unit time) of the last flow computation. Default off.
   */
  vtkSetMacro(GenerateFlowArrays, vtkTypeBool);
  vtkGetMacro(GenerateFlowArrays, vtkTypeBool);
  vtkBooleanMacro(GenerateFlowArrays, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Number of OpenMP threads; 0 (default) uses all cores. Range [0, 256].
   * The output does not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 256);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Ghost layers requested around each piece in parallel (pvbatch/pvserver
   * with MPI, or any request for one of several pieces), in samples of the
   * grid (images: point samples, which are also cell layers) or in cell
   * layers (meshes). Range [0, 64], default 16.
   *
   * What it changes: a piece is filtered together with GhostLevels layers of
   * its neighbours' data, so that flow lines starting in the piece can be
   * traced across the piece boundary. A sample gets exactly the serial result
   * when its flow line and the smoothing and gradient stencils around it
   * (about 2 x SmoothingPasses + 2 samples) stay within the ghost layers; one
   * whose flow line would run further is traced as if the data ended there.
   * Flow lines stop at ridges of the potential, so they are short: with the
   * default SmoothingPasses, 8 layers gave the serial result in every
   * measurement (FlowTime up to 4096) and 16 leaves room for up to 4
   * smoothing passes; docs/parallel.md has the measured fractions. 0 filters
   * each piece alone. Rule of thumb: GhostLevels >= 2 x SmoothingPasses + 4.
   *
   * What it costs: each piece reads and filters the grown region, (n + 2 G)^d
   * instead of n^d samples for a piece of n^d samples (images), or G rings of
   * cells more (meshes), plus the exchange of those layers.
   *
   * Images: with a controller (MPI), each piece gets a halo of samples from
   * the processes that hold them (vtkImageShockAdvectionFilter uses
   * GhostLevels as the largest halo: with Method ADVECTION and one flow it
   * starts with the flow's stencil, 2 x SmoothingPasses + 2 samples, and two
   * more, and all pieces get a larger one only when the flow lines of some
   * piece's own samples run further than that leaves exact
   * (shock::GridStencilLayers), so that its result is the serial one; when
   * GhostLevels samples are still too few it warns). Without a controller
   * (serial streaming) the source cuts its piece GhostLevels layers larger.
   * A one-piece request for a sub-extent is served from the whole image. The
   * output is cropped back to what was requested, so pieces tile the image
   * exactly. Cell arrays are grown by the same number of layers.
   * Surfaces: the piece's own cells get rings of their neighbours' cells
   * (fetched over the Controller, one exchange per ring), are filtered with
   * them, and the output holds each owned cell once, shared points marked in
   * vtkGhostType (DUPLICATEPOINT on all copies but the owner's). Ghost cells
   * arriving from upstream are replaced: their depth cannot be checked.
   * vtkPolyDataShockAdvectionFilter uses GhostLevels as the most rings: its
   * pieces start with the rings the flow's stencils need and two more, and
   * get more (all pieces together) only when a flow line of their own points
   * read a triangle whose flow those rings cannot make exact
   * (shock::MeshStencilRings), so that its result is the serial one; when
   * GhostLevels rings are still too few it warns. vtkPolyDataShockSharpenFilter
   * does the same for the normals its fit reads (shock::SharpeningStencilRings,
   * one ring more for the fit; it starts 5 rings beyond the stencil and grows
   * before the fit). Serial runs (one piece) are not affected.
   */
  vtkSetClampMacro(GhostLevels, int, 0, 64);
  vtkGetMacro(GhostLevels, int);
  ///@}

  /**
   * Intensity scale used by the last execution instead of the data range of
   * the processed array: 0 for a serial run (the array's own data range), and
   * for one piece of a parallel run the data range of the array over all
   * pieces (an MPI reduction over the Controller), so that every piece
   * is normalised like the whole data set. Read only.
   */
  vtkGetMacro(ParallelValueScale, double);

  ///@{
  /**
   * The controller the parallel executions communicate through (reductions of
   * the data range and the mean edge length, ghost cells, the distributed fit).
   * Default: the global controller (vtkMultiProcessController::GetGlobalController()).
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * Measurements of the last execution: seconds spent preparing the domain
   * (mesh topology and geometry; 0 for images), computing the flow
   * (smoothing, potential, flow) and advecting (tracing and sampling), and the
   * number of tracing steps (face crossings or delta-steps) over all traces.
   * For vtkImageShockAdvectionFilter with Method PDE, the "advection" seconds
   * are those of the explicit updates and there are no tracing steps.
   */
  vtkGetMacro(LastSetupSeconds, double);
  vtkGetMacro(LastFlowSeconds, double);
  vtkGetMacro(LastAdvectionSeconds, double);
  vtkGetMacro(LastTraceSteps, vtkTypeUInt64);
  ///@}

  /// Names of the optional output arrays.
  static const char* PotentialArrayName() { return "ShockPotential"; }
  static const char* FlowArrayName() { return "ShockFlow"; }

  /**
   * For the filters' executive (vtkShockCompositeDataPipeline): whether the
   * input `updated` for the data request being processed. Returns true when
   * the filter must execute although its input failed, because it runs in
   * parallel (its output asks for one of its Controller's pieces) and the
   * other processes wait for it in a collective step: RequestData then stops
   * every process with the same one-line error. False otherwise: the filter
   * does not execute after a failed input, as any VTK filter.
   */
  bool ExecutesAfterInputFailure(bool updated);

  /**
   * For the filters' executive: whether the input `updated` in the
   * information pass being processed. Returns true when the pipeline must go
   * on although the input's information failed, because the filter may run
   * in parallel (its Controller has more than one process) and the other
   * processes would wait for it: the executive then asks the input nothing
   * more until its information is asked again (InputInformationFailed), and
   * the data request fails upstream, as after ExecutesAfterInputFailure. In
   * serial, or without such a controller, false: the update stops there, as
   * any VTK pipeline's.
   */
  bool ContinuesAfterInformationFailure(bool updated);

  /// Whether the input's last information pass failed on this process of a parallel run.
  bool InputInformationFailed() const { return this->InformationFailed; }

  /**
   * For the filters' executive: whether the input `updated` in the data-object
   * pass being processed (e.g. a reader that cannot tell its output's type
   * because its file is missing on one node). As ContinuesAfterInformationFailure:
   * true when the filter may run in parallel, and the pipeline goes on without
   * the input: its information is not asked in this pass
   * (InputDataObjectFailed), and the information pass goes on as after
   * a failed one. False in serial or without such a controller.
   */
  bool ContinuesAfterDataObjectFailure(bool updated);

  /// Whether the input's last data-object pass failed on this process of a parallel run.
  bool InputDataObjectFailed() const { return this->DataObjectFailed; }

  /**
   * For the filters' executive: whether an input VTK finds invalid (of a
   * type the filter does not take) is let through, because the filter may run
   * in parallel (its Controller has more than one process) and the other
   * processes would wait for it: RequestData then stops every process with
   * the same one-line error naming the input's type. False in serial or
   * without such a controller: VTK refuses the input, as for any filter.
   */
  bool ContinuesAfterInvalidInput() const;

protected:
  vtkShockAdvectionFilter();
  ~vtkShockAdvectionFilter() override;

  /**
   * Whether this filter may run on pieces in parallel: its Controller has more
   * than one process (the pieces themselves are known only in the data pass).
   */
  bool MayRunInParallel() const;

  /// Checks the parameters that clamping cannot enforce; vtkErrorMacro and false if invalid.
  bool ValidateParameters();

  /// Zero the Last* measurements (subclasses add theirs) so a failed run reports nothing stale.
  virtual void ResetMeasurements();

  /**
   * Start of RequestData: ResetMeasurements, then ValidateParameters. False
   * when the execution cannot start: its parameters are invalid (reported),
   * or its input failed to update (ExecutesAfterInputFailure; reported by the
   * filter that failed). `reason`, when given, receives why, for the other
   * processes of a parallel execution.
   */
  bool BeginExecution(std::string* reason = nullptr);

  /// The output type of a data-set input: vtkPolyData (the image filter: vtkImageData).
  virtual const char* PieceOutputType() const { return "vtkPolyData"; }

  /// Creates a vtkShockCompositeDataPipeline.
  vtkExecutive* CreateDefaultExecutive() override;

  /// Notes a composite input before the pipeline hands its blocks to RequestData.
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /// Whether `data` is a block of the composite input (RequestData is filtering it block by block).
  bool IsBlockOfCompositeInput(vtkDataObject* data);

  /// Whether this filter filters `input`'s type (the image filter images, the surface filters surfaces).
  virtual bool FiltersType(vtkDataObject* input) = 0;

  /**
   * A block of a composite input that this filter does not filter (a mesh
   * block under the image filter, an image block under the surface filters)
   * is copied to the output unchanged, said at verbosity 1: returns true.
   * False for anything else (the filter runs).
   */
  bool PassForeignBlock(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  /// Progress/abort bridge for the kernels: UpdateProgress, then false once AbortExecute is set.
  bool ReportProgress(double fraction, const char* phase = nullptr);

  /**
   * The array chosen with SetInputArrayToProcess (index 0), with its association
   * (vtkDataObject::FIELD_ASSOCIATION_POINTS or _CELLS). With no array named
   * (the default, or an empty name) the active point scalars, else the active
   * cell scalars, said at verbosity 1 (vtkLog; quiet at the default INFO).
   * A block of a composite input that lacks the named array takes its own
   * active scalars the same way, with a warning (ParaView names one array for
   * all blocks).
   * Reports a vtkErrorMacro and returns nullptr when it is missing, not
   * numeric, or not point/cell data.
   */
  vtkDataArray* GetArrayToFilter(vtkInformationVector** inputVector, int& association);
  /// The active point scalars, else the active cell scalars (no array named).
  vtkAbstractArray* GetActiveScalarsToFilter(vtkInformationVector** inputVector, int& association);

  /**
   * The controller of this execution's collectives, or nullptr when the
   * output request is not for one of several pieces (see
   * ShockParallel::PieceController); `unknown` flags a piece request that
   * no controller matches.
   */
  vtkMultiProcessController* PieceController(vtkInformationVector* outputVector, bool& unknown);

  /**
   * The data range of the array to process over all pieces (0 when not a
   * parallel piece): every piece is normalised like the whole data set.
   * Collective on `controller` when it is not null.
   */
  double GlobalValueScale(vtkMultiProcessController* controller, vtkInformationVector** inputVector);

  /**
   * The finite range [low, high] of the array to process on the local input,
   * over the samples the kernel normalises with (tuples whose components are
   * all finite). Returns false when there is none.
   */
  virtual bool LocalValueRange(vtkInformationVector** inputVector, double range[2]);

  /// The array GetArrayToFilter would choose, without messages (nullptr when none).
  vtkDataArray* FindArrayToFilter(vtkInformationVector** inputVector, int& association);

  /**
   * The parameters that change the result, as "Name=value;..." (full
   * precision; not NumberOfThreads, which does not): what the processes of a
   * parallel execution compare before any collective step. Subclasses append theirs.
   */
  virtual std::string ParametersText();

  /// Store the measurements of a run; warns when traces were cut at the step limit.
  void RecordRun(double flowSeconds, double advectionSeconds, vtkTypeUInt64 traceSteps,
    vtkTypeUInt64 truncatedTraces);

  double FlowTime = 64.0;
  int SmoothingPasses = 1;
  double StepFraction = 0.1;
  int FlowMode = FIXED;
  int NumberOfFlowUpdates = 8;
  int Sampling = LINEAR;
  int TracingMode = FACE_CROSSING;
  vtkTypeBool GenerateFlowArrays = false;
  int NumberOfThreads = 0;
  int GhostLevels = 16;

  /// Data range over all pieces for the current execution (0: the array's own range).
  double ParallelValueScale = 0.0;
  /// Mean edge length over all pieces for the current execution (0: the mesh's own).
  double ParallelLengthScale = 0.0;
  vtkMultiProcessController* Controller = nullptr;
  /// The input failed to update for this parallel execution (ExecutesAfterInputFailure).
  bool InputFailed = false;
  /// The input's information failed in a parallel run (ContinuesAfterInformationFailure).
  bool InformationFailed = false;
  /// The input's data object failed in a parallel run (ContinuesAfterDataObjectFailure).
  bool DataObjectFailed = false;
  /// The composite input last seen (the pipeline then hands RequestData its blocks one by one).
  vtkWeakPointer<vtkCompositeDataSet> CompositeInput;

  double LastSetupSeconds = 0.0;
  double LastFlowSeconds = 0.0;
  double LastAdvectionSeconds = 0.0;
  vtkTypeUInt64 LastTraceSteps = 0;

private:
  vtkShockAdvectionFilter(const vtkShockAdvectionFilter&) = delete;
  void operator=(const vtkShockAdvectionFilter&) = delete;
};

#endif
