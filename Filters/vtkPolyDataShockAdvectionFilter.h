/**
 * @class   vtkPolyDataShockAdvectionFilter
 * @brief   shock-filter advection of signals on triangle meshes
 *
 * Sharpens the selected point or cell array of a vtkPolyData (per-vertex
 * colours, scalar fields, texture-like data) by shock-filter advection over the
 * surface (Prada and Kazhdan 2015, section 4 and Appendix A; see
 * vtkShockAdvectionFilter for the principle and the shared parameters).
 *
 * The gradient of the signal is the per-triangle gradient of its linear
 * interpolant; the potential at a point is the area-weighted average of
 * |grad I|^2 (summed over all components) over the adjacent triangles; the flow
 * u = 1/2 grad P lies in each triangle's plane. Flow lines are traced over the
 * surface: straight inside a triangle and, across an edge, on in the
 * neighbouring triangle unfolded into the current plane. They stop at boundary
 * edges, at non-manifold edges (shared by more than two triangles) and at
 * degenerate (zero-area) triangles.
 *
 * Point data is advected per vertex: from an offset of 0.001 towards the centre
 * of each adjacent triangle, traced, sampled and averaged. Cell data is advected
 * per triangle from its centre; to define the potential and for LINEAR sampling
 * it is first averaged to the points (area-weighted). NEAREST sampling reads the
 * value of the nearest vertex (point data) or of the triangle reached (cell data).
 *
 * Meshes as users have them:
 * - polygons with more than three points and triangle strips are triangulated
 *   internally for point data; the output keeps the input's cells. Cell data on
 *   such cells is refused with an error: triangulate first (vtkTriangleFilter,
 *   or ParaView's Triangulate).
 * - vertex and line cells, points used by no polygon, and polygons with fewer
 *   than three points pass through with their values unchanged.
 * - duplicate points are distinct vertices: a seam of duplicates acts as a
 *   boundary (merge them first, e.g. with vtkCleanPolyData, to trace across it).
 * - several connected components are filtered independently.
 * - non-finite values (NaN, inf) keep their place and do not spread.
 *
 * The array comes from SetInputArrayToProcess (default: the active point
 * scalars), any numeric type and number of components (all components share one
 * flow). The output has the input's points and cells; the array keeps its name,
 * type and attribute role (integer types are rounded and clamped) and every other
 * array passes through. With GenerateFlowArrays, the output also gets the point
 * array "ShockPotential" and the cell array "ShockFlow" (3 components, mesh
 * axes; for a triangulated polygon the area-weighted mean of its triangles;
 * zero on vertex and line cells).
 *
 * Surfaces as ParaView distributes them: an unstructured grid whose cells
 * are vertices, lines, polygons or strips (what RedistributeDataSet and D3
 * make) is read as polydata, and the output is polydata; other cells are
 * refused with a message saying to add Extract Surface.
 *
 * In parallel (one piece per process, as in pvbatch or pvserver with MPI) the
 * piece gets rings of its neighbours' cells (built with the mesh's own
 * connectivity, over the Controller; see vtkShockAdvectionFilter::SetGhostLevels)
 * and is filtered with them, normalised by the data range and the mean edge
 * length over all pieces. It starts with the rings the flow's stencils need
 * and two more; when a flow line of its own points read a triangle whose
 * flow those rings cannot make exact, every piece is filtered again with
 * more rings, up to GhostLevels (GetLastGhostLevels), so that the result
 * equals the serial one up to the order of floating-point sums (the limits
 * are in docs/parallel.md, "Rings sized from the flow lines"); a warning says
 * when GhostLevels rings were too few. The output holds each
 * owned cell once; shared points are marked in vtkGhostType. A data set that
 * every process holds whole (replicated) is filtered once, on process 0.
 *
 * The prepared mesh (triangles, connectivity, geometry) is kept between
 * executions and prepared again only when the input's points or cells change
 * (ShockPolyDataInternals::MeshCache): changing only a parameter (e.g.
 * FlowTime) and updating again skips the preparation
 * (GetNumberOfMeshPreparations counts them).
 *
 * @warning Errors (RequestData returns 0): negative or non-finite FlowTime,
 * missing or non-numeric array, field-data array, cell data on non-triangle
 * polygons or strips, non-finite point coordinates. An empty input, or an input
 * without polygons, passes through with a warning.
 *
 * @sa vtkShockAdvectionFilter vtkImageShockAdvectionFilter
 */
#ifndef vtkPolyDataShockAdvectionFilter_h
#define vtkPolyDataShockAdvectionFilter_h

#include "vtkFiltersShockModule.h" // for export macro
#include "vtkShockAdvectionFilter.h"

#include <memory> // for std::unique_ptr

class vtkDataArray;
class vtkPolyData;
namespace ShockPolyDataInternals
{
class MeshCache;
struct PieceReach;
class RingAgreement;
}

class VTKFILTERSSHOCK_EXPORT vtkPolyDataShockAdvectionFilter : public vtkShockAdvectionFilter
{
public:
  static vtkPolyDataShockAdvectionFilter* New();
  vtkTypeMacro(vtkPolyDataShockAdvectionFilter, vtkShockAdvectionFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The filtered mesh (output port 0, or the given port).
  vtkPolyData* GetOutput();
  vtkPolyData* GetOutput(int port);
  ///@}

  /**
   * How many times the mesh was prepared (triangles, connectivity, geometry).
   * The prepared mesh is kept between executions and prepared again only
   * when the input's points or cells change, so changing only a parameter
   * (e.g. FlowTime) and updating again does not add one.
   */
  int GetNumberOfMeshPreparations() const;

  /**
   * The ghost rings each piece had in the last execution (0 when serial).
   * In parallel a piece starts with few rings and gets more only when a flow
   * line of its own points read a triangle whose flow the rings could not
   * make exact, up to GhostLevels (see SetGhostLevels).
   */
  vtkGetMacro(LastGhostLevels, int);

  /**
   * How many times the last execution filtered its piece: 1 when the
   * starting rings were enough (always in serial), one more each time every
   * piece got more rings. A second execution of the same input (a parameter
   * changed) starts with the rings the first one agreed on.
   */
  vtkGetMacro(LastRingAttempts, int);

protected:
  vtkPolyDataShockAdvectionFilter();
  ~vtkPolyDataShockAdvectionFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// Point data: all points; cell data: the polygons and strips only (as the kernel).
  bool LocalValueRange(vtkInformationVector** inputVector, double range[2]) override;

  /// vtkPolyData output, also for an unstructured-grid input.
  int RequestDataObject(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /**
   * Normalise like the whole surface: data range and mean edge length over
   * all pieces (ParallelValueScale, ParallelLengthScale), lengths in the unit
   * of the whole surface, returned (see ShockPolyDataInternals::MeshUnit).
   * Collective.
   */
  double GlobalScales(vtkMultiProcessController* controller, vtkPolyData* piece, vtkInformationVector** inputVector);

  /// Mean edge length over the cells all pieces own (collective; 0 without a controller);
  /// `wholeTriangles`: how many triangles all pieces own.
  double GlobalMeanEdgeLength(vtkMultiProcessController* controller, vtkPolyData* piece, double& wholeTriangles);

  /// Filter `selected` (as chosen on the input) on `input` (lengths in `unit`, see
  /// ShockPolyDataInternals::MeshUnit) into `output`; false after vtkErrorMacro.
  bool FilterSurface(vtkPolyData* input, vtkDataArray* selected, int association, vtkPolyData* output,
    double unit = 1.0, ShockPolyDataInternals::PieceReach* reach = nullptr);

  /// Zero LastGhostLevels with the other Last* measurements.
  void ResetMeasurements() override;

  /**
   * The rings a piece starts with: the flow's stencils and two more, or the
   * rings the last execution of the same input agreed on, at most GhostLevels;
   * the largest over the processes (collective when `controller` is given).
   */
  int StartingRings(vtkDataObject* input, vtkMultiProcessController* controller);

  /// Surfaces: vtkPolyData and vtkUnstructuredGrid (a block of another type in a composite input passes through).
  bool FiltersType(vtkDataObject* input) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkPolyDataShockAdvectionFilter(const vtkPolyDataShockAdvectionFilter&) = delete;
  void operator=(const vtkPolyDataShockAdvectionFilter&) = delete;

  /// The prepared mesh of the last input, kept between executions.
  std::unique_ptr<ShockPolyDataInternals::MeshCache> PreparedMeshes;
  int LastGhostLevels = 0;
  int LastRingAttempts = 0;
  std::unique_ptr<ShockPolyDataInternals::RingAgreement> Rings; ///< the rings the last parallel execution agreed on
  double ParallelTriangles = 0.0; ///< the whole mesh's triangles in parallel (the trace cap), 0 when serial
};

#endif
