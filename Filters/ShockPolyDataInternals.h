/**
 * @file ShockPolyDataInternals.h
 * @brief Private glue between vtkPolyData and the VTK-free triangle-mesh kernels.
 */
#ifndef ShockPolyDataInternals_h
#define ShockPolyDataInternals_h

#include "MeshShockAdvection.h"
#include "TriangleMesh.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

class vtkDataObject;
class vtkDataSet;
class vtkMultiProcessController;
namespace ShockParallel
{
struct CarriedArrays;
struct SurfacePiece;
}
class vtkInformationVector;
class vtkMultiProcessController;
class vtkDoubleArray;
class vtkPolyData;

namespace ShockPolyDataInternals
{
/**
 * The triangles of a vtkPolyData's polygons and strips as plain arrays.
 * Polygons with more than three points are triangulated (vtkPolygon's ear
 * cutting), strips are split into their triangles; vertices and lines have no
 * triangles. Each triangle remembers the cell it comes from.
 */
struct Triangles
{
  shock::ValueVector points;           ///< 3 coordinates per point (all points; see PreparedMesh::pointOrder)
  shock::IdVector triangles;           ///< 3 point ids per triangle
  std::vector<vtkIdType> sourceCell;   ///< cell id (vtkPolyData numbering) of each triangle
  vtkIdType nonTriangleCells = 0;      ///< polygons with more than 3 points, and strips
  vtkIdType degenerateCells = 0;       ///< polygons with fewer than 3 points (no triangle)

  shock::TriangleMeshView View() const;
};

/**
 * How deep into its ghost rings a piece's filtering read (Surface Shock
 * Advection): given each cell's ring, the deepest ring the traces of the own
 * points (or cells) entered, and the rings the flow's stencils add
 * (shock::MeshStencilRings; -1 when not known). A piece with R rings gave
 * the whole mesh's result when deepest <= R - stencil.
 */
struct PieceReach
{
  const std::vector<unsigned char>* cellRing = nullptr; ///< per cell of the piece with its rings
  int deepest = -1;
  int stencil = -1;
  bool aborted = false;
};

/**
 * The ghost rings the pieces of a surface filter agreed on for an input, kept
 * for the next execution of the same input (a parameter changed), so that it
 * starts with them instead of growing them again. A stale match costs rings,
 * never the result: they only start higher.
 */
class RingAgreement
{
public:
  /**
   * The rings a piece starts with: `stencil` + `spare`, or the rings the last
   * execution of this same input agreed on, at most `most` (`most` when
   * `stencil` < 0: no bound, or without a controller); the largest over the
   * processes (collective: every process of `controller` calls it).
   */
  int Start(vtkMultiProcessController* controller, vtkDataObject* input, int stencil, int spare, int most);
  /// Keep `rings` as agreed for `input`.
  void Keep(vtkDataObject* input, int rings);

private:
  int Rings = 0;
  std::array<std::uintptr_t, 4> Stamp{}; ///< of the input (object, sizes, points; compared only)
};

/**
 * The warning of process 0 when the flow lines of a piece's `samples` (what
 * the filter traces: "points", "normals") ran further than `ghostLevels`
 * rings make exact.
 */
std::string TooFewRingsWarning(int ghostLevels, const char* samples);

/// Whether a cell's point ids lie in [0, numberOfPoints); else the message in `error`.
bool IdsInRange(const char* kind, vtkIdType cellId, vtkIdType size, const vtkIdType* ids,
  vtkIdType numberOfPoints, std::string& error);

/// Fill `out` from `input`. Returns false with `error` set when the input cannot be read.
bool ExtractTriangles(vtkPolyData* input, Triangles& out, std::string& error);

/// The triangles of a vtkPolyData and the TriangleMesh built from them.
struct PreparedMesh
{
  /// The triangles' ids are moved into `mesh` (triangles.triangles is empty: read mesh.Corners).
  Triangles triangles;
  shock::TriangleMesh mesh;
  /// With merging: for each point, the first point with the same coordinates; else empty.
  std::vector<std::int64_t> representative;
  /**
   * With a locality order: mesh point i is input point pointOrder[i] (and
   * triangles.sourceCell follows the triangles' new order); else empty, and the
   * mesh's points are the input's. `representative` keeps the input's numbering.
   */
  shock::IdVector pointOrder;
  double seconds = 0.0; ///< time spent preparing

  /// Per-point values (C per point) in the input's numbering, in the mesh's (0 threads: all).
  /// Both throw std::invalid_argument unless `values` holds C values per point (a caller's bug).
  std::vector<double> ToMeshPoints(std::vector<double> values, int components, int threads) const;
  /// Per-point values (C per point) in the mesh's numbering, in the input's.
  std::vector<double> FromMeshPoints(std::vector<double> values, int components, int threads) const;
};

/**
 * Extract the triangles, optionally merge exactly coincident points (the mesh
 * then uses one copy of each; the others have no triangles), and build the mesh
 * of the points divided by `unit` (see MeshUnit; 0: the mesh's size is not finite).
 * With `localityOrder`, the mesh's points and triangles are renumbered so that
 * neighbours are near in memory (shock::LocalityNumbering; see pointOrder).
 * Returns false with a complete one-sentence `error` when the input is unusable.
 */
bool PrepareMesh(vtkPolyData* input, bool mergeCoincidentPoints, int threads, PreparedMesh& out,
  std::string& error, double unit = 1.0, bool localityOrder = false);

/**
 * The length unit a surface filter works in: 1 for a mesh whose bounding box's
 * largest side lies in [2^-64, 2^64] (filtered as it is); else the power of two
 * nearest above that side. The filter divides the points by it (exactly) and
 * multiplies the lengths it outputs by it: the algorithm is scale-covariant,
 * and lengths to the fourth power of meshes beyond about 1e+-75 would leave
 * the double range (NaN, no change, false flipped triangles). 0 when the side
 * is not finite. With a controller all processes agree (collective).
 * `threads`: for the bounds of large float or double point arrays (0 = all cores).
 */
double MeshUnit(vtkMultiProcessController* controller, vtkPolyData* piece, int threads = 0);

/**
 * The prepared mesh of a filter's input, kept between executions: a filter
 * executed again with only its parameters changed (ParaView's Apply after a
 * new FlowTime) does not prepare the mesh again. It is prepared again when
 * anything PrepareMesh reads changes: the points (object, modification time,
 * data type, count), the vertex, line, polygon and strip cell arrays (object,
 * modification time, count: vertices and lines number the polygons' cells), or
 * the merging of coincident points. The thread count is no part of the key:
 * the prepared mesh does not depend on it.
 */
class MeshCache
{
public:
  /**
   * The prepared mesh of `input`: the kept one when nothing it depends on has
   * changed, else prepared anew with PrepareMesh. nullptr with a complete
   * one-sentence `error` when the input is unusable (nothing is kept then).
   * `seconds` receives the time this call took; `unit` as for PrepareMesh.
   */
  const PreparedMesh* Get(vtkPolyData* input, bool mergeCoincidentPoints, int threads,
    std::string& error, double* seconds = nullptr, double unit = 1.0, bool localityOrder = false);
  /// Meshes prepared so far (a kept one does not count): how tests see the cache work.
  int GetNumberOfPreparations() const { return this->Preparations; }
  /// Forget the kept mesh and free its memory.
  void Clear();

private:
  std::vector<unsigned long long> Key; ///< empty: nothing kept
  PreparedMesh Mesh;
  int Preparations = 0;
};

/**
 * A per-cell array of 3-vectors from per-triangle ones: the area-weighted mean
 * of each cell's triangles (zero for cells without triangles).
 */
vtkSmartPointer<vtkDoubleArray> TrianglesToCells(const char* name, vtkIdType numberOfCells,
  const shock::TriangleMesh& mesh, const Triangles& triangles, const std::vector<double>& vectors);

/**
 * The input of a surface filter as vtkPolyData: a vtkPolyData as it is, or a
 * vtkUnstructuredGrid whose cells are all vertices, lines, polygons or strips
 * (what ParaView's RedistributeDataSet and D3 make of a surface) converted
 * with the same points, point data and cell data. Anything else: nullptr and
 * a one-sentence `error` that says to add Extract Surface.
 */
vtkSmartPointer<vtkPolyData> AsSurface(vtkDataSet* input, std::string& error);

/**
 * The first steps of a surface filter's RequestData (both surface filters):
 * the input as a surface (AsSurface), the filter's own checks on it
 * (`check` returns an error message, or "" when the surface is usable; it is
 * not called when ValidateSurface refuses the surface, and called with
 * nullptr when there is no surface: then it returns the filter's own reason
 * not to start, if any, which wins over AsSurface's), then,
 * with a `controller`, the agreement of every process (ShockParallel::Agree
 * on the error, on `parameters` and `*selection`, the filtered array as
 * `check` chose it) and the piece's ghost layers, carrying the arrays
 * `carried` names (read after `check`, which may fill it in)
 * (ShockParallel::PrepareSurfacePiece, collective: call it on every
 * process). Returns false with a one-sentence `error` to report; on success,
 * `piece.skip` says the output stays empty (replicated data: process 0
 * filters it) and `piece.work` is what to filter.
 */
bool BeginSurface(vtkInformationVector** inputVector, vtkMultiProcessController* controller,
  int ghostLevels, const std::function<std::string(vtkPolyData* surface)>& check,
  const std::string& parameters, const std::string* selection, const ShockParallel::CarriedArrays& carried,
  vtkSmartPointer<vtkPolyData>& input, ShockParallel::SurfacePiece& piece, std::string& error);

/**
 * The checks every surface filter makes before anything reads the mesh: the
 * point ids of every vertex, line, polygon and strip cell lie in [0, number of
 * points), and every coordinate is finite. "" when they hold, else the
 * one-sentence message.
 */
std::string ValidateSurface(vtkPolyData* surface);

/**
 * RequestDataObject of the surface filters: for a data-set input, make the
 * output a vtkPolyData and return true; false for a composite input (the
 * superclass then copies its structure and the blocks come one by one).
 */
bool EnsurePolyDataOutput(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

/// vtkPolyData or vtkUnstructuredGrid: the types the surface filters filter.
bool IsSurfaceType(vtkDataObject* data);

/// Add "ShockPotential" (points) and "ShockFlow" (`numberOfCells` cells) to `output`.
void AttachFlowArrays(vtkPolyData* output, vtkIdType numberOfCells, const shock::TriangleMesh& mesh,
  const Triangles& triangles, const shock::MeshFlowFields& fields);
}

#endif
