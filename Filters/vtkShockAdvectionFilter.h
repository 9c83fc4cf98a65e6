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
 * domain, so a TimeStep means the same on 8-bit and floating-point data, and on
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
#include "vtkFiltersShockModule.h" // for export macro

class vtkDataArray;

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
   * converges to a steady state as t grows. Default 64.
   */
  vtkSetMacro(TimeStep, double);
  vtkGetMacro(TimeStep, double);
  ///@}

  ///@{
  /**
   * Umbrella-smoothing passes (Gaussian weights exp(-|(v-w)/l|^2), l the mean
   * edge length) applied to the signal before computing the potential and to the
   * potential before computing the flow. More passes suppress noise and small
   * features in the flow. Range [0, 10000], default 1 (the paper's setting).
   */
  vtkSetClampMacro(SmoothingPasses, int, 0, 10000);
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
   * advection step lasts TimeStep / K. Ignored by FIXED. Range [1, 100000], default 8.
   */
  vtkSetClampMacro(NumberOfFlowUpdates, int, 1, 100000);
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
   * Number of OpenMP threads; 0 (default) uses all cores. Range [0, 4096].
   * The output does not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 4096);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Measurements of the last execution: seconds spent preparing the domain
   * (mesh topology and geometry; 0 for images), computing the flow
   * (smoothing, potential, flow) and advecting (tracing and sampling), and the
   * number of tracing steps (face crossings or delta-steps) over all traces.
   */
  vtkGetMacro(LastSetupSeconds, double);
  vtkGetMacro(LastFlowSeconds, double);
  vtkGetMacro(LastAdvectionSeconds, double);
  vtkGetMacro(LastTraceSteps, vtkTypeUInt64);
  ///@}

  /// Names of the optional output arrays.
  static const char* PotentialArrayName() { return "ShockPotential"; }
  static const char* FlowArrayName() { return "ShockFlow"; }

protected:
  vtkShockAdvectionFilter();
  ~vtkShockAdvectionFilter() override = default;

  /// Checks the parameters that clamping cannot enforce; vtkErrorMacro and false if invalid.
  bool ValidateParameters();

  /// Zero the Last* measurements (subclasses add theirs) so a failed run reports nothing stale.
  virtual void ResetMeasurements();

  /// Start of RequestData: ResetMeasurements, then ValidateParameters.
  bool BeginExecution();

  /// Progress/abort bridge for the kernels: UpdateProgress, then false once AbortExecute is set.
  bool ReportProgress(double fraction);

  /**
   * The array chosen with SetInputArrayToProcess (index 0), with its association
   * (vtkDataObject::FIELD_ASSOCIATION_POINTS or _CELLS). Reports a vtkErrorMacro
   * and returns nullptr when it is missing, not numeric, or not point/cell data.
   */
  vtkDataArray* GetArrayToFilter(vtkInformationVector** inputVector, int& association);

  /// Store the measurements of a run; warns when traces were cut at the step limit.
  void RecordRun(double flowSeconds, double advectionSeconds, vtkTypeUInt64 traceSteps,
    vtkTypeUInt64 truncatedTraces);

  double TimeStep = 64.0;
  int SmoothingPasses = 1;
  double StepFraction = 0.1;
  int FlowMode = FIXED;
  int NumberOfFlowUpdates = 8;
  int Sampling = LINEAR;
  int TracingMode = FACE_CROSSING;
  vtkTypeBool GenerateFlowArrays = false;
  int NumberOfThreads = 0;

  double LastSetupSeconds = 0.0;
  double LastFlowSeconds = 0.0;
  double LastAdvectionSeconds = 0.0;
  vtkTypeUInt64 LastTraceSteps = 0;

private:
  vtkShockAdvectionFilter(const vtkShockAdvectionFilter&) = delete;
  void operator=(const vtkShockAdvectionFilter&) = delete;
};

#endif
