/**
 * @class   vtkPolyDataShockSharpenFilter
 * @brief   sharpen the geometry of a triangle mesh: shock-filtered normals, screened Poisson fit
 *
 * Geometry sharpening of Prada and Kazhdan (2015), section 4.1. The face
 * normals are treated as a 3-channel signal and sharpened by shock-filter
 * advection (see vtkShockAdvectionFilter for the shared parameters): per-point
 * normals (area-weighted) define the potential P = sum_j |grad N_j|^2, the sum of
 * the squared principal curvatures, so normals flow towards the extrema of total
 * curvature and become discontinuous there. The points are then moved so that
 * the surface's normals match the sharpened ones, by solving the screened
 * Poisson equation (eps M + S) c1 = eps M c0 + div w, with w the target
 * gradients of the coordinates (FitTarget), M the finite-element mass matrix and
 * S the cotangent stiffness matrix. Creases and corners come out sharp; flat and
 * smooth parts stay as they are.
 *
 * Four departures from the paper, each with a value that reproduces it
 * (docs/sharpening.md has the evaluation): creases sharper than FeatureAngle are
 * kept as they are (the paper's per-point normals round them: 180 reproduces
 * it); the fit maps each triangle onto its target plane by a central
 * projection from the centre of curvature instead of an orthogonal
 * projection, so that sharpening does not shrink the shape (FitTarget
 * PROJECTION reproduces the paper); and the advection's potential keeps only
 * what stands out CurvatureContrast times above its surroundings, so that a
 * coarsely tessellated smooth shape is not sharpened (0 reproduces the paper);
 * the fit holds the points whose triangles the sharpening did not turn
 * where they were (AnchorWeight, AnchorAngle; AnchorWeight 0 reproduces the paper);
 * and the part of the fitted displacement smoother than DriftRadius edges
 * is removed, so that no region moves as a whole (DriftRadius 0 reproduces
 * the paper).
 *
 * FlowTime (of the base class) defaults to 256 here, not 64: a crease rounded
 * over 4 rows of triangles is sharp again from t = 128, over 6 rows from 512,
 * over 8 rows from 1024 (the time grows about like the fourth power of the
 * width). Smooth shapes do not move more at longer times (docs/sharpening.md,
 * "Choosing the flow time").
 *
 * Parameters specific to this filter: FeatureAngle, CurvatureContrast, FitTarget,
 * NormalSmoothingPasses (pre-mollification of noisy normals), KeepUnmovedNormals, ScreeningWeight
 * (eps), AnchorWeight, AnchorAngle, DriftRadius, Solver, SolverIterations, SolverTolerance, MergeCoincidentPoints,
 * GenerateSharpenedNormals. Of the base
 * class, Sampling LINEAR (default) interpolates the per-point normals
 * barycentrically, which also smooths the normals (even at FlowTime 0, as the
 * paper's Figure 7 shows); NEAREST copies the normal of the triangle reached, so
 * that FlowTime 0 with the EXACT solver returns the input. The normals are unit
 * vectors, so their intensity scale is fixed (2) instead of the data range: the
 * filter selects no input array.
 *
 * Meshes as users have them:
 * - closed and open meshes: boundary points are unknowns of the fit like any
 *   other (natural boundary conditions); only the screening anchors them;
 * - polygons with more than three points and strips are triangulated internally;
 *   the output keeps the input's cells (with the new point positions);
 * - degenerate (zero-area) triangles and triangles that repeat another
 *   triangle's vertex set (a mesh appended to itself, in either orientation)
 *   are removed for the computation, so the result is that of the mesh without
 *   them (repeated triangles with a warning that counts them; both counts in
 *   LastRepeatedTriangles and LastDegenerateTriangles); points used by no triangle keep
 *   their position; vertex and line cells pass through;
 * - exactly coincident points (e.g. the seams of STL files) are merged for the
 *   computation when MergeCoincidentPoints is on (default), so the surface is
 *   treated as connected; every copy receives the same new position;
 * - several components are sharpened together (independently in effect).
 *
 * Output: the input's points (new coordinates, same type), cells and arrays
 * (passed through), except the active normals: active point normals become the
 * mean of the unit normals of the cells around each point and active cell
 * normals the cells' unit normals, both of the new geometry (as
 * vtkPolyDataNormals computes them without splitting), in the same array type
 * and name. Field data gets "ShockSolverIterations",
 * "ShockSolverResidual", "ShockFlippedTriangles" and "ShockMaxDisplacement"
 * (largest displacement / bounding-box diagonal), which are also logged at
 * verbosity 1 (quiet at the default INFO). Optional cell arrays: "ShockNormals" (the sharpened normals);
 * with GenerateFlowArrays, "ShockPotential" (points) and "ShockFlow" (cells).
 *
 * Parallel use: a mesh split over MPI processes (e.g. by RedistributeDataSet,
 * D3 or a partitioned .pvtp file; unstructured grids of polygons are read as
 * polydata) gives the serial result. Each piece gets layers of ghost cells
 * (rings built with the mesh's connectivity: as many as its normals' flow
 * lines need, at most GhostLevels, see GetLastGhostLevels) and global point ids; normals,
 * potential, flow and advection run per piece, normalised by the mean edge
 * length over all pieces; the screened Poisson fit runs across the processes
 * of the Controller: area and centroid summed over the pieces, the same
 * Jacobi-preconditioned conjugate gradients with global sums and an exchange
 * of the points each piece needs from its neighbours (shock::MeshPartition).
 * The result equals the serial one up to the order of the sums (the fixed 25
 * iterations are not converged, so that order shows at 1e-7 of the size;
 * converged solves agree to 1e-13; docs/parallel.md). The EXACT solver is
 * refused on a split mesh. A mesh every process holds whole (replicated) is
 * sharpened once, on process 0; the others output nothing.
 *
 * @warning Errors (RequestData returns 0): negative or non-finite FlowTime,
 * non-finite point coordinates, a failed exact factorisation, the EXACT
 * solver on a split mesh, a piece request without a matching controller. An empty input, or
 * one without polygons, passes through with a warning.
 *
 * @sa vtkShockAdvectionFilter vtkPolyDataShockAdvectionFilter
 */
#ifndef vtkPolyDataShockSharpenFilter_h
#define vtkPolyDataShockSharpenFilter_h

#include "vtkFiltersShockModule.h" // for export macro
#include "vtkShockAdvectionFilter.h"

#include <memory> // for std::unique_ptr
#include <string> // for errors
#include <vector> // for the kernels' buffers

class vtkPolyData;
namespace shock
{
class TriangleMesh;
struct MeshPartition;
struct SharpeningCache;
struct SharpeningReport;
struct MeshFlowFields;
}
namespace ShockPolyDataInternals
{
class MeshCache;
struct PreparedMesh;
class RingAgreement;
}
namespace ShockParallel
{
struct SurfacePiece;
}

class VTKFILTERSSHOCK_EXPORT vtkPolyDataShockSharpenFilter : public vtkShockAdvectionFilter
{
public:
  static vtkPolyDataShockSharpenFilter* New();
  vtkTypeMacro(vtkPolyDataShockSharpenFilter, vtkShockAdvectionFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How the screened Poisson system is solved.
  enum Solvers
  {
    CONJUGATE_GRADIENT = 0,           ///< SolverIterations of Jacobi-preconditioned CG (the paper: 25)
    CONJUGATE_GRADIENT_TOLERANCE = 1, ///< CG until the relative residual is below SolverTolerance
    EXACT = 2                         ///< sparse Cholesky (LDL^T) factorisation
  };

  /// What the fit asks each triangle's edges to become (see FitTarget).
  enum FitTargets
  {
    PROJECTION = 0, ///< their projection onto the target plane (the paper); shortens edges
    ROTATION = 1,   ///< their rotation onto the target plane: lengths kept
    SHEAR = 2,      ///< moved along the triangle's normal onto the target plane
    CENTRAL_PROJECTION = 3 ///< projected from the centre of curvature onto the target plane (default)
  };

  ///@{
  /**
   * Creases whose face normals differ by more than this angle (degrees) across
   * an edge are already sharp and are kept: the normals are neither averaged
   * nor traced across them (as vtkPolyDataNormals splits at its FeatureAngle).
   * The potential that moves the normals is still computed across them, so a
   * blurred crease is sharpened, whether it turns by small angles from edge to
   * edge or is still sharper than this angle with bent faces beside it (a
   * Gaussian blur). A corner whose averaged normal is more than this angle
   * from one of its faces' normals (the apex of a cone) is read per face when
   * the normals are sampled, so that it does not tilt them. Measured on the
   * normals after NormalSmoothingPasses. Range [0, 180], default 30; 180 (no
   * feature edge) reproduces the paper. On a CAD tessellation with curved
   * surfaces or designed roundings (facets turning by 5 to 15 degrees per
   * edge), set it just below the facets' angle (5 to 10): below this angle
   * the facets are sharpened like a blurred crease (docs/sharpening.md,
   * "Designed roundings and coarse tessellations").
   */
  vtkSetClampMacro(FeatureAngle, double, 0.0, 180.0);
  vtkGetMacro(FeatureAngle, double);
  ///@}

  ///@{
  /**
   * Tells a smooth shape from a blurred crease (not the paper's): the
   * advection's potential |grad N|^2 keeps only what exceeds this many times
   * its minimum over the points within 6 rings. A sphere or a torus, however
   * coarsely tessellated, has a potential that varies by less than that and is
   * left alone; a blurred crease is a peak over flat sides and is sharpened as
   * before. Range [0, 1000], default 16; 0 reproduces the paper's potential (the
   * output of the filter before this setting, to the last bit).
   * docs/sharpening.md, "Telling a smooth shape from a blurred crease".
   */
  vtkSetClampMacro(CurvatureContrast, double, 0.0, 1000.0);
  vtkGetMacro(CurvatureContrast, double);
  ///@}

  ///@{
  /**
   * What the fit asks each triangle's edges to become, all with the sharpened
   * normal N. CENTRAL_PROJECTION (default): the image of the edge under the
   * central projection onto the target plane from the centre of curvature,
   * which maps a crease rounded with a constant radius exactly onto the sharp
   * crease it was rounded from; SHEAR: moved along the triangle's own normal
   * onto the target plane (its footprint kept); ROTATION: turned by the
   * smallest rotation taking the triangle's normal to N (lengths kept);
   * PROJECTION: the paper's w = grad c0 - N <N, grad c0>, projected onto the
   * target plane (shortened). A rounded crease is shorter than the corner it
   * was rounded from, so the shorter the edges come out, the more the shape
   * shrinks as it sharpens (docs/sharpening.md has the evaluation). SHEAR and
   * CENTRAL_PROJECTION rotate triangles tilted by more than 45 degrees.
   */
  vtkSetClampMacro(FitTarget, int, PROJECTION, CENTRAL_PROJECTION);
  vtkGetMacro(FitTarget, int);
  void SetFitTargetToProjection() { this->SetFitTarget(PROJECTION); }
  void SetFitTargetToRotation() { this->SetFitTarget(ROTATION); }
  void SetFitTargetToShear() { this->SetFitTarget(SHEAR); }
  void SetFitTargetToCentralProjection() { this->SetFitTarget(CENTRAL_PROJECTION); }
  ///@}

  ///@{
  /**
   * Laplacian smoothing passes of the face normals before the advection, with
   * the positions fixed (the paper's Figure 11, for noisy scans). Each pass
   * replaces a normal by the renormalised area-weighted mean of itself and its
   * edge neighbours. With KeepUnmovedNormals (the default) the triangles the
   * flow does not move keep their own normals. Range [0, 100], default 0.
   */
  vtkSetClampMacro(NormalSmoothingPasses, int, 0, 100);
  vtkGetMacro(NormalSmoothingPasses, int);
  ///@}

  ///@{
  /**
   * Not the paper's: a triangle on which the flow is zero (the advection does
   * not move it) keeps its own input normal as its target, instead of the
   * Linear sampling's interpolated average (and instead of its smoothed normal
   * after NormalSmoothingPasses). So a smooth shape the flow leaves alone
   * (CurvatureContrast) does not move at all, and the normal smoothing acts
   * where the flow does (docs/sharpening.md, "What the flow does not move
   * keeps its normal"). Applies with FlowMode FIXED (the default); the other
   * modes recompute the flow and sample every triangle. Off: the paper's
   * sampling everywhere, and the normal smoothing calms the noise of flat
   * parts too (for noisy scans). Default on.
   */
  vtkSetMacro(KeepUnmovedNormals, vtkTypeBool);
  vtkGetMacro(KeepUnmovedNormals, vtkTypeBool);
  vtkBooleanMacro(KeepUnmovedNormals, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Screening weight eps of the fit, for the mesh normalised to unit area (so it
   * does not depend on the mesh's size or position). Larger values keep the
   * points closer to the input. Range [1e-6, 1e6], default 1 (the paper's value).
   */
  vtkSetClampMacro(ScreeningWeight, double, 1e-6, 1e6);
  vtkGetMacro(ScreeningWeight, double);
  ///@}

  ///@{
  /**
   * Not the paper's: the fit holds in place the points whose triangles the
   * sharpening did not turn. A point whose triangles' sharpened normals all lie
   * within AnchorAngle degrees of their input normals gets an extra screening
   * of AnchorWeight times its row's diagonal in the fit, fading linearly to
   * none at AnchorAngle; so the fit no longer drifts the flat and smooth parts
   * away from where they were while it moves the creases (docs/sharpening.md,
   * "Points the sharpening did not turn stay"). AnchorWeight 0 or AnchorAngle
   * 0 is the paper's fit. AnchorWeight: range [0, 1e6], default 1;
   * AnchorAngle: degrees, range [0, 180], default 5.
   */
  vtkSetClampMacro(AnchorWeight, double, 0.0, 1e6);
  vtkGetMacro(AnchorWeight, double);
  vtkSetClampMacro(AnchorAngle, double, 0.0, 180.0);
  vtkGetMacro(AnchorAngle, double);
  ///@}

  ///@{
  /**
   * Not the paper's: the sharpening keeps the surface's local mean position.
   * The part of the fitted displacement smoother than DriftRadius edge lengths
   * (its heat diffusion over that radius; an edge length is the side of an
   * equilateral triangle of the mesh's mean triangle area) is removed after
   * the fit: points move against each other within a few edges, so creases
   * form, but no region moves as a whole, and the area-weighted mean position
   * is kept, as blurs that keep the local mean (windowed sinc, Taubin) keep
   * it; on blurs that shrink creases (Laplacian, Gaussian) it keeps a little
   * of their lost volume lost (docs/sharpening.md, "Keeping the local mean:
   * DriftRadius"). Default 8; 0 is the paper's fit. Range [0, 1000].
   */
  vtkSetClampMacro(DriftRadius, double, 0.0, 1000.0);
  vtkGetMacro(DriftRadius, double);
  ///@}

  ///@{
  /// Solver of the fit: CONJUGATE_GRADIENT (default), CONJUGATE_GRADIENT_TOLERANCE or EXACT.
  vtkSetClampMacro(Solver, int, CONJUGATE_GRADIENT, EXACT);
  vtkGetMacro(Solver, int);
  void SetSolverToConjugateGradient() { this->SetSolver(CONJUGATE_GRADIENT); }
  void SetSolverToConjugateGradientTolerance() { this->SetSolver(CONJUGATE_GRADIENT_TOLERANCE); }
  void SetSolverToExact() { this->SetSolver(EXACT); }
  ///@}

  ///@{
  /**
   * Conjugate-gradient iterations of the CONJUGATE_GRADIENT solver, started from
   * the input positions; also the iteration cap of CONJUGATE_GRADIENT_TOLERANCE.
   * Range [0, 10000], default 25 (the paper's value).
   */
  vtkSetClampMacro(SolverIterations, int, 0, 10000);
  vtkGetMacro(SolverIterations, int);
  ///@}

  ///@{
  /**
   * Relative residual |b - A x| / |b| at which CONJUGATE_GRADIENT_TOLERANCE stops.
   * Range [0, 1], default 1e-6.
   */
  vtkSetClampMacro(SolverTolerance, double, 0.0, 1.0);
  vtkGetMacro(SolverTolerance, double);
  ///@}

  ///@{
  /**
   * Merge exactly coincident points for the computation (the output keeps all
   * points, each copy moved alike). Default on.
   */
  vtkSetMacro(MergeCoincidentPoints, vtkTypeBool);
  vtkGetMacro(MergeCoincidentPoints, vtkTypeBool);
  vtkBooleanMacro(MergeCoincidentPoints, vtkTypeBool);
  ///@}

  ///@{
  /// Add the sharpened unit normals as the cell array "ShockNormals". Default off.
  vtkSetMacro(GenerateSharpenedNormals, vtkTypeBool);
  vtkGetMacro(GenerateSharpenedNormals, vtkTypeBool);
  vtkBooleanMacro(GenerateSharpenedNormals, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Measurements of the last execution: seconds of the fit's system set-up and
   * solve, solver iterations and final relative residual, triangles whose
   * orientation flipped, and the largest displacement relative to the
   * bounding-box diagonal. (LastSetupSeconds holds the mesh preparation.)
   */
  vtkGetMacro(LastFitSetupSeconds, double);
  vtkGetMacro(LastFitSolveSeconds, double);
  vtkGetMacro(LastSolverIterations, int);
  vtkGetMacro(LastSolverResidual, double);
  vtkGetMacro(LastFlippedTriangles, vtkIdType);
  vtkGetMacro(LastMaxDisplacement, double);
  ///@}

  ///@{
  /// Of the last execution: triangles removed as repeats or degenerate, and feature edges kept.
  vtkGetMacro(LastRepeatedTriangles, vtkIdType);
  vtkGetMacro(LastDegenerateTriangles, vtkIdType);
  vtkGetMacro(LastFeatureEdges, vtkIdType);
  ///@}

  /**
   * The ghost rings each piece had in the last execution (0 when serial).
   * In parallel a piece starts with the rings its sharpened normals' stencils
   * need (shock::SharpeningStencilRings, one more for the fit's rows, two
   * more to spare) and gets more only when a flow line of the normals the fit
   * reads ran deeper than its rings make exact, up to GhostLevels (then a
   * warning); see vtkShockAdvectionFilter::SetGhostLevels.
   */
  vtkGetMacro(LastGhostLevels, int);

  /**
   * How many times the last execution advected the normals of its piece: 1
   * when the starting rings were enough (always in serial), one more each
   * time every piece got more rings (before the fit, which runs once). A
   * second execution of the same input (a parameter changed) starts with the
   * rings the first one agreed on.
   */
  vtkGetMacro(LastRingAttempts, int);

  ///@{
  /**
   * How many times the mesh was prepared (triangles, connectivity, geometry)
   * and the fit's matrix assembled. Both are kept between executions: the
   * mesh (with its version without repeated triangles, and the smoothed
   * normals with their feature split) until the input's points or cells
   * change, the matrix until they or ScreeningWeight change; so changing
   * only a flow parameter (e.g. FlowTime) and updating again adds neither.
   * The result is the same as a new filter's.
   */
  int GetNumberOfMeshPreparations() const;
  int GetNumberOfFitAssemblies() const { return this->FitAssemblies; }
  ///@}

  /// Name of the optional sharpened-normals cell array.
  static const char* NormalsArrayName() { return "ShockNormals"; }

  ///@{
  /// The sharpened mesh (output port 0, or the given port).
  vtkPolyData* GetOutput();
  vtkPolyData* GetOutput(int port);
  ///@}

protected:
  std::string ParametersText() override;

  vtkPolyDataShockSharpenFilter();
  ~vtkPolyDataShockSharpenFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// vtkPolyData output, also for an unstructured-grid input.
  int RequestDataObject(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  /// Surfaces: vtkPolyData and vtkUnstructuredGrid (a block of another type in a composite input passes through).
  bool FiltersType(vtkDataObject* input) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  void ResetMeasurements() override;

  /**
   * After the agreement: the piece prepared, distributed, sharpened (Sharpen)
   * and written (BuildOutput). A piece whose rings were too few for the
   * normals the fit reads stops before the fit with every other piece, and
   * `moreRings` says how many they agreed to get (more than piece.rings);
   * `tooFew`: some piece needed more than GhostLevels rings.
   */
  int SharpenPiece(vtkPolyData* input, ShockParallel::SurfacePiece& piece, vtkPolyData* output, int& moreRings,
    bool& tooFew);

  /**
   * The rings a piece's normals depend on, with the one the fit's rows add
   * (the triangles around the owned points: ring 1); -1 for the flows that
   * are recomputed (GhostLevels rings, whatever the traces do).
   */
  int RingStencil();

  /**
   * The rings beyond the stencils a piece starts with: about how deep the
   * normals' flow lines read on typical scans, so that a second advection is
   * rare (the measurements are in docs/parallel.md, "Surface Shock Sharpen's
   * rings"). Unit: rings of cells.
   */
  static constexpr int StartingReach = 5;

  /**
   * Run the kernels (a piece of a distributed mesh with `partition`, and its
   * triangles' rings counted from the fit's: see SharpenPiece); false with the kernel's `error`.
   */
  bool Sharpen(const shock::TriangleMesh& mesh, const shock::MeshPartition* partition,
    const unsigned char* triangleRing, double meanEdgeLength, double wholeTriangles, bool localNumbering,
    std::vector<double>& positions, std::vector<double>& normals, shock::SharpeningReport& report,
    shock::MeshFlowFields& fields, std::string& error);

  /// The prepared mesh of `input` in the length unit `unit` (MeshUnit), kept between
  /// executions (the kernels' cache goes with it), renumbered for locality (a
  /// piece's exchanges map the mesh's points back to the piece's through pointOrder).
  const ShockPolyDataInternals::PreparedMesh* Prepare(vtkPolyData* input, double unit, std::string& error);

  /// `piece.work` with the new positions, the field data of the run and the requested arrays.
  void BuildOutput(const ShockParallel::SurfacePiece& piece, const ShockPolyDataInternals::PreparedMesh& prepared,
    std::vector<double>& positions, const std::vector<double>& normals,
    const shock::MeshFlowFields& fields, const shock::SharpeningReport& report, vtkPolyData* output);

  double FeatureAngle = 30.0;
  double CurvatureContrast = 16.0;
  int FitTarget = CENTRAL_PROJECTION;
  int NormalSmoothingPasses = 0;
  vtkTypeBool KeepUnmovedNormals = 1;
  double ScreeningWeight = 1.0;
  double AnchorWeight = 1.0;
  double AnchorAngle = 5.0;
  double DriftRadius = 8.0;
  int Solver = CONJUGATE_GRADIENT;
  int SolverIterations = 25;
  double SolverTolerance = 1e-6;
  vtkTypeBool MergeCoincidentPoints = true;
  vtkTypeBool GenerateSharpenedNormals = false;

  double LastFitSetupSeconds = 0.0;
  double LastFitSolveSeconds = 0.0;
  int LastSolverIterations = 0;
  double LastSolverResidual = 0.0;
  vtkIdType LastFlippedTriangles = 0;
  double LastMaxDisplacement = 0.0;
  vtkIdType LastRepeatedTriangles = 0;
  vtkIdType LastDegenerateTriangles = 0;
  vtkIdType LastFeatureEdges = 0;
  int LastGhostLevels = 0;
  int LastRingAttempts = 0;

private:
  vtkPolyDataShockSharpenFilter(const vtkPolyDataShockSharpenFilter&) = delete;
  void operator=(const vtkPolyDataShockSharpenFilter&) = delete;

  /// The prepared mesh of the last input, and what the kernels kept for it.
  std::unique_ptr<ShockPolyDataInternals::MeshCache> PreparedMeshes;
  std::unique_ptr<shock::SharpeningCache> KernelCache;
  int KernelCachePreparation = -1; ///< the preparation the kernel cache belongs to
  std::unique_ptr<ShockPolyDataInternals::RingAgreement> Rings; ///< the rings the last parallel execution agreed on
  int FitAssemblies = 0;
};

#endif
