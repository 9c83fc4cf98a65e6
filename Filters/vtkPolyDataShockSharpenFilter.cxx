#include "vtkPolyDataShockSharpenFilter.h"

#include "MeshSharpening.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShockFilterInternals.h"
#include "vtkShockParallel.h"
#include "vtkShockPolyDataInternals.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <chrono>
#include <algorithm>
#include <cmath>
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
  return vtkShockPolyDataInternals::EnsurePolyDataOutput(inputVector, outputVector)
    ? 1
    : this->Superclass::RequestDataObject(request, inputVector, outputVector);
}

namespace
{
/// A piece of a distributed mesh as the fit sees it, and the exchange behind it.
struct Distribution
{
  shock::MeshPartition partition;
  vtkShockParallel::PointExchange exchange;
  double meanEdgeLength = 0.0;
};

/**
 * Ownership from the ghost marks (each point and triangle owned by one
 * process), the points whose owners' values this piece needs (corners of the
 * triangles around its owned points and of its owned triangles), the exchange
 * keyed by global point ids, and the mean edge length over all pieces.
 */
void Distribute(vtkMultiProcessController* controller, vtkPolyData* piece,
  const vtkShockPolyDataInternals::PreparedMesh& prepared, Distribution& out)
{
  const shock::TriangleMesh& mesh = prepared.mesh;
  const std::int64_t np = mesh.NumberOfPoints();
  const std::int64_t nt = mesh.NumberOfTriangles();
  vtkUnsignedCharArray* pointGhosts = vtkShockParallel::PointGhosts(piece);
  vtkUnsignedCharArray* cellGhosts = piece->GetCellGhostArray();
  shock::MeshPartition& partition = out.partition;
  partition.ownedPoints.assign(static_cast<size_t>(np), 1);
  partition.ownedTriangles.assign(static_cast<size_t>(nt), 1);
  for (std::int64_t p = 0; pointGhosts && p < np; ++p)
  {
    partition.ownedPoints[static_cast<size_t>(p)] =
      (pointGhosts->GetValue(p) & vtkDataSetAttributes::DUPLICATEPOINT) ? 0 : 1;
  }
  double lengths[2] = { 0.0, 0.0 };
  std::vector<char> needed(static_cast<size_t>(np), 0);
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const vtkIdType cell = prepared.triangles.sourceCell[static_cast<size_t>(f)];
    const bool owned = !cellGhosts || !(cellGhosts->GetValue(cell) & vtkDataSetAttributes::DUPLICATECELL);
    partition.ownedTriangles[static_cast<size_t>(f)] = owned ? 1 : 0;
    const std::int64_t* t = mesh.Corners(f);
    bool touchesOwned = owned;
    for (int k = 0; k < 3; ++k)
    {
      touchesOwned = touchesOwned || partition.ownedPoints[static_cast<size_t>(t[k])];
    }
    for (int k = 0; k < 3 && touchesOwned; ++k)
    {
      needed[static_cast<size_t>(t[k])] |= partition.ownedPoints[static_cast<size_t>(t[k])] ? 0 : 1;
    }
    if (owned)
    {
      lengths[0] += shock::TrianglePerimeter(
        prepared.triangles.points.data(), &prepared.triangles.triangles[static_cast<size_t>(3 * f)]);
      lengths[1] += 3.0;
    }
  }
  vtkShockParallel::Sum(controller, lengths, 2);
  out.meanEdgeLength = lengths[1] > 0.0 ? lengths[0] / lengths[1] : 0.0;
  vtkDataArray* ids = piece->GetPointData()->GetGlobalIds();
  std::vector<vtkIdType> globalIds(static_cast<size_t>(np), -1);
  for (std::int64_t p = 0; ids && p < np; ++p)
  {
    globalIds[static_cast<size_t>(p)] = static_cast<vtkIdType>(ids->GetTuple1(p));
  }
  out.exchange.Setup(controller, globalIds.data(), partition.ownedPoints, needed);
  // What a piece costs: its ghost layers, and the traffic of one CG iteration
  // (one exchange of 3 doubles per point, two global sums of 3 and 6 doubles).
  std::int64_t ownedPoints = 0;
  for (char owned : partition.ownedPoints)
  {
    ownedPoints += owned;
  }
  vtkLogF(INFO,
    "vtkPolyDataShockSharpenFilter piece %d of %d: %lld points (%lld owned, %lld in ghost "
    "layers), %lld triangles; per CG iteration %lld bytes sent and %lld received point to "
    "point, 72 bytes reduced",
    controller->GetLocalProcessId(), controller->GetNumberOfProcesses(), static_cast<long long>(np),
    static_cast<long long>(ownedPoints), static_cast<long long>(np - ownedPoints),
    static_cast<long long>(nt), static_cast<long long>(24 * out.exchange.SentPoints()),
    static_cast<long long>(24 * out.exchange.ReceivedPoints()));
  partition.globalSum = [controller](double* values, int count) {
    vtkShockParallel::Sum(controller, values, count);
  };
  partition.exchangePoints = [&out](double* values) { out.exchange.Exchange(values); };
}
}

int vtkPolyDataShockSharpenFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!output || !this->BeginExecution())
  {
    return 0;
  }
  // The surface (an unstructured grid of polygons is read as polydata).
  std::string error;
  vtkSmartPointer<vtkPolyData> input =
    vtkShockPolyDataInternals::AsSurface(vtkDataSet::GetData(inputVector[0]), error);
  // In parallel: all agree, replicated data is recognised, pieces get ghost layers
  // (collective; at least one: the fit's rows need the one-rings of their points).
  bool unknown = false;
  vtkMultiProcessController* controller = this->PieceController(outputVector, unknown);
  if (unknown && input && input->GetNumberOfPoints() > 0)
  {
    error = "This is one of several pieces of the mesh, and no MPI controller with as many "
            "processes is available to fit them together; give the whole mesh to one process.";
  }
  vtkShockParallel::SurfacePiece piece;
  if (!vtkShockParallel::PrepareSurfacePiece(
        controller, input, error, std::max(1, this->GhostLevels), piece, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (piece.skip)
  {
    output->Initialize();
    return 1; // replicated data: process 0 sharpens it once
  }
  if (piece.controller && this->Solver == EXACT)
  {
    vtkErrorMacro("The EXACT solver factorises the whole system on one process, but the mesh is "
                  "split over processes: use the CONJUGATE_GRADIENT solvers (solved across them).");
    return 0;
  }
  // The triangle mesh of the piece (with its ghost cells).
  vtkShockPolyDataInternals::PreparedMesh prepared;
  const bool empty = piece.work->GetNumberOfPoints() == 0;
  bool ok = empty ||
    vtkShockPolyDataInternals::PrepareMesh(
      piece.work, this->MergeCoincidentPoints, this->NumberOfThreads, prepared, error);
  if (piece.controller ? vtkShockParallel::AnyFailed(piece.controller, !ok, error) : !ok)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->LastSetupSeconds = prepared.seconds;
  if (!piece.controller && (empty || prepared.mesh.NumberOfTriangles() == 0))
  {
    output->ShallowCopy(input);
    vtkWarningMacro(<< (empty ? "The input mesh is empty" : "The mesh has no polygons")
                    << ": nothing to sharpen.");
    return 1;
  }
  // A piece: what it owns, what it exchanges, the whole mesh's length unit.
  Distribution distribution;
  if (piece.controller)
  {
    Distribute(piece.controller, piece.work, prepared, distribution);
  }
  // Normals, potential, flow and advection on the piece; the fit across pieces.
  std::vector<double> positions(prepared.triangles.points.size());
  std::vector<double> normals(static_cast<size_t>(3 * prepared.mesh.NumberOfTriangles()));
  shock::SharpeningReport report;
  shock::MeshFlowFields fields;
  if (!this->Sharpen(prepared.mesh, piece.controller ? &distribution.partition : nullptr,
        distribution.meanEdgeLength, positions, normals, report, fields))
  {
    return 0;
  }
  if (report.advection.aborted || empty)
  {
    output->ShallowCopy(input);
    return 1; // aborted (the output holds the input), or an empty piece
  }
  // The output: the piece's own cells with the new positions and the requested arrays.
  vtkNew<vtkPolyData> sharpened;
  this->BuildOutput(piece.work, prepared, positions, normals, fields, report, sharpened);
  output->ShallowCopy(piece.controller ? vtkShockParallel::OwnedPiece(sharpened, input).GetPointer()
                                       : sharpened.GetPointer());
  return 1;
}

bool vtkPolyDataShockSharpenFilter::Sharpen(const shock::TriangleMesh& mesh,
  const shock::MeshPartition* partition, double meanEdgeLength, std::vector<double>& positions,
  std::vector<double>& normals, shock::SharpeningReport& report, shock::MeshFlowFields& fields)
{
  shock::SharpeningParameters parameters;
  parameters.advection = vtkShockFilterInternals::MakeParameters(this);
  parameters.normalSmoothingPasses = this->NormalSmoothingPasses;
  parameters.lengthScale = meanEdgeLength;
  parameters.fit.screeningWeight = this->ScreeningWeight;
  parameters.fit.solver = static_cast<shock::FitSolver>(this->Solver);
  parameters.fit.iterations = this->SolverIterations;
  parameters.fit.maxIterations = this->SolverIterations;
  parameters.fit.tolerance = this->SolverTolerance;
  parameters.fit.partition = partition;
  shock::Status status;
  if (mesh.NumberOfPoints() == 0)
  {
    // An empty piece takes part in the distributed fit's sums and exchanges.
    status = shock::FitPositionsToNormals(mesh, nullptr, nullptr, parameters.fit, &report.fit);
    double flipped = 0.0;
    partition->globalSum(&flipped, 1);
    report.flippedTriangles = static_cast<std::int64_t>(flipped);
  }
  else
  {
    status = shock::SharpenMeshGeometry(mesh, parameters, positions.data(), normals.data(),
      &report, this->GenerateFlowArrays ? &fields : nullptr,
      [this](double fraction) { return this->ReportProgress(0.8 * fraction); });
  }
  if (!status.Ok())
  {
    vtkErrorMacro("Geometry sharpening failed: " << status.error);
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
  return true;
}

void vtkPolyDataShockSharpenFilter::BuildOutput(vtkPolyData* input,
  const vtkShockPolyDataInternals::PreparedMesh& prepared, std::vector<double>& positions,
  const std::vector<double>& normals, const shock::MeshFlowFields& fields,
  const shock::SharpeningReport& report, vtkPolyData* output)
{
  const shock::TriangleMesh& mesh = prepared.mesh;
  const vtkShockPolyDataInternals::Triangles& triangles = prepared.triangles;
  output->ShallowCopy(input);
  // Coincident copies take the position computed for their representative.
  const std::vector<std::int64_t>& representative = prepared.representative;
  for (size_t p = 0; p < representative.size(); ++p)
  {
    const size_t r = static_cast<size_t>(representative[p]);
    std::copy(&positions[3 * r], &positions[3 * r] + 3, &positions[3 * p]);
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(input->GetPoints()->GetDataType());
  points->SetNumberOfPoints(input->GetNumberOfPoints());
  for (vtkIdType p = 0; p < input->GetNumberOfPoints(); ++p)
  {
    points->SetPoint(p, &positions[static_cast<size_t>(3 * p)]);
  }
  output->SetPoints(points);

  vtkNew<vtkFieldData> field;
  field->ShallowCopy(input->GetFieldData());
  field->AddArray(SingleValue("ShockSolverIterations", report.fit.iterations));
  field->AddArray(SingleValue("ShockSolverResidual", report.fit.residual));
  field->AddArray(SingleValue("ShockFlippedTriangles", report.flippedTriangles));
  field->AddArray(SingleValue("ShockMaxDisplacement", report.maxDisplacement));
  output->SetFieldData(field);
  vtkLogF(INFO,
    "vtkPolyDataShockSharpenFilter: %d solver iterations, relative residual %.3g%s, %lld flipped "
    "triangles, max displacement %.3g of the bounding-box diagonal",
    report.fit.iterations, report.fit.residual,
    // The paper's fixed 25 iterations do not aim at a tolerance: only flag the modes that do.
    (this->Solver == CONJUGATE_GRADIENT || report.fit.converged) ? "" : " (above the tolerance)",
    static_cast<long long>(report.flippedTriangles), report.maxDisplacement);
  if (report.fit.invalidTargets > 0)
  {
    vtkWarningMacro(<< report.fit.invalidTargets
                    << " triangles had no valid sharpened normal and kept their own.");
  }
  if (this->GenerateSharpenedNormals)
  {
    auto cells = vtkShockPolyDataInternals::TrianglesToCells(
      NormalsArrayName(), input->GetNumberOfCells(), mesh, triangles, normals);
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
    vtkShockPolyDataInternals::AttachFlowArrays(output, mesh, triangles, fields);
  }
}

void vtkPolyDataShockSharpenFilter::ResetMeasurements()
{
  this->Superclass::ResetMeasurements();
  this->LastFitSetupSeconds = this->LastFitSolveSeconds = 0.0;
  this->LastSolverIterations = 0;
  this->LastSolverResidual = this->LastMaxDisplacement = 0.0;
  this->LastFlippedTriangles = 0;
}

void vtkPolyDataShockSharpenFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* solverNames[] = { "ConjugateGradient", "ConjugateGradientTolerance", "Exact" };
  os << indent << "NormalSmoothingPasses: " << this->NormalSmoothingPasses << "\n";
  os << indent << "ScreeningWeight: " << this->ScreeningWeight << "\n";
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
}
