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
#include "vtkShockPolyDataInternals.h"

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
  return 1;
}

int vtkPolyDataShockSharpenFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkPolyData.");
    return 0;
  }
  if (!this->BeginExecution())
  {
    return 0;
  }
  // One piece of a distributed mesh: the global fit cannot be done per piece.
  if (this->ParallelPiecesWithData > 1 ||
    (this->ParallelPiecesWithData == UNKNOWN_PIECES && input->GetNumberOfPoints() > 0))
  {
    std::ostringstream held;
    if (this->ParallelPiecesWithData > 1)
    {
      held << "the mesh is split over " << this->ParallelPiecesWithData << " processes";
    }
    else
    {
      held << "this is one of several pieces of the mesh";
    }
    vtkErrorMacro("Surface Shock Sharpen cannot run on one piece of a distributed mesh ("
      << held.str()
      << "): the screened Poisson fit is global, so pieces fitted separately would not match "
         "along their boundaries. Give the whole mesh to one process: in ParaView, gather it "
         "with Aggregate Dataset (Number Of Target Processes 1) before this filter, or read it "
         "with a serial reader; or run in the builtin session, pvpython or a serial pvbatch.");
    return 0;
  }
  if (input->GetNumberOfPoints() == 0)
  {
    output->ShallowCopy(input);
    if (this->ParallelPiecesWithData == NOT_A_PIECE) // an empty piece of a parallel run is normal
    {
      vtkWarningMacro("The input mesh is empty: nothing to sharpen.");
    }
    return 1;
  }

  vtkShockPolyDataInternals::PreparedMesh prepared;
  std::string error;
  if (!vtkShockPolyDataInternals::PrepareMesh(
        input, this->MergeCoincidentPoints, this->NumberOfThreads, prepared, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const vtkShockPolyDataInternals::Triangles& triangles = prepared.triangles;
  const shock::TriangleMesh& mesh = prepared.mesh;
  const std::vector<std::int64_t>& representative = prepared.representative;
  this->LastSetupSeconds = prepared.seconds;
  if (mesh.NumberOfTriangles() == 0)
  {
    output->ShallowCopy(input);
    vtkWarningMacro("The mesh has no polygons: nothing to sharpen.");
    return 1;
  }

  shock::SharpeningParameters parameters;
  parameters.advection = vtkShockFilterInternals::MakeParameters(this);
  parameters.normalSmoothingPasses = this->NormalSmoothingPasses;
  parameters.fit.screeningWeight = this->ScreeningWeight;
  parameters.fit.solver = static_cast<shock::FitSolver>(this->Solver);
  parameters.fit.iterations = this->SolverIterations;
  parameters.fit.maxIterations = this->SolverIterations;
  parameters.fit.tolerance = this->SolverTolerance;
  std::vector<double> positions(triangles.points.size());
  std::vector<double> normals(static_cast<size_t>(3 * mesh.NumberOfTriangles()));
  shock::SharpeningReport report;
  shock::MeshFlowFields fields;
  const shock::Status status = shock::SharpenMeshGeometry(mesh, parameters, positions.data(),
    normals.data(), &report, this->GenerateFlowArrays ? &fields : nullptr,
    [this](double fraction) { return this->ReportProgress(0.8 * fraction); });
  if (!status.Ok())
  {
    vtkErrorMacro("Geometry sharpening failed: " << status.error);
    return 0;
  }
  this->RecordRun(report.normalsSeconds + report.advection.flowSeconds,
    report.advection.advectionSeconds, report.advection.traceSteps, report.advection.truncatedTraces);
  output->ShallowCopy(input);
  if (report.advection.aborted)
  {
    return 1; // aborted: the output holds the input
  }
  this->UpdateProgress(1.0);
  this->LastFitSetupSeconds = report.fit.setupSeconds;
  this->LastFitSolveSeconds = report.fit.solveSeconds;
  this->LastSolverIterations = report.fit.iterations;
  this->LastSolverResidual = report.fit.residual;
  this->LastFlippedTriangles = static_cast<vtkIdType>(report.flippedTriangles);
  this->LastMaxDisplacement = report.maxDisplacement;

  // Coincident copies take the position computed for their representative.
  if (!representative.empty())
  {
    for (size_t p = 0; p < representative.size(); ++p)
    {
      const size_t r = static_cast<size_t>(representative[p]);
      std::copy(&positions[3 * r], &positions[3 * r] + 3, &positions[3 * p]);
    }
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
  return 1;
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
