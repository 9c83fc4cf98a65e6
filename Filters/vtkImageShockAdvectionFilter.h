/**
 * @class   vtkImageShockAdvectionFilter
 * @brief   shock-filter advection of images (2D) and volumes (3D)
 *
 * Sharpens the edges of the selected array of a vtkImageData by shock-filter
 * advection (Prada and Kazhdan 2015, section 3 and Appendix A; see
 * vtkShockAdvectionFilter for the principle and the shared parameters).
 *
 * The samples are the grid points and the faces are the squares (2D) or cubes
 * (3D) between them; images with a single row (1 x N) are 1D signals, and flat
 * images may lie in any plane (XY, XZ or YZ). The face gradient is the average
 * of the finite differences on the face's parallel edges, the potential at a
 * sample is the average of |grad I|^2 (summed over all components) over its
 * adjacent faces, and every sample is back-traced from an offset into each
 * adjacent face; the results are averaged. Spacing (also anisotropic), origin
 * and direction are respected; lengths are measured in mean edge lengths.
 *
 * The array comes from SetInputArrayToProcess (default: the active point
 * scalars). Any numeric type and number of components is accepted; all
 * components share one flow, so colours do not fringe. The output keeps the
 * array's name, type and attribute role (integer types are rounded and clamped);
 * every other array passes through untouched. Cell data is processed on the grid
 * of cell centres. Non-finite values (NaN, inf) keep their place and do not spread.
 *
 * With GenerateFlowArrays, the output gets "ShockPotential" on the processed
 * samples (point data, or cell data when a cell array is filtered) and
 * "ShockFlow", the per-face flow in world axes: a cell array for point data, and
 * for cell data a point array on the interior points (the centres of the faces
 * between cell centres; zero on the boundary).
 *
 * In parallel (one piece per process, as in pvbatch or pvserver with MPI,
 * the filter's Controller set) each piece gets a halo of samples: read with
 * the piece when the source cuts any extent (GetLastHaloFromSource), else
 * from the processes that hold them (into layers beside the piece, without a
 * copy of it, when the halo lies along the piece's last axis:
 * GetLastHaloInLayers). It is filtered with it (only its own samples are
 * traced) and keeps its own extent, so that the pieces tile the image; every
 * piece is normalised by the data range over all pieces (ParallelValueScale)
 * and measures lengths in the whole image's mean edge. With Method ADVECTION
 * and one flow the halo is sized from the flow lines (GetLastGhostLevels): the
 * result equals the serial one, or a warning says GhostLevels is too small;
 * the other methods take GhostLevels samples. See GhostLevels and
 * docs/parallel.md. Without a controller (serial streaming) the filter asks
 * the source for GhostLevels more ghost levels and crops the output back to
 * the piece requested. Cell data: the halo is counted in cells. An input that
 * is not cut into pieces (a reader that gives the whole image to one process)
 * is kept whole.
 *
 * Method selects how the shock filter is computed: ADVECTION (default, the
 * paper's method, above) or PDE, the Osher-Rudin shock-filter PDE integrated
 * with the classic explicit upwind/minmod scheme (GridShockPDE.h): equation
 * (1) of the paper with F the identity and the second derivative along the
 * gradient as edge detector, which is equation (2), the PDE that the advection
 * solves. It uses the same flow (so SmoothingPasses means the same), the same
 * normalisation and the same flow time FlowTime, so that both methods can be
 * compared parameter for parameter; FlowMode, NumberOfFlowUpdates, Sampling,
 * TracingMode and StepFraction do not apply to it. Its cost is linear in
 * FlowTime (one flow computation per CFL step, CourantNumber) and it is meant
 * as a reference, not for production: see the paper's Figure 9 and
 * docs/paper-evidence.md. In parallel each piece integrates the PDE on its
 * piece with its ghost layers, so pieces agree with the serial result only
 * near their centres (a step moves information by up to 2 x SmoothingPasses + 2
 * samples).
 *
 * @warning Errors (RequestData returns 0): negative or non-finite FlowTime,
 * missing or non-numeric array, field-data array, zero spacing. An empty image
 * passes through with a warning.
 *
 * @sa vtkShockAdvectionFilter
 */
#ifndef vtkImageShockAdvectionFilter_h
#define vtkImageShockAdvectionFilter_h

#include "vtkShockAdvectionFilter.h"
#include "vtkFiltersShockModule.h" // for export macro

#include <array>   // for the written samples
#include <cstdint> // for the written samples

class vtkDataArray;
class vtkImageData;
class vtkMultiProcessController;
namespace ShockParallel
{
struct ImageLayers;
}
namespace shock
{
struct GridShape;
struct GridFlowFields;
struct Status;
}
namespace ShockImageInternals
{
struct SampleTarget;
}
namespace ShockFilterInternals
{
struct KernelOutput;
struct GridRun;
}

class VTKFILTERSSHOCK_EXPORT vtkImageShockAdvectionFilter : public vtkShockAdvectionFilter
{
public:
  static vtkImageShockAdvectionFilter* New();
  vtkTypeMacro(vtkImageShockAdvectionFilter, vtkShockAdvectionFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How the shock filter is computed.
  enum Methods
  {
    ADVECTION = 0, ///< back-tracing along the flow (Prada and Kazhdan 2015): stable for any t
    PDE = 1        ///< explicit Osher-Rudin PDE (upwind/minmod, CFL step): the baseline
  };

  ///@{
  /**
   * ADVECTION (default) or PDE; see the class documentation.
   */
  vtkSetClampMacro(Method, int, ADVECTION, PDE);
  vtkGetMacro(Method, int);
  void SetMethodToAdvection() { this->SetMethod(ADVECTION); }
  void SetMethodToPDE() { this->SetMethod(PDE); }
  ///@}

  /// What the advection carries along the flow.
  enum Domains
  {
    VALUES = 0,   ///< the signal's values (the paper)
    GRADIENTS = 1 ///< the signal's gradients, integrated back (beyond the paper: docs/gradient-domain.md)
  };

  ///@{
  /**
   * ADVECTION method: VALUES (default) advects the signal's values, as the
   * paper does. GRADIENTS is the gradient-domain mode the paper's section 6
   * proposes as future work (GridGradientDomain.h, docs/gradient-domain.md):
   * the signal's differences are carried along the flow of its values, each
   * grid edge keeps the advected difference where the flow stretches it (the
   * sharpened edges) and the difference carried from the trace's end where the
   * flow compresses it (the shading that value advection flattens), and a
   * screened Poisson solve (GradientScreening) integrates them back into a
   * signal. It needs the whole image in one piece (the solve couples every
   * sample), finite values, FlowMode FIXED, and Method ADVECTION; anything else
   * is an error. Its memory is about 8 x C x (1 + 2 x axes) bytes per sample
   * (C components). Default VALUES.
   */
  vtkSetClampMacro(Domain, int, VALUES, GRADIENTS);
  vtkGetMacro(Domain, int);
  void SetDomainToValues() { this->SetDomain(VALUES); }
  void SetDomainToGradients() { this->SetDomain(GRADIENTS); }
  ///@}

  ///@{
  /**
   * Domain GRADIENTS: the screening weight lambda of the Poisson solve, per
   * squared mean edge length. The result keeps the input's structure longer
   * than about 1 / sqrt(lambda) edges and takes the advected gradients below
   * it: larger values stay closer to the input. Range [1e-6, 1e6], default 0.01.
   */
  vtkSetClampMacro(GradientScreening, double, 1e-6, 1e6);
  vtkGetMacro(GradientScreening, double);
  ///@}

  ///@{
  /**
   * ADVECTION method: number of resolution levels of the coarse-to-fine
   * tracing, beyond the paper (after its section 6; docs/hierarchy.md). 1, the
   * default, is the paper's single level. With L > 1 a pyramid of the signal
   * halves every axis L - 1 times, every level computes its own flow, and every
   * back-trace starts at the coarsest level and continues at each finer one
   * (the input is sampled once, at the finest), so that traces cross the small
   * potential maxima of noise and texture on their way to large edges. Every
   * level runs the same FlowTime in the input's units. Levels the image is too
   * small for (an axis below 3 samples) are not built. Range [1, 16], default 1.
   */
  vtkSetClampMacro(HierarchyLevels, int, 1, 16);
  vtkGetMacro(HierarchyLevels, int);
  ///@}

  ///@{
  /**
   * PDE method: Courant number of the explicit step, dt = CourantNumber /
   * (max |u| x sum over axes of 1 / spacing), spacings in mean edge lengths.
   * Range [0.01, 1], default 0.5; above 1 the scheme is not stable.
   */
  vtkSetClampMacro(CourantNumber, double, 0.01, 1.0);
  vtkGetMacro(CourantNumber, double);
  ///@}

  ///@{
  /**
   * PDE method: the most explicit steps one execution may take. When they do
   * not reach FlowTime, the output holds the solution at the time reached
   * (LastReachedTime) and a warning says so. Range [1, 100000000], default 100000.
   */
  vtkSetClampMacro(MaximumIterations, int, 1, 100000000);
  vtkGetMacro(MaximumIterations, int);
  ///@}

  ///@{
  /**
   * PDE method, measurements of the last execution: explicit steps taken and
   * the flow time reached (FlowTime, unless MaximumIterations stopped it
   * first). Both 0 after an ADVECTION run.
   */
  vtkGetMacro(LastIterations, vtkTypeInt64);
  vtkGetMacro(LastReachedTime, double);
  ///@}

  /**
   * Parallel runs (pieces with a controller), measurement of the last
   * execution: the halo samples every piece had when its result was made, the
   * same on every process (0 for a serial run). With Method ADVECTION, Domain
   * VALUES and one flow (FlowMode Fixed, or one update) on one level, a piece
   * starts with the halo the flow's stencil needs (2 x SmoothingPasses + 2
   * samples) and two more; when the flow lines of some piece's own samples run
   * further into the halo than that leaves exact, every process filters its
   * piece again with a larger halo, up to GhostLevels (a warning when that is
   * still too small). The result then equals the serial one. Other methods
   * and flows take GhostLevels samples.
   */
  vtkGetMacro(LastGhostLevels, int);

  /// Parallel runs: how many times the last execution filtered the pieces (1 + the halo's growths; 0 serial).
  vtkGetMacro(LastHaloAttempts, int);

  /**
   * Parallel runs: whether the last result was made from pieces the source
   * read with their halo (true), or from pieces whose halo came from the other
   * processes (false). A source that cuts any extent (an image reader, the
   * Wavelet; vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT) is asked for the piece with
   * its halo, and the filter reads it where it is: no copy of the piece and no
   * exchange. When downstream asks for ghost levels, when the source cannot
   * cut extents, when a piece would be empty or one point thick, when the
   * other arrays hold more bytes than the filtered one (as the input last
   * came; unknown before its first execution), or when the flow lines need a
   * wider halo than was read, the halo is exchanged. Process 0's, in ParaView.
   */
  vtkGetMacro(LastHaloFromSource, bool);

  /**
   * Parallel runs: whether the last result read each piece where it lies and
   * its halo in layers of their own (true; shock::LayeredSignal), instead of
   * a copy of the piece with its halo. Taken when the halo came from the other
   * processes and lies only along the piece's last axis of more than one
   * sample (the pipeline cuts a volume into slabs along z, an image into rows
   * along y), the filtered array is float, double or 8-bit, Method is
   * ADVECTION, Domain VALUES, HierarchyLevels 1, and no piece has blanked
   * samples. When every piece's halo would lie so, the source is asked for the
   * plain pieces (no second execution with the halo, GetLastHaloFromSource
   * false). Process 0's, in ParaView.
   */
  vtkGetMacro(LastHaloInLayers, bool);

  ///@{
  /// The filtered image (output port 0, or the given port).
  vtkImageData* GetOutput();
  vtkImageData* GetOutput(int port);
  ///@}

protected:
  std::string ParametersText() override;

  vtkImageShockAdvectionFilter();
  ~vtkImageShockAdvectionFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  const char* PieceOutputType() const override { return "vtkImageData"; }

  /// A piece of a distributed image asks a source that cuts any extent for the piece with
  /// its halo (PieceFromSource), else for what is asked of it (the halo comes from the
  /// other processes); a piece without a controller, its extent grown by GhostLevels (and
  /// as many ghost levels); a sub-extent of one piece, the whole extent (cropped after:
  /// the samples equal the whole image's result).
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /// Crop the output (filtered on the larger input extent) to the output's UPDATE_EXTENT.
  void CropToUpdateExtent(vtkInformationVector* outputVector);

  /// The data range over all pieces, FilterImage, then CropToUpdateExtent.
  /// Images (a block of another type in a composite input passes through).
  bool FiltersType(vtkDataObject* input) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /// Filter the input image (with its ghost layers) into the output; `piece`: one of several.
  int FilterImage(vtkInformationVector** inputVector, vtkInformationVector* outputVector, bool piece);

  /// Filter `array` (checked, of `association`) of `input` into `output` (which starts as
  /// `input`); `wholeExtent`: of the image `input` is a piece of (null: `input` is whole).
  int FilterImageArray(vtkImageData* input, vtkDataArray* array, int association, vtkImageData* output,
    const int* wholeExtent = nullptr);

  /// Filter `array` (checked, of `association`) of `input`: the results of the
  /// target's samples replace its array (see SampleTarget).
  int FilterSamples(vtkImageData* input, vtkDataArray* array, int association,
    const ShockImageInternals::SampleTarget& target);

  /**
   * A piece of a distributed image (collective on `controller`): every process
   * checks its piece and they agree; the piece is filtered with its halo, read
   * in place when every process's source read it (PieceFromSource), else
   * received from the processes that hold it (ShockParallel::GrowImageSamples);
   * the output is the piece with the filtered rows.
   */
  int FilterPieceWithHalo(vtkMultiProcessController* controller, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector);

  void ResetMeasurements() override;

  /// The flow's stencil in halo samples (shock::GridStencilLayers); -1 when the halo stays GhostLevels.
  int HaloStencil();
  /// Whether the settings let the kernel read a piece's halo in layers
  /// (GetLastHaloInLayers: Method ADVECTION, Domain VALUES, one hierarchy level).
  bool ReadsHaloInLayers() const;
  /**
   * Whether a piece of a distributed image is asked of its source with its
   * halo (see GetLastHaloFromSource): then `own` is the piece this process
   * owns (the pipeline's cut of the extent asked of the filter, no ghost
   * levels) and `grown` the extent asked for, the piece with the starting
   * halo. Not when a piece would have no samples on an axis the image spans
   * (the same answer on every process), nor when it would hold more bytes
   * than the exchange (other arrays besides the filtered one).
   */
  bool PieceFromSource(vtkInformation* inInfo, vtkInformation* outInfo, int own[6], int grown[6]);

  /// The halo the pieces start with (collective): the stencil and two more, or what the last
  /// execution of this input agreed on, at most GhostLevels.
  int StartingHalo(vtkImageData* input, vtkDataArray* array, vtkMultiProcessController* controller, int stencil);

  int Method = ADVECTION;
  int Domain = VALUES;
  double GradientScreening = 0.01;
  int HierarchyLevels = 1;
  double CourantNumber = 0.5;
  int MaximumIterations = 100000;
  vtkTypeInt64 LastIterations = 0;
  double LastReachedTime = 0.0;
  int LastGhostLevels = 0;
  int LastHaloAttempts = 0;
  bool LastHaloFromSource = false;
  bool LastHaloInLayers = false;
  bool AskedPieceFromSource = false; ///< RequestUpdateExtent asked the source for AskedPiece with its halo
  int AskedPiece[6] = { 0, -1, 0, -1, 0, -1 };
  int AgreedHalo = 0;                               ///< the halo the last parallel execution agreed on
  std::array<std::uintptr_t, 3> AgreedInputStamp{}; ///< of this input (object, size, array; compared only)

private:
  /// Run the selected method on the array's samples, results to `output`; false (with
  /// vtkErrorMacro) on failure.
  bool RunKernel(const shock::GridShape& grid, vtkDataArray* array,
    const ShockFilterInternals::KernelOutput& output, shock::GridFlowFields* fields,
    const std::array<std::int64_t, 6>& written, bool& aborted, std::array<std::int64_t, 6>& reach,
    const ShockParallel::ImageLayers* layers = nullptr);
  /// The paper's advection (Method ADVECTION), of the values or of their gradients (Domain).
  shock::Status RunAdvection(
    const ShockFilterInternals::GridRun& run, bool& aborted, std::array<std::int64_t, 6>& reach);
  /// The Osher-Rudin PDE, integrated explicitly (Method PDE), on a double copy of the signal.
  shock::Status RunPDE(ShockFilterInternals::GridRun& run, bool& aborted);

  vtkImageShockAdvectionFilter(const vtkImageShockAdvectionFilter&) = delete;
  void operator=(const vtkImageShockAdvectionFilter&) = delete;
};

#endif
