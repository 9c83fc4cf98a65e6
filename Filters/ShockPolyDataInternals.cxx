/**
 * @file ShockPolyDataInternals.cxx
 * @brief The surface filters' shared glue: the input as a surface, its checks and
 * the agreement of the pieces (BeginSurface), the output's flow arrays.
 */
#include "vtkLogger.h"
#include "ShockPolyDataInternals.h"

#include "MeshOrder.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkShockAdvectionFilter.h"
#include "vtkCellArrayIterator.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "ShockFilterInternals.h"
#include "ShockParallel.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>


namespace ShockPolyDataInternals
{
namespace
{
std::array<std::uintptr_t, 4> InputStamp(vtkDataObject* input)
{
  auto* data = vtkDataSet::SafeDownCast(input);
  auto* surface = vtkPointSet::SafeDownCast(input);
  return { reinterpret_cast<std::uintptr_t>(input),
    data ? static_cast<std::uintptr_t>(data->GetNumberOfPoints()) : 0,
    data ? static_cast<std::uintptr_t>(data->GetNumberOfCells()) : 0,
    surface && surface->GetPoints() ? reinterpret_cast<std::uintptr_t>(surface->GetPoints()->GetData()) : 0 };
}
}

int RingAgreement::Start(vtkMultiProcessController* controller, vtkDataObject* input, int stencil, int spare, int most)
{
  if (!controller)
  {
    return most;
  }
  if (!input || InputStamp(input) != this->Stamp)
  {
    this->Rings = 0; // another input: grown again from the stencil
  }
  // Every process takes part, whatever its parameters (they are compared after this).
  const int mine = stencil < 0 ? most : std::min(most, std::max(stencil + spare, this->Rings));
  int rings = mine;
  controller->AllReduce(&mine, &rings, 1, vtkCommunicator::MAX_OP); // the same on every process
  return rings;
}

void RingAgreement::Keep(vtkDataObject* input, int rings)
{
  this->Rings = rings;
  this->Stamp = InputStamp(input);
}

std::string TooFewRingsWarning(int ghostLevels, const char* samples)
{
  return std::string("Flow lines of ") + samples + " near the pieces' borders run further than the " +
    std::to_string(ghostLevels) + " ghost rings (Ghost Levels) make exact: those " + samples +
    " may differ from a serial run. Raise Ghost Levels (up to 64) for the serial result.";
}

vtkSmartPointer<vtkDoubleArray> TrianglesToCells(const char* name, vtkIdType numberOfCells,
  const shock::TriangleMesh& mesh, const Triangles& triangles, const std::vector<double>& vectors)
{
  auto cells = vtkSmartPointer<vtkDoubleArray>::New();
  cells->SetName(name);
  cells->SetNumberOfComponents(3);
  cells->SetNumberOfTuples(numberOfCells);
  cells->Fill(0.0);
  std::vector<double> area(static_cast<size_t>(numberOfCells), 0.0);
  double* sum = cells->GetPointer(0);
  for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
  {
    const vtkIdType cell = triangles.sourceCell[static_cast<size_t>(f)];
    const double a = mesh.Area(f);
    area[static_cast<size_t>(cell)] += a;
    for (int k = 0; k < 3; ++k)
    {
      sum[3 * cell + k] += a * vectors[static_cast<size_t>(3 * f + k)];
    }
  }
  for (vtkIdType cell = 0; cell < numberOfCells; ++cell)
  {
    const double a = area[static_cast<size_t>(cell)];
    for (int k = 0; k < 3; ++k)
    {
      sum[3 * cell + k] = a > 0.0 ? sum[3 * cell + k] / a : 0.0;
    }
  }
  return cells;
}

void AttachFlowArrays(vtkPolyData* output, vtkIdType numberOfCells, const shock::TriangleMesh& mesh,
  const Triangles& triangles, const shock::MeshFlowFields& fields)
{
  vtkNew<vtkDoubleArray> potential;
  potential->SetName(vtkShockAdvectionFilter::PotentialArrayName());
  potential->SetNumberOfTuples(output->GetNumberOfPoints());
  std::copy(fields.potential.begin(), fields.potential.end(), potential->GetPointer(0));
  output->GetPointData()->AddArray(potential);
  output->GetCellData()->AddArray(TrianglesToCells(
    vtkShockAdvectionFilter::FlowArrayName(), numberOfCells, mesh, triangles, fields.flow));
}

vtkSmartPointer<vtkPolyData> AsSurface(vtkDataSet* input, std::string& error)
{
  if (vtkPolyData* polyData = vtkPolyData::SafeDownCast(input))
  {
    return polyData;
  }
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::SafeDownCast(input);
  if (!grid)
  {
    error = std::string("The input is a ") + (input ? input->GetClassName() : "null data set") +
      ", not a surface: add Extract Surface before this filter.";
    return nullptr;
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(grid->GetPoints());
  surface->GetPointData()->ShallowCopy(grid->GetPointData());
  surface->GetFieldData()->ShallowCopy(grid->GetFieldData());
  // Polygons only (what a distributed triangle mesh is): the grid's cell array is the polygons' as it is.
  vtkUnsignedCharArray* types = grid->GetCellTypesArray();
  bool polygonsOnly = types && types->GetNumberOfTuples() == grid->GetNumberOfCells() && grid->GetCells();
  for (vtkIdType c = 0; polygonsOnly && c < types->GetNumberOfTuples(); ++c)
  {
    const unsigned char type = types->GetValue(c);
    polygonsOnly = type == VTK_TRIANGLE || type == VTK_QUAD || type == VTK_POLYGON;
  }
  if (polygonsOnly)
  {
    surface->SetPolys(grid->GetCells());
    surface->GetCellData()->ShallowCopy(grid->GetCellData());
    return surface;
  }
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  // vtkPolyData numbers verts, lines, polygons, strips in that order: cell data follows.
  std::vector<vtkIdType> order[4];
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const int type = grid->GetCellType(c);
    const int kind = (type == VTK_VERTEX || type == VTK_POLY_VERTEX) ? 0
      : (type == VTK_LINE || type == VTK_POLY_LINE)                   ? 1
      : (type == VTK_TRIANGLE || type == VTK_QUAD || type == VTK_POLYGON) ? 2
      : type == VTK_TRIANGLE_STRIP                                     ? 3
                                                                       : -1;
    if (kind < 0)
    {
      error = "The input is an unstructured grid with cells that are not surface polygons (cell " +
        std::to_string(c) + " is of VTK type " + std::to_string(type) +
        "): add Extract Surface before this filter.";
      return nullptr;
    }
    order[kind].push_back(c);
  }
  vtkCellArray* arrays[4] = { verts, lines, polys, strips };
  vtkNew<vtkIdList> ids, cells;
  for (int kind = 0; kind < 4; ++kind)
  {
    for (vtkIdType c : order[kind])
    {
      grid->GetCellPoints(c, ids);
      arrays[kind]->InsertNextCell(ids);
      cells->InsertNextId(c);
    }
  }
  surface->SetVerts(verts);
  surface->SetLines(lines);
  surface->SetPolys(polys);
  surface->SetStrips(strips);
  surface->GetCellData()->CopyAllocate(grid->GetCellData(), cells->GetNumberOfIds());
  vtkNew<vtkIdList> rows;
  rows->SetNumberOfIds(cells->GetNumberOfIds());
  for (vtkIdType k = 0; k < cells->GetNumberOfIds(); ++k)
  {
    rows->SetId(k, k);
  }
  surface->GetCellData()->CopyData(grid->GetCellData(), cells, rows);
  return surface;
}

std::string ValidateSurface(vtkPolyData* surface)
{
  // Point ids of every kind of cell (vtkPolyData numbers verts, lines, polygons, strips in turn).
  const vtkIdType numberOfPoints = surface->GetNumberOfPoints();
  const char* kinds[4] = { "vertex cell", "line cell", "cell", "strip" };
  vtkCellArray* arrays[4] = { surface->GetVerts(), surface->GetLines(), surface->GetPolys(), surface->GetStrips() };
  vtkIdType cellId = 0;
  std::string error;
  for (int kind = 0; kind < 4; ++kind)
  {
    if (!arrays[kind])
    {
      continue;
    }
    auto iterator = vtk::TakeSmartPointer(arrays[kind]->NewIterator());
    for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++cellId)
    {
      vtkIdType size;
      const vtkIdType* ids;
      iterator->GetCurrentCell(size, ids);
      if (!IdsInRange(kinds[kind], cellId, size, ids, numberOfPoints, error))
      {
        return "Cannot read the mesh: " + error + ".";
      }
    }
  }
  vtkDataArray* coordinates = surface->GetPoints() ? surface->GetPoints()->GetData() : nullptr;
  if (coordinates)
  {
    bool finite = true;
    const vtkIdType values = coordinates->GetNumberOfValues();
    if (auto* doubles = vtkDoubleArray::SafeDownCast(coordinates))
    {
      const double* x = doubles->GetPointer(0);
      for (vtkIdType k = 0; k < values; ++k)
      {
        finite = finite && std::isfinite(x[k]);
      }
    }
    else if (auto* floats = vtkFloatArray::SafeDownCast(coordinates))
    {
      const float* x = floats->GetPointer(0);
      for (vtkIdType k = 0; k < values; ++k)
      {
        finite = finite && std::isfinite(x[k]);
      }
    }
    else
    {
      for (vtkIdType k = 0; k < values; ++k)
      {
        finite = finite && std::isfinite(coordinates->GetComponent(k / 3, static_cast<int>(k % 3)));
      }
    }
    if (!finite)
    {
      return "Cannot use the mesh: a point coordinate is not finite (NaN or infinity).";
    }
  }
  return "";
}

bool BeginSurface(vtkInformationVector** inputVector, vtkMultiProcessController* controller,
  int ghostLevels, const std::function<std::string(vtkPolyData* surface)>& check,
  const std::string& parameters, const std::string* selection, const ShockParallel::CarriedArrays& carried,
  vtkSmartPointer<vtkPolyData>& input, ShockParallel::SurfacePiece& piece, std::string& error)
{
  error.clear();
  input = AsSurface(vtkDataSet::GetData(inputVector[0]), error);
  if (!input)
  {
    // A filter that cannot start says why (e.g. its input failed to update, and left no data set).
    const std::string reason = check ? check(nullptr) : std::string();
    error = reason.empty() ? error : reason;
  }
  else
  {
    // Ids and coordinates first: no later step (nor any collective one) reads a broken piece.
    error = ValidateSurface(input);
    if (error.empty() && check)
    {
      error = check(input);
    }
  }
  // In parallel: every process agrees (on failure, parameters and arrays), then gets ghost cells (collective).
  return ShockParallel::PrepareSurfacePiece(controller, input, error, parameters,
    selection ? *selection : std::string(), ghostLevels, carried, piece, error);
}

bool IsSurfaceType(vtkDataObject* data)
{
  return vtkPolyData::SafeDownCast(data) || vtkUnstructuredGrid::SafeDownCast(data);
}

bool EnsurePolyDataOutput(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // Other data sets (a block of another type in a composite input) keep their type and pass through.
  if (!inInfo || !outInfo || !IsSurfaceType(inInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    return false;
  }
  if (!vtkPolyData::SafeDownCast(outInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    vtkNew<vtkPolyData> output;
    outInfo->Set(vtkDataObject::DATA_OBJECT(), output);
  }
  return true;
}

}
