#include "vtkPolyDataShockAdvectionFilter.h"

#include "MeshShockAdvection.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkShockFilterInternals.h"
#include "vtkShockPolyDataInternals.h"
#include "vtkUnsignedCharArray.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkPolyDataShockAdvectionFilter);

vtkPolyData* vtkPolyDataShockAdvectionFilter::GetOutput()
{
  return this->GetOutput(0);
}

vtkPolyData* vtkPolyDataShockAdvectionFilter::GetOutput(int port)
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(port));
}

int vtkPolyDataShockAdvectionFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkPolyDataShockAdvectionFilter::RequestData(
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
  if (input->GetNumberOfPoints() == 0)
  {
    output->ShallowCopy(input);
    if (this->ParallelPiecesWithData == NOT_A_PIECE) // an empty piece of a parallel run is normal
    {
      vtkWarningMacro("The input mesh is empty: nothing to filter.");
    }
    return 1;
  }
  int association = -1;
  vtkDataArray* array = this->GetArrayToFilter(inputVector, association);
  if (!array)
  {
    return 0;
  }
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const char* name = array->GetName() ? array->GetName() : "(unnamed)";
  const vtkIdType expected = cellData ? input->GetNumberOfCells() : input->GetNumberOfPoints();
  if (array->GetNumberOfTuples() != expected)
  {
    vtkErrorMacro("Array '" << name << "' has " << array->GetNumberOfTuples() << " tuples, the mesh has "
                            << expected << (cellData ? " cells." : " points."));
    return 0;
  }

  vtkShockPolyDataInternals::PreparedMesh prepared;
  std::string error;
  if (!vtkShockPolyDataInternals::PrepareMesh(input, false, this->NumberOfThreads, prepared, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const vtkShockPolyDataInternals::Triangles& triangles = prepared.triangles;
  const shock::TriangleMesh& mesh = prepared.mesh;
  if (cellData && triangles.nonTriangleCells > 0)
  {
    vtkErrorMacro("Cell array '" << name << "' lives on " << triangles.nonTriangleCells
                                 << " polygons with more than 3 points or triangle strips: cell data "
                                    "is only filtered on triangles. Triangulate the mesh first "
                                    "(vtkTriangleFilter, or ParaView's Triangulate filter).");
    return 0;
  }
  this->LastSetupSeconds = prepared.seconds;

  // Everything checked: the output starts as the input, arrays shared.
  output->ShallowCopy(input);
  if (mesh.NumberOfTriangles() == 0)
  {
    vtkWarningMacro("The mesh has no polygons: nothing to filter.");
    return 1;
  }

  const int components = array->GetNumberOfComponents();
  std::vector<double> values = vtkShockFilterInternals::ToDoubles(array);
  std::vector<double> signal;
  if (cellData)
  {
    // The kernel sees one value per triangle; other cells keep theirs.
    signal.resize(static_cast<size_t>(mesh.NumberOfTriangles() * components));
    for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
    {
      const double* row = &values[static_cast<size_t>(triangles.sourceCell[static_cast<size_t>(f)] * components)];
      std::copy(row, row + components, &signal[static_cast<size_t>(f * components)]);
    }
  }
  shock::MeshSignal meshSignal;
  meshSignal.location = cellData ? shock::MeshLocation::Triangles : shock::MeshLocation::Points;
  meshSignal.components = components;
  meshSignal.values = cellData ? signal.data() : values.data();
  meshSignal.valueScale = this->ParallelValueScale; // 0 (own range) unless a parallel piece
  meshSignal.lengthScale = this->ParallelLengthScale; // likewise for the mean edge length
  std::vector<double> filtered(cellData ? signal.size() : values.size());
  shock::AdvectionReport report;
  shock::MeshFlowFields fields;
  const shock::Status status = shock::AdvectMeshSignal(mesh, meshSignal, filtered.data(),
    vtkShockFilterInternals::MakeParameters(this), &report, this->GenerateFlowArrays ? &fields : nullptr,
    [this](double fraction) { return this->ReportProgress(fraction); });
  if (!status.Ok())
  {
    vtkErrorMacro("Shock filter failed: " << status.error);
    return 0;
  }
  this->RecordRun(report.flowSeconds, report.advectionSeconds, report.traceSteps, report.truncatedTraces);
  if (report.aborted)
  {
    return 1; // aborted: the output holds the unfiltered input
  }
  if (cellData)
  {
    for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
    {
      const double* row = &filtered[static_cast<size_t>(f * components)];
      std::copy(row, row + components,
        &values[static_cast<size_t>(triangles.sourceCell[static_cast<size_t>(f)] * components)]);
    }
    filtered.swap(values);
  }
  vtkDataSetAttributes* attributes =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetCellData()) : output->GetPointData();
  vtkShockFilterInternals::ReplaceArray(
    attributes, array, vtkShockFilterInternals::FromDoubles(array, filtered));
  if (this->GenerateFlowArrays)
  {
    vtkShockPolyDataInternals::AttachFlowArrays(output, mesh, triangles, fields);
  }
  return 1;
}

int vtkPolyDataShockAdvectionFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!inInfo || !outInfo || this->ExecutingBlock)
  {
    return 1; // a block of a composite input: the request was made for the whole input
  }
  const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES())
    : 1;
  if (pieces > 1)
  {
    const int requested = outInfo->Has(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS())
      ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS())
      : 0;
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), requested + this->GhostLevels);
  }
  return 1;
}

bool vtkPolyDataShockAdvectionFilter::LocalEdgeLengthSum(
  vtkInformationVector** inputVector, double& sum, double& count)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkShockPolyDataInternals::Triangles triangles;
  std::string error;
  if (!input || !vtkShockPolyDataInternals::ExtractTriangles(input, triangles, error))
  {
    return false; // RequestData reports the error
  }
  vtkUnsignedCharArray* ghosts = input->GetCellGhostArray();
  sum = count = 0.0;
  for (size_t f = 0; f < triangles.sourceCell.size(); ++f)
  {
    if (ghosts && (ghosts->GetValue(triangles.sourceCell[f]) & vtkDataSetAttributes::DUPLICATECELL))
    {
      continue;
    }
    sum += shock::TrianglePerimeter(triangles.points.data(), &triangles.triangles[3 * f]);
    count += 3.0;
  }
  return true;
}

bool vtkPolyDataShockAdvectionFilter::LocalValueRange(
  vtkInformationVector** inputVector, double range[2])
{
  int association = -1;
  vtkDataArray* array =
    vtkDataArray::SafeDownCast(this->GetInputAbstractArrayToProcess(0, inputVector, association));
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  if (!array || !input || association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    return this->Superclass::LocalValueRange(inputVector, range);
  }
  range[0] = std::numeric_limits<double>::infinity();
  range[1] = -range[0];
  const int components = array->GetNumberOfComponents();
  std::vector<double> tuple(static_cast<size_t>(components));
  const vtkIdType cells = std::min(array->GetNumberOfTuples(), input->GetNumberOfCells());
  for (vtkIdType c = 0; c < cells; ++c)
  {
    const int type = input->GetCellType(c);
    const bool surface = type == VTK_TRIANGLE || type == VTK_QUAD || type == VTK_POLYGON ||
      type == VTK_TRIANGLE_STRIP;
    if (!surface || input->GetCellSize(c) < 3)
    {
      continue; // no triangle: the kernel does not see this cell
    }
    array->GetTuple(c, tuple.data());
    if (std::all_of(tuple.begin(), tuple.end(), [](double v) { return std::isfinite(v); }))
    {
      for (double v : tuple)
      {
        range[0] = std::min(range[0], v);
        range[1] = std::max(range[1], v);
      }
    }
  }
  return range[0] <= range[1];
}

void vtkPolyDataShockAdvectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
