#include "vtkPolyDataShockSharpenFilter.h"

#include "MeshSharpening.h"
#include "vtkCellData.h"
#include "vtkIdList.h"
#include "vtkPointData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "ShockFilterInternals.h"
#include "ShockParallel.h"
#include "ShockSharpenDistribution.h"
#include "ShockPolyDataInternals.h"
#include "vtkSmartPointer.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <chrono>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

vtkStandardNewMacro(vtkPolyDataShockSharpenFilter);

namespace
{
template <typename T>
vtkSmartPointer<vtkDataArray> SingleValue(const char* name, T value)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->InsertNextValue(static_cast<double>(value));
  return array;
}

/// Unit normal of every cell of `output` with its new points: the normalised sum of its triangles' area vectors.
std::vector<double> CellNormals(vtkPolyData* output, const ShockPolyDataInternals::Triangles& triangles,
  const shock::TriangleMesh& mesh, const std::vector<double>& positions)
{
  std::vector<double> normals(static_cast<size_t>(3 * output->GetNumberOfCells()), 0.0);
  for (size_t f = 0; f < triangles.sourceCell.size(); ++f)
  {
    const std::int64_t* t = mesh.Corners(static_cast<std::int64_t>(f));
    const double* a = &positions[static_cast<size_t>(3 * t[0])];
    const double* b = &positions[static_cast<size_t>(3 * t[1])];
    const double* c = &positions[static_cast<size_t>(3 * t[2])];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    double* n = &normals[static_cast<size_t>(3 * triangles.sourceCell[f])];
    n[0] += u[1] * v[2] - u[2] * v[1];
    n[1] += u[2] * v[0] - u[0] * v[2];
    n[2] += u[0] * v[1] - u[1] * v[0];
  }
  for (size_t c = 0; c < normals.size(); c += 3)
  {
    const double length = std::sqrt(normals[c] * normals[c] + normals[c + 1] * normals[c + 1] +
      normals[c + 2] * normals[c + 2]);
    for (int k = 0; k < 3 && length > 0.0; ++k)
    {
      normals[c + static_cast<size_t>(k)] /= length;
    }
  }
  return normals;
}

/// Give `output` new points of the input's type; coincident copies take their representative's position.
void SetNewPoints(vtkPolyData* output, vtkIdType count, int pointType,
  const std::vector<std::int64_t>& representative, std::vector<double>& positions, int threads)
{
  // A representative is the first of its copies (never a copy itself): the copies read
  // positions nobody writes, so the points are independent.
  const auto n = static_cast<std::int64_t>(representative.size());
  shock::ParallelFor(n, shock::ThreadsForWork(threads, n), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t p = begin; p < end; ++p)
    {
      const size_t r = static_cast<size_t>(representative[static_cast<size_t>(p)]);
      if (r != static_cast<size_t>(p))
      {
        std::copy(&positions[3 * r], &positions[3 * r] + 3, &positions[3 * static_cast<size_t>(p)]);
      }
    }
  });
  // The input's point type, the values converted as vtkPoints::SetPoint does (a cast).
  vtkNew<vtkPoints> points;
  if (pointType == VTK_FLOAT || pointType == VTK_DOUBLE)
  {
    vtkSmartPointer<vtkDataArray> data = ShockFilterInternals::FromDoubles(
      pointType, 3, count, positions.data(), shock::ThreadsForWork(threads, 3 * count));
    data->SetName("Points"); // as vtkPoints names its own arrays
    points->SetData(data);
  }
  else
  {
    points->SetDataType(pointType);
    points->SetNumberOfPoints(count);
    for (vtkIdType p = 0; p < count; ++p)
    {
      points->SetPoint(p, &positions[static_cast<size_t>(3 * p)]);
    }
  }
  output->SetPoints(points);
}

/// The warnings, field data and log line of a completed run.
void ReportRun(vtkPolyDataShockSharpenFilter* self, const shock::SharpeningReport& report,
  vtkPolyData* input, vtkPolyData* output)
{
  if (report.repeatedTriangles > 0)
  {
    vtkWarningWithObjectMacro(self, << report.repeatedTriangles
                    << " triangles repeat the points of another triangle and were ignored (a mesh "
                       "appended to itself?): the result is that of the mesh without them.");
  }
  if (report.degenerateTriangles > 0)
  {
    // Removed, they no longer change the result (they used to stop traces): no warning.
    vtkLogF(1, "vtkPolyDataShockSharpenFilter: %lld degenerate (zero-area) triangles ignored",
      static_cast<long long>(report.degenerateTriangles));
  }

  vtkNew<vtkFieldData> field;
  field->ShallowCopy(input->GetFieldData());
  field->AddArray(SingleValue("ShockSolverIterations", report.fit.iterations));
  field->AddArray(SingleValue("ShockSolverResidual", report.fit.residual));
  field->AddArray(SingleValue("ShockFlippedTriangles", report.flippedTriangles));
  field->AddArray(SingleValue("ShockMaxDisplacement", report.maxDisplacement));
  output->SetFieldData(field);
  vtkLogF(1,
    "vtkPolyDataShockSharpenFilter: %d solver iterations, relative residual %.3g%s, %lld flipped "
    "triangles, max displacement %.3g of the bounding-box diagonal, %lld feature edges",
    report.fit.iterations, report.fit.residual,
    // The paper's fixed 25 iterations do not aim at a tolerance: only flag the modes that do.
    (self->GetSolver() == vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT || report.fit.converged) ? "" : " (above the tolerance)",
    static_cast<long long>(report.flippedTriangles), report.maxDisplacement,
    static_cast<long long>(report.featureEdges));
  if (report.fit.invalidTargets > 0)
  {
    vtkWarningWithObjectMacro(self, << report.fit.invalidTargets
                    << " triangles had no valid sharpened normal and kept their own.");
  }
}

/**
 * Replace the active point and cell normals of `output` (if any) by those of its
 * new geometry, in a new array of the same type and name: cell normals are the
 * cells' unit normals, point normals the normalised sum of the unit normals of
 * the cells around each point (points without cells keep theirs).
 */
void RecomputeActiveNormals(vtkPolyData* output, const ShockPolyDataInternals::Triangles& triangles,
  const shock::TriangleMesh& mesh, const std::vector<double>& positions)
{
  vtkDataArray* pointNormals = output->GetPointData()->GetNormals();
  vtkDataArray* cellNormals = output->GetCellData()->GetNormals();
  if (!pointNormals && !cellNormals)
  {
    return;
  }
  const std::vector<double> cells = CellNormals(output, triangles, mesh, positions);
  if (cellNormals)
  {
    vtkSmartPointer<vtkDataArray> fresh = vtk::TakeSmartPointer(cellNormals->NewInstance());
    fresh->DeepCopy(cellNormals);
    for (vtkIdType c = 0; c < output->GetNumberOfCells(); ++c)
    {
      if (cells[static_cast<size_t>(3 * c)] != 0.0 || cells[static_cast<size_t>(3 * c + 1)] != 0.0 ||
        cells[static_cast<size_t>(3 * c + 2)] != 0.0)
      {
        fresh->SetTuple(c, &cells[static_cast<size_t>(3 * c)]);
      }
    }
    output->GetCellData()->SetNormals(fresh);
  }
  if (pointNormals)
  {
    std::vector<double> sums(static_cast<size_t>(3 * output->GetNumberOfPoints()), 0.0);
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < output->GetNumberOfCells(); ++c)
    {
      output->GetCellPoints(c, ids);
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        for (int k = 0; k < 3; ++k)
        {
          sums[static_cast<size_t>(3 * ids->GetId(i) + k)] += cells[static_cast<size_t>(3 * c + k)];
        }
      }
    }
    vtkSmartPointer<vtkDataArray> fresh = vtk::TakeSmartPointer(pointNormals->NewInstance());
    fresh->DeepCopy(pointNormals);
    for (vtkIdType p = 0; p < output->GetNumberOfPoints(); ++p)
    {
      double* n = &sums[static_cast<size_t>(3 * p)];
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (length > 0.0)
      {
        const double unit[3] = { n[0] / length, n[1] / length, n[2] / length };
        fresh->SetTuple(p, unit);
      }
    }
    output->GetPointData()->SetNormals(fresh);
  }
}
}

vtkPolyDataShockSharpenFilter::vtkPolyDataShockSharpenFilter()
  : PreparedMeshes(new ShockPolyDataInternals::MeshCache)
  , KernelCache(new shock::SharpeningCache)
  , Rings(new ShockPolyDataInternals::RingAgreement)
{
  // Roundings over 4 to 6 rows of triangles are sharp at 256; at 64 (the advection
  // filters' default) most blurred parts of docs/sharpening.md hardly changed.
  this->FlowTime = 256.0;
}

vtkPolyDataShockSharpenFilter::~vtkPolyDataShockSharpenFilter() = default;

int vtkPolyDataShockSharpenFilter::GetNumberOfMeshPreparations() const
{
  return this->PreparedMeshes->GetNumberOfPreparations();
}

const ShockPolyDataInternals::PreparedMesh* vtkPolyDataShockSharpenFilter::Prepare(
  vtkPolyData* input, double unit, std::string& error)
{
  const ShockPolyDataInternals::PreparedMesh* prepared = this->PreparedMeshes->Get(input,
    this->MergeCoincidentPoints, this->NumberOfThreads, error, &this->LastSetupSeconds, unit, true);
  const int preparation = this->PreparedMeshes->GetNumberOfPreparations();
  if (!prepared || preparation != this->KernelCachePreparation)
  {
    this->KernelCache->Clear(); // what the kernels kept belongs to the previous mesh
    this->KernelCachePreparation = prepared ? preparation : -1;
  }
  return prepared;
}

vtkPolyData* vtkPolyDataShockSharpenFilter::GetOutput()
{
  return this->GetOutput(0);
}

vtkPolyData* vtkPolyDataShockSharpenFilter::GetOutput(int port)
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(port));
}

int vtkPolyDataShockSharpenFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

int vtkPolyDataShockSharpenFilter::RequestDataObject(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return ShockPolyDataInternals::EnsurePolyDataOutput(inputVector, outputVector)
    ? 1
    : this->Superclass::RequestDataObject(request, inputVector, outputVector);
}


bool vtkPolyDataShockSharpenFilter::FiltersType(vtkDataObject* input)
{
  return ShockPolyDataInternals::IsSurfaceType(input);
}

int vtkPolyDataShockSharpenFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (this->PassForeignBlock(inputVector, outputVector))
  {
    return 1;
  }
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  bool unknown = false;
  vtkMultiProcessController* controller = this->PieceController(outputVector, unknown);
  std::string notStarted = "the filter has no output";
  const bool started = output && this->BeginExecution(&notStarted);
  if (!started && !controller)
  {
    return 0; // in parallel the other processes learn of it in the agreement below
  }
  // The surface (an unstructured grid of polygons is read as polydata); in
  // parallel, all agree, replicated data is recognised, pieces get ghost layers
  // (collective; at least one: the fit's rows need the one-rings of their points).
  // The ghost rings carry the positions, and the active normals (recomputed for the output) only.
  ShockParallel::CarriedArrays carried{ false, {}, {} };
  auto wholeOrPieces = [&unknown, &carried, &notStarted, started](vtkPolyData* surface) -> std::string {
    if (!started || !surface)
    {
      return started ? "" : notStarted;
    }
    for (auto* normals : { surface->GetPointData()->GetNormals(), surface->GetCellData()->GetNormals() })
    {
      if (normals && normals->GetName())
      {
        (normals == surface->GetPointData()->GetNormals() ? carried.point : carried.cell).push_back(normals->GetName());
      }
    }
    return unknown && surface->GetNumberOfPoints() > 0
      ? "This is one of several pieces of the mesh, and no MPI controller with as many "
        "processes is available to fit them together; give the whole mesh to one process."
      : "";
  };
  // The pieces start with the rings the stencils of the normals the fit reads
  // need and StartingReach more, and get more only when their flow lines run
  // deeper (the agreement before the fit), up to GhostLevels.
  const int most = std::max(1, this->GhostLevels);
  vtkDataObject* given = vtkDataObject::GetData(inputVector[0]);
  int rings = this->Rings->Start(controller, given, started ? this->RingStencil() : -1, StartingReach, most);
  for (;;)
  {
    carried = ShockParallel::CarriedArrays{ false, {}, {} };
    vtkSmartPointer<vtkPolyData> input;
    ShockParallel::SurfacePiece piece;
    std::string error;
    vtkLogStartScope(TRACE, "shock: input, agreement and ghost rings");
    const bool begun = ShockPolyDataInternals::BeginSurface(
      inputVector, controller, rings, wholeOrPieces, this->ParametersText(), nullptr, carried, input, piece, error);
    vtkLogEndScope("shock: input, agreement and ghost rings");
    if (!begun)
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    if (piece.skip)
    {
      output->Initialize();
      return 1; // replicated data: process 0 sharpens it once
    }
    this->LastGhostLevels = piece.controller ? piece.rings : 0;
    ++this->LastRingAttempts;
    int more = 0;
    bool tooFew = false;
    const int done = this->SharpenPiece(input, piece, output, more, tooFew);
    if (done && piece.controller && more > piece.rings)
    {
      vtkLogF(TRACE, "shock: a flow line of the normals read too deep into %d ghost rings: again with %d", rings, more);
      rings = more;
      continue;
    }
    if (done && piece.controller)
    {
      // Kept for the next execution of the same input (a parameter changed).
      this->Rings->Keep(given, rings);
      if (tooFew && this->GhostLevels > 0 && piece.controller->GetLocalProcessId() == 0)
      {
        vtkWarningMacro(<< ShockPolyDataInternals::TooFewRingsWarning(this->GhostLevels, "normals"));
      }
    }
    return done;
  }
}

int vtkPolyDataShockSharpenFilter::RingStencil()
{
  shock::SharpeningParameters parameters;
  parameters.advection = ShockFilterInternals::MakeParameters(this);
  parameters.normalSmoothingPasses = this->NormalSmoothingPasses;
  parameters.curvatureContrast = this->CurvatureContrast;
  const int normals = shock::SharpeningStencilRings(parameters);
  return normals < 0 ? -1 : normals + 1;
}

/**
 * The piece (or the whole mesh) prepared, distributed, sharpened and written:
 * every step that can fail agrees across the processes first.
 */
int vtkPolyDataShockSharpenFilter::SharpenPiece(
  vtkPolyData* input, ShockParallel::SurfacePiece& piece, vtkPolyData* output, int& moreRings, bool& tooFew)
{
  std::string error;
  moreRings = piece.rings; // unless the pieces agree on more before the fit
  tooFew = false;
  if (piece.controller && this->Solver == EXACT)
  {
    vtkErrorMacro("The EXACT solver factorises the whole system on one process, but the mesh is "
                  "split over processes: use the CONJUGATE_GRADIENT solvers (solved across them).");
    return 0;
  }
  // The triangle mesh of the piece (with its ghost cells), in the whole mesh's
  // length unit, kept between executions.
  vtkLogStartScope(TRACE, "shock: unit and mesh");
  const double unit = ShockPolyDataInternals::MeshUnit(piece.controller, piece.work, this->NumberOfThreads);
  const bool empty = piece.work->GetNumberOfPoints() == 0;
  const ShockPolyDataInternals::PreparedMesh* kept =
    empty ? nullptr : this->Prepare(piece.work, unit, error);
  const bool ok = empty || kept;
  vtkLogEndScope("shock: unit and mesh");
  if (piece.controller ? ShockParallel::AnyFailed(piece.controller, !ok, error) : !ok)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const ShockPolyDataInternals::PreparedMesh none;
  const ShockPolyDataInternals::PreparedMesh& prepared = kept ? *kept : none;
  if (!piece.controller && (empty || prepared.mesh.NumberOfTriangles() == 0))
  {
    output->ShallowCopy(input);
    vtkWarningMacro(<< (empty ? "The input mesh is empty" : "The mesh has no polygons")
                    << ": nothing to sharpen.");
    return 1;
  }
  // A piece: what it owns, what it exchanges, the whole mesh's length unit.
  ShockParallel::Distribution distribution;
  if (piece.controller)
  {
    vtkLogScopeF(TRACE, "shock: ownership and exchange set-up");
    ShockParallel::Distribute(piece.controller, piece.work, prepared, distribution);
  }
  // The piece's copy with its rings has been read into the mesh: its points
  // and cells go before the largest phase (not when RecomputeActiveNormals
  // will read its cells).
  if (piece.controller && !piece.work->GetPointData()->GetNormals() && !piece.work->GetCellData()->GetNormals())
  {
    ShockParallel::ReleaseGeometry(piece);
  }
  // The fit's rows read the triangles around the owned points (ring 1 at
  // most), so the rings count from those: a ring-1 triangle is one whose
  // sharpened normal must be the whole mesh's, as the piece's own ones.
  const int stencil = piece.controller ? this->RingStencil() : -1;
  std::vector<unsigned char> triangleRing;
  if (stencil >= 0)
  {
    triangleRing.resize(prepared.triangles.sourceCell.size());
    for (size_t f = 0; f < triangleRing.size(); ++f)
    {
      const vtkIdType cell = prepared.triangles.sourceCell[f];
      const unsigned char ring = cell < static_cast<vtkIdType>(piece.cellRing.size())
        ? piece.cellRing[static_cast<size_t>(cell)]
        : std::numeric_limits<unsigned char>::max();
      triangleRing[f] = ring <= 1 ? 0 : static_cast<unsigned char>(ring - 1);
    }
    // After the advection, before the fit: all stop when one stopped, or
    // when some piece's flow lines ran deeper than its rings make exact.
    const int most = std::max(1, this->GhostLevels);
    const int rings = piece.rings;
    vtkMultiProcessController* controller = piece.controller;
    distribution.partition.anyStopped = [controller, stencil, rings, most, &moreRings, &tooFew](
                                          bool stopped, int deepest) {
      vtkLogF(TRACE, "shock: the normals' flow lines read ring %d of %d (the stencils: %d rings)", deepest, rings,
        stencil);
      bool anyStopped = false;
      moreRings = ShockParallel::MoreLayers(
        controller, stopped, deepest >= 0 ? deepest + stencil : -1, rings, most, tooFew, &anyStopped);
      return anyStopped || moreRings > rings;
    };
  }
  // Normals, potential, flow and advection on the piece; the fit across pieces.
  std::vector<double> positions(prepared.triangles.points.size());
  std::vector<double> normals( // only asked for when they become an array
    this->GenerateSharpenedNormals ? static_cast<size_t>(3 * prepared.mesh.NumberOfTriangles()) : 0);
  shock::SharpeningReport report;
  shock::MeshFlowFields fields;
  vtkLogStartScope(TRACE, "shock: sharpen the piece");
  bool sharpened = this->Sharpen(prepared.mesh, piece.controller ? &distribution.partition : nullptr,
    triangleRing.empty() ? nullptr : triangleRing.data(), distribution.meanEdgeLength, distribution.wholeTriangles,
    !prepared.pointOrder.empty(), positions, normals, report, fields, error);
  vtkLogEndScope("shock: sharpen the piece");
  if (piece.controller ? ShockParallel::AnyFailed(piece.controller, !sharpened, error) : !sharpened)
  {
    vtkErrorMacro("Geometry sharpening failed: " << error);
    return 0;
  }
  if (piece.controller && moreRings > piece.rings)
  {
    return 1; // every process stopped before the fit: again with more rings
  }
  if (report.advection.aborted || empty)
  {
    output->ShallowCopy(input);
    return 1; // aborted (the output holds the input), or an empty piece
  }
  for (double& x : positions)
  {
    x *= unit; // back from the mesh unit (a power of two: exact)
  }
  // The output: the piece's own cells with the new positions and the requested arrays.
  vtkLogScopeF(TRACE, "shock: output");
  vtkNew<vtkPolyData> result;
  this->BuildOutput(piece, prepared, positions, normals, fields, report, result);
  output->ShallowCopy(piece.controller ? ShockParallel::OwnedPiece(result, piece).GetPointer()
                                       : result.GetPointer());
  return 1;
}

bool vtkPolyDataShockSharpenFilter::Sharpen(const shock::TriangleMesh& mesh,
  const shock::MeshPartition* partition, const unsigned char* triangleRing, double meanEdgeLength,
  double wholeTriangles, bool localNumbering, std::vector<double>& positions, std::vector<double>& normals,
  shock::SharpeningReport& report, shock::MeshFlowFields& fields, std::string& error)
{
  shock::SharpeningParameters parameters;
  parameters.advection = ShockFilterInternals::MakeParameters(this);
  parameters.normalSmoothingPasses = this->NormalSmoothingPasses;
  parameters.featureAngle = this->FeatureAngle;
  parameters.curvatureContrast = this->CurvatureContrast;
  parameters.fit.target = static_cast<shock::FitTarget>(this->FitTarget);
  parameters.lengthScale = meanEdgeLength;
  parameters.triangleRing = triangleRing;
  parameters.wholeTriangles = static_cast<std::int64_t>(wholeTriangles);
  parameters.fit.screeningWeight = this->ScreeningWeight;
  parameters.fit.anchorWeight = this->AnchorWeight;
  parameters.fit.anchorAngle = this->AnchorAngle;
  parameters.keepUnmovedNormals = this->KeepUnmovedNormals != 0;
  parameters.fit.driftRadius = this->DriftRadius;
  parameters.fit.solver = static_cast<shock::FitSolver>(this->Solver);
  parameters.fit.iterations = this->SolverIterations;
  parameters.fit.maxIterations = this->SolverIterations;
  parameters.fit.tolerance = this->SolverTolerance;
  parameters.fit.partition = partition;
  parameters.fit.rowsInMeshOrder = localNumbering; // renumbered for locality: no row order of its own
  shock::Status status;
  if (mesh.NumberOfPoints() == 0)
  {
    // An empty piece takes part in the distributed fit's agreement, sums and exchanges.
    if (partition->anyStopped && partition->anyStopped(false, -1))
    {
      report.advection.aborted = true;
      return true;
    }
    status = shock::FitPositionsToNormals(mesh, nullptr, nullptr, parameters.fit, &report.fit);
    double flipped = 0.0;
    partition->globalSum(&flipped, 1);
    report.flippedTriangles = static_cast<std::int64_t>(flipped);
  }
  else
  {
    status = shock::SharpenMeshGeometry(mesh, parameters, positions.data(),
      normals.empty() ? nullptr : normals.data(),
      &report, this->GenerateFlowArrays ? &fields : nullptr,
      [this](double fraction) {
        // The advection reports up to 1; the fit follows.
        return this->ReportProgress(
          0.8 * fraction, fraction < 1.0 ? "advecting the face normals" : "fitting the positions to the normals");
      },
      partition ? nullptr : this->KernelCache.get());
  }
  this->FitAssemblies += report.advection.aborted || report.fit.reusedSystem ? 0 : 1;
  if (!status.Ok())
  {
    error = status.error;
    return false;
  }
  this->RecordRun(report.normalsSeconds + report.advection.flowSeconds,
    report.advection.advectionSeconds, report.advection.traceSteps, report.advection.truncatedTraces);
  this->UpdateProgress(1.0);
  this->LastFitSetupSeconds = report.fit.setupSeconds;
  this->LastFitSolveSeconds = report.fit.solveSeconds;
  this->LastSolverIterations = report.fit.iterations;
  this->LastSolverResidual = report.fit.residual;
  this->LastFlippedTriangles = static_cast<vtkIdType>(report.flippedTriangles);
  this->LastMaxDisplacement = report.maxDisplacement;
  this->LastRepeatedTriangles = static_cast<vtkIdType>(report.repeatedTriangles);
  this->LastDegenerateTriangles = static_cast<vtkIdType>(report.degenerateTriangles);
  this->LastFeatureEdges = static_cast<vtkIdType>(report.featureEdges);
  return true;
}

void vtkPolyDataShockSharpenFilter::BuildOutput(const ShockParallel::SurfacePiece& piece,
  const ShockPolyDataInternals::PreparedMesh& prepared, std::vector<double>& positions,
  const std::vector<double>& normals, const shock::MeshFlowFields& fields,
  const shock::SharpeningReport& report, vtkPolyData* output)
{
  vtkPolyData* input = piece.work;
  const shock::TriangleMesh& mesh = prepared.mesh;
  const ShockPolyDataInternals::Triangles& triangles = prepared.triangles;
  // The counts of what `input` holds (a released piece: what it held).
  const vtkIdType numberOfPoints = piece.released ? piece.workPoints : input->GetNumberOfPoints();
  const vtkIdType numberOfCells = piece.released
    ? std::accumulate(piece.workCells.begin(), piece.workCells.end(), vtkIdType{ 0 })
    : input->GetNumberOfCells();
  const int pointType = piece.released ? piece.workPointType : input->GetPoints()->GetDataType();
  output->ShallowCopy(input);
  // `positions` are the mesh's points; a renumbered mesh's go back to the input's numbering.
  std::vector<double> renumbered;
  if (!prepared.pointOrder.empty())
  {
    renumbered = prepared.FromMeshPoints(positions, 3, this->NumberOfThreads);
  }
  std::vector<double>& inputPositions = prepared.pointOrder.empty() ? positions : renumbered;
  SetNewPoints(output, numberOfPoints, pointType, prepared.representative, inputPositions, this->NumberOfThreads);
  RecomputeActiveNormals(output, triangles, mesh, positions); // (a piece with normals is not released)
  ReportRun(this, report, input, output);
  if (this->GenerateSharpenedNormals)
  {
    auto cells = ShockPolyDataInternals::TrianglesToCells(
      NormalsArrayName(), numberOfCells, mesh, triangles, normals);
    for (vtkIdType c = 0; c < cells->GetNumberOfTuples(); ++c)
    {
      double* n = cells->GetPointer(3 * c);
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int k = 0; k < 3 && length > 0.0; ++k)
      {
        n[k] /= length;
      }
    }
    output->GetCellData()->AddArray(cells);
  }
  if (this->GenerateFlowArrays)
  {
    shock::MeshFlowFields inputFields = fields;
    inputFields.potential = prepared.FromMeshPoints(fields.potential, 1, this->NumberOfThreads);
    // Coincident copies take their representative's potential, as they take its position.
    for (size_t p = 0; p < prepared.representative.size() && p < inputFields.potential.size(); ++p)
    {
      inputFields.potential[p] = inputFields.potential[static_cast<size_t>(prepared.representative[p])];
    }
    ShockPolyDataInternals::AttachFlowArrays(output, numberOfCells, mesh, triangles, inputFields);
  }
}

void vtkPolyDataShockSharpenFilter::ResetMeasurements()
{
  this->Superclass::ResetMeasurements();
  this->LastFitSetupSeconds = this->LastFitSolveSeconds = 0.0;
  this->LastSolverIterations = 0;
  this->LastSolverResidual = this->LastMaxDisplacement = 0.0;
  this->LastFlippedTriangles = 0;
  this->LastRepeatedTriangles = this->LastDegenerateTriangles = this->LastFeatureEdges = 0;
  this->LastGhostLevels = this->LastRingAttempts = 0;
}

std::string vtkPolyDataShockSharpenFilter::ParametersText()
{
  std::ostringstream text;
  text.precision(17);
  text << this->Superclass::ParametersText()
       << "FeatureAngle=" << this->FeatureAngle << ";"
       << "CurvatureContrast=" << this->CurvatureContrast << ";"
       << "FitTarget=" << this->FitTarget << ";"
       << "NormalSmoothingPasses=" << this->NormalSmoothingPasses << ";"
       << "KeepUnmovedNormals=" << this->KeepUnmovedNormals << ";"
       << "ScreeningWeight=" << this->ScreeningWeight << ";"
       << "AnchorWeight=" << this->AnchorWeight << ";"
       << "AnchorAngle=" << this->AnchorAngle << ";"
       << "DriftRadius=" << this->DriftRadius << ";"
       << "Solver=" << this->Solver << ";"
       << "SolverIterations=" << this->SolverIterations << ";"
       << "SolverTolerance=" << this->SolverTolerance << ";"
       << "MergeCoincidentPoints=" << this->MergeCoincidentPoints << ";"
       << "GenerateSharpenedNormals=" << this->GenerateSharpenedNormals << ";";
  return text.str();
}

void vtkPolyDataShockSharpenFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* solverNames[] = { "ConjugateGradient", "ConjugateGradientTolerance", "Exact" };
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "CurvatureContrast: " << this->CurvatureContrast << "\n";
  static const char* targetNames[] = { "Projection", "Rotation", "Shear", "CentralProjection" };
  os << indent << "FitTarget: " << targetNames[this->FitTarget] << "\n";
  os << indent << "NormalSmoothingPasses: " << this->NormalSmoothingPasses << "\n";
  os << indent << "KeepUnmovedNormals: " << (this->KeepUnmovedNormals ? "On" : "Off") << "\n";
  os << indent << "ScreeningWeight: " << this->ScreeningWeight << "\n";
  os << indent << "AnchorWeight: " << this->AnchorWeight << "\n";
  os << indent << "AnchorAngle: " << this->AnchorAngle << "\n";
  os << indent << "DriftRadius: " << this->DriftRadius << "\n";
  os << indent << "Solver: " << solverNames[this->Solver] << "\n";
  os << indent << "SolverIterations: " << this->SolverIterations << "\n";
  os << indent << "SolverTolerance: " << this->SolverTolerance << "\n";
  os << indent << "MergeCoincidentPoints: " << (this->MergeCoincidentPoints ? "On" : "Off") << "\n";
  os << indent << "GenerateSharpenedNormals: " << (this->GenerateSharpenedNormals ? "On" : "Off")
     << "\n";
  os << indent << "LastFitSetupSeconds: " << this->LastFitSetupSeconds << "\n";
  os << indent << "LastFitSolveSeconds: " << this->LastFitSolveSeconds << "\n";
  os << indent << "LastSolverIterations: " << this->LastSolverIterations << "\n";
  os << indent << "LastSolverResidual: " << this->LastSolverResidual << "\n";
  os << indent << "LastFlippedTriangles: " << this->LastFlippedTriangles << "\n";
  os << indent << "LastMaxDisplacement: " << this->LastMaxDisplacement << "\n";
  os << indent << "LastRepeatedTriangles: " << this->LastRepeatedTriangles << "\n";
  os << indent << "LastDegenerateTriangles: " << this->LastDegenerateTriangles << "\n";
  os << indent << "LastFeatureEdges: " << this->LastFeatureEdges << "\n";
  os << indent << "LastGhostLevels: " << this->LastGhostLevels << "\n";
  os << indent << "LastRingAttempts: " << this->LastRingAttempts << "\n";
  os << indent << "NumberOfMeshPreparations: " << this->GetNumberOfMeshPreparations() << "\n";
  os << indent << "NumberOfFitAssemblies: " << this->FitAssemblies << "\n";
}
