/**
 * @file MeshSharpening.h
 * @brief Geometry sharpening: shock-filter advection of face normals, then a screened Poisson fit.
 *
 * Prada and Kazhdan (2015), section 4.1: the face normals of a triangle mesh are
 * treated as a 3-channel cell signal and sharpened by shock-filter advection
 * (MeshShockAdvection: per-point normals by area-weighted averaging define the
 * potential P = sum_j |grad N_j|^2, the sum of the squared principal curvatures;
 * faces are advected from their centres); the advected normals are renormalised;
 * then the positions are fitted to them (ScreenedPoissonFit). Creases and
 * corners sharpen where the total curvature peaks; flat and smooth parts stay.
 *
 * Normals are unit vectors, so their intensity scale is fixed at 2 (the range
 * of a component) rather than measured: a time t means the same on a gently
 * curved and on a strongly curved mesh. Lengths are in mean edge lengths.
 *
 * Optional pre-mollification for noisy meshes (the paper's Figure 11, after Jones
 * et al. 2003): NormalSmoothingPasses of Laplacian smoothing of the face normals
 * with the positions fixed: each normal becomes the renormalised area-weighted
 * mean of itself and its edge neighbours.
 *
 * What is left alone (SharpFeatures): triangles that repeat another triangle's
 * vertex set and degenerate triangles are removed first (counted in the report),
 * so the result is that of the mesh without them. Creases already sharper than
 * the feature angle keep their normals: the points on feature edges are split
 * for the advection, so normals are neither averaged nor traced across them
 * (featureAngle 180, no split, reproduces the paper).
 *
 * With Sampling::Linear, the advected normal is the barycentric interpolation of
 * the per-point normals, which smooths the normals even at t = 0 (the paper's
 * Figure 7); Sampling::Nearest copies the normal of the triangle reached, so
 * t = 0 with the exact solver returns the input positions.
 *
 * Not the paper's (SharpeningParameters::keepUnmovedNormals, off gives the
 * paper's sampling): a triangle on which the flow is zero is not moved by the
 * advection (its trace stays at its centre), so it keeps its own normal
 * instead of the interpolated average, which would bend a smooth shape that
 * the flow leaves alone (with the flow fixed, FlowMode Fixed, the default; the
 * other modes recompute the flow and sample every triangle). At t = 0 no
 * triangle moves: every one keeps its own normal and the input comes back.
 */
#ifndef MeshSharpening_h
#define MeshSharpening_h

#include "MeshShockAdvection.h"
#include "ScreenedPoissonFit.h"
#include "SharpFeatures.h"

namespace shock
{

/// Parameters of SharpenMeshGeometry.
struct SharpeningParameters
{
  AdvectionParameters advection; ///< advection of the normals (time, smoothing, sampling, ...)
  int normalSmoothingPasses = 0; ///< Laplacian smoothing passes of the face normals (>= 0)
  /// Edges whose (smoothed) face normals differ by more than this many degrees are
  /// already sharp and are kept (SharpFeatures); [0, 180], 180 = the paper (none).
  double featureAngle = 30.0;
  FitParameters fit;             ///< the screened Poisson fit
  /// Length unit of the advection (0: the mesh's own mean edge length). A piece of a
  /// distributed mesh (fit.partition) passes the whole mesh's mean edge length.
  double lengthScale = 0.0;
  /**
   * Not the paper's: the advection's potential keeps only what exceeds this
   * many times its minimum over `contrastRings` rings (MeshFlow.h,
   * CurvatureContrast), so that smooth shapes, however coarsely tessellated,
   * are not sharpened; 0 is the paper's potential (docs/sharpening.md,
   * "Telling a smooth shape from a blurred crease").
   */
  double curvatureContrast = 16.0;
  int contrastRings = 6; ///< rings of the contrast's minimum (>= 1)
  /// Not the paper's: a triangle the flow does not move keeps its own normal (file comment).
  bool keepUnmovedNormals = true;
  /**
   * A piece of a distributed mesh: each triangle's ghost ring (0: the
   * triangles whose sharpened normals must be the whole mesh's), or null.
   * The run then reports in SharpeningReport::advection.deepestRing the
   * deepest ring the traces of the ring-0 triangles read (see
   * SharpeningStencilRings).
   */
  const unsigned char* triangleRing = nullptr;
  /// The triangles of the whole mesh a piece is cut from, for the traces' step cap (MeshSignal::wholeTriangles; 0: this mesh's).
  std::int64_t wholeTriangles = 0;
};

/// What a sharpening run did.
struct SharpeningReport
{
  AdvectionReport advection; ///< flow and advection of the normals
  FitReport fit;             ///< solver iterations, residual, set-up and solve times
  /// Face normals, their optional smoothing, the search for repeated triangles and the feature split.
  double normalsSeconds = 0.0;
  /// Non-degenerate triangles whose normal points against the input normal after the fit.
  std::int64_t flippedTriangles = 0;
  /// Largest point displacement divided by the diagonal of the input's bounding box.
  double maxDisplacement = 0.0;
  std::int64_t repeatedTriangles = 0;   ///< triangles repeating another's vertex set: removed
  std::int64_t degenerateTriangles = 0; ///< degenerate triangles (see TriangleMesh): removed
  std::int64_t featureEdges = 0;        ///< edges sharper than the feature angle: kept
  /// Taken from the SharpeningCache given: the mesh without repeated and degenerate
  /// triangles, and the smoothed normals with their feature split.
  bool reusedMesh = false;
  bool reusedFeatures = false;
};

/**
 * What SharpenMeshGeometry can keep between runs on the same mesh, so that a
 * run with other advection parameters (another flow time) only advects and
 * solves: the mesh without repeated and degenerate triangles; the smoothed
 * face normals and the mesh split at feature edges, for the smoothing passes
 * and feature angle they were made with; the fit's matrix and mass term
 * (FitSystem), for its screening weight. A run with other values of those
 * rebuilds the part concerned. The caller clears the cache when the mesh
 * changes; a piece of a distributed mesh (fit.partition) does not use it.
 */
struct SharpeningCache
{
  bool cleaned = false; ///< the fields below `removed` hold the mesh's clean version
  bool removed = false; ///< triangles were removed: `reduced` is the clean mesh
  TriangleMesh reduced;
  std::vector<std::int64_t> source; ///< input triangle -> reduced triangle (-1: degenerate)
  std::int64_t repeatedTriangles = 0;
  std::int64_t degenerateTriangles = 0;

  int smoothingPasses = -1; ///< of `normals` and `split` (-1: none kept)
  double featureAngle = -1.0;
  std::vector<double> normals; ///< smoothed face normals of the clean mesh (empty without smoothing: its own)
  FeatureSplitMesh split;

  FitSystem fit;

  void Clear() { *this = SharpeningCache(); }
};

/**
 * Sharpen a mesh's geometry.
 *
 * @param mesh       built TriangleMesh (the input positions and topology).
 * @param parameters see SharpeningParameters.
 * @param positions  output: 3 coordinates per point (points without triangles keep theirs).
 * @param normals    optional output: the sharpened unit normal per triangle (3 each;
 *                   zero for degenerate triangles; a repeated triangle gets that of
 *                   its first occurrence).
 * @param report     optional: timings, solver figures, flips, displacement.
 * @param fields     optional: potential and flow of the normals' advection (the
 *                   potential of a point split at feature edges is the mean over
 *                   its copies, weighted by their triangles; repeated and
 *                   degenerate triangles get zero flow).
 * @param progress   optional: progress/abort callback (advection part).
 * @param cache      optional: what earlier runs on this same mesh kept (see
 *                   SharpeningCache); the result is the same with or without it.
 * @return an error for invalid parameters or a failed solve; when aborted
 *         (report->advection.aborted), positions hold the input positions.
 */
/**
 * How many ghost rings around a triangle its sharpened normal depends on: one
 * per normal smoothing pass (each reads a triangle's edge neighbours), then
 * the advection's stencil of a triangle signal with the curvature contrast
 * (MeshStencilRings). The feature split reads no further: whether a point is
 * split, and how, depends on the normals of its own triangles, which the
 * advection's first step (the normals' average to the points) reads already.
 * On a piece with R rings, the sharpened normal of every ring-0 triangle is
 * the whole mesh's when SharpeningReport::advection.deepestRing <= R - this.
 * -1 when the flow is recomputed from advected values (no such bound).
 */
int SharpeningStencilRings(const SharpeningParameters& parameters);

Status SharpenMeshGeometry(const TriangleMesh& mesh, const SharpeningParameters& parameters,
  double* positions, double* normals = nullptr, SharpeningReport* report = nullptr,
  MeshFlowFields* fields = nullptr, const ProgressFunction& progress = ProgressFunction(),
  SharpeningCache* cache = nullptr);

} // namespace shock

#endif
