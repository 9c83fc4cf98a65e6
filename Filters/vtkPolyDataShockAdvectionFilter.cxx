#include "vtkPolyDataShockAdvectionFilter.h"

#include "MeshShockAdvection.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "ShockFilterInternals.h"
#include "ShockParallel.h"
#include "ShockPolyDataInternals.h"
#include "vtkUnsignedCharArray.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkPolyDataShockAdvectionFilter);

vtkPolyData* vtkPolyDataShockAdvectionFilter::GetOutput()
{
  return this->GetOutput(0);
}

vtkPolyData* vtkPolyDataShockAdvectionFilter::GetOutput(int port)
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(port));
}

vtkPolyDataShockAdvectionFilter::vtkPolyDataShockAdvectionFilter()
  : PreparedMeshes(new ShockPolyDataInternals::MeshCache)
  , Rings(new ShockPolyDataInternals::RingAgreement)
{
  // Default array: the active point scalars.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
}

vtkPolyDataShockAdvectionFilter::~vtkPolyDataShockAdvectionFilter() = default;

int vtkPolyDataShockAdvectionFilter::GetNumberOfMeshPreparations() const
{
  return this->PreparedMeshes->GetNumberOfPreparations();
}

int vtkPolyDataShockAdvectionFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

namespace
{
/**
 * What identifies an input between executions for the agreed rings: the
 * object, its sizes and where its points are (its modification time does not:
 * VTK's cell caches and the arrays an output shares touch it).
 */
/**
 * The rings every piece gets next, the same on every process (collective):
 * more than `rings` when a flow line of a piece's own points read a triangle
 * deeper than its rings make exact (PieceReach), up to `most`; `rings` when
 * none did, or a process aborted. `tooFew`: some did with `most` rings already.
 */
int MoreRings(vtkMultiProcessController* controller, const ShockPolyDataInternals::PieceReach& reach, int rings,
  int most, bool& tooFew)
{
  const int needed = reach.stencil >= 0 ? reach.deepest + reach.stencil : -1;
  return ShockParallel::MoreLayers(controller, reach.aborted, needed, rings, most, tooFew);
}
}

int vtkPolyDataShockAdvectionFilter::RequestDataObject(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return ShockPolyDataInternals::EnsurePolyDataOutput(inputVector, outputVector)
    ? 1
    : this->Superclass::RequestDataObject(request, inputVector, outputVector);
}

bool vtkPolyDataShockAdvectionFilter::FiltersType(vtkDataObject* input)
{
  return ShockPolyDataInternals::IsSurfaceType(input);
}

int vtkPolyDataShockAdvectionFilter::RequestData(
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
  // The surface (an unstructured grid of polygons is read as polydata) and the
  // array to filter; in parallel, every process agrees, then gets ghost cells.
  int association = -1;
  vtkDataArray* array = nullptr;
  std::string selection; // the filtered array, which every piece must agree on
  ShockParallel::CarriedArrays carried{ false, {}, {} }; // the ghost rings carry the filtered array only
  bool reported = false; // the failure's own message is out already (serial: not repeated)
  auto findArray = [&](vtkPolyData* surface) -> std::string {
    if (!started)
    {
      return notStarted;
    }
    if (!surface)
    {
      return "";
    }
    array = surface->GetNumberOfPoints() > 0 ? this->GetArrayToFilter(inputVector, association) : nullptr;
    if (array)
    {
      selection = std::string("filtered ") +
        (association == vtkDataObject::FIELD_ASSOCIATION_CELLS ? "cell" : "point") + " array '" +
        (array->GetName() ? array->GetName() : "(unnamed)") + "';";
      (association == vtkDataObject::FIELD_ASSOCIATION_CELLS ? carried.cell : carried.point)
        .push_back(array->GetName() ? array->GetName() : "");
    }
    reported = !array && surface->GetNumberOfPoints() > 0;
    return reported ? "no array to filter (see the message above)" : "";
  };
  // In parallel the pieces start with the rings the flow's stencils need and
  // two more, and get more only when the flow lines of their own points read
  // deeper (MoreRings), up to GhostLevels.
  int rings = this->StartingRings(vtkDataObject::GetData(inputVector[0]), controller);
  for (;;)
  {
    selection.clear();
    carried = ShockParallel::CarriedArrays{ false, {}, {} };
    vtkSmartPointer<vtkPolyData> input;
    ShockParallel::SurfacePiece piece;
    std::string error;
    vtkLogStartScope(TRACE, "shock: input, agreement and ghost rings");
    reported = false;
    const bool begun = ShockPolyDataInternals::BeginSurface(inputVector, controller, rings, findArray,
      this->ParametersText(), &selection, carried, input, piece, error);
    vtkLogEndScope("shock: input, agreement and ghost rings");
    if (!begun)
    {
      if (controller || !reported)
      {
        vtkErrorMacro(<< error);
      }
      return 0;
    }
    if (piece.skip)
    {
      output->Initialize();
      return 1; // replicated data: process 0 filters it once
    }
    const double unit = this->GlobalScales(piece.controller, piece.work, inputVector);
    this->LastGhostLevels = piece.controller ? piece.rings : 0;
    ++this->LastRingAttempts;
    if (!piece.controller && input->GetNumberOfPoints() == 0)
    {
      output->ShallowCopy(input);
      vtkWarningMacro("The input mesh is empty: nothing to filter.");
      return 1;
    }
    // Filter the piece with its ghost cells; the output holds each owned cell once.
    vtkNew<vtkPolyData> filtered;
    ShockPolyDataInternals::PieceReach reach;
    reach.cellRing = piece.controller ? &piece.cellRing : nullptr;
    bool done = true;
    if (input->GetNumberOfPoints() > 0) // an empty piece of a parallel run is normal
    {
      vtkLogStartScope(TRACE, "shock: filter the piece");
      done = this->FilterSurface(piece.work, array, association, filtered, unit, &reach);
      vtkLogEndScope("shock: filter the piece");
      vtkLogF(TRACE, "shock: the own flow lines read ring %d of %d (the flow's stencils: %d rings)", reach.deepest,
        rings, reach.stencil);
    }
    if (piece.controller)
    {
      // Every process learns of a failure, and of a piece whose rings were too few.
      if (ShockParallel::AnyFailed(piece.controller, !done, error))
      {
        if (done)
        {
          vtkErrorMacro(<< error);
        }
        return 0;
      }
      bool tooFew = false;
      const int more = MoreRings(piece.controller, reach, rings, this->GhostLevels, tooFew);
      if (more > rings)
      {
        vtkLogF(TRACE, "shock: a flow line read too deep into %d ghost rings: again with %d", rings, more);
        rings = more;
        continue;
      }
      // Kept for the next execution of the same input (a parameter changed):
      // it starts with the rings agreed here instead of growing them again.
      this->Rings->Keep(vtkDataObject::GetData(inputVector[0]), rings);
      if (tooFew && this->GhostLevels > 0 && piece.controller->GetLocalProcessId() == 0)
      {
        vtkWarningMacro(<< ShockPolyDataInternals::TooFewRingsWarning(this->GhostLevels, "points"));
      }
    }
    if (!done)
    {
      return 0;
    }
    vtkLogScopeF(TRACE, "shock: output of the owned cells");
    if (input->GetNumberOfPoints() == 0)
    {
      output->ShallowCopy(input);
      return 1;
    }
    output->ShallowCopy(piece.controller ? ShockParallel::OwnedPiece(filtered, piece).GetPointer()
                                         : filtered.GetPointer());
    return 1;
  }
}

int vtkPolyDataShockAdvectionFilter::StartingRings(vtkDataObject* input, vtkMultiProcessController* controller)
{
  shock::MeshSignal points; // a point signal: a cell signal's one more ring is found by MoreRings
  points.location = shock::MeshLocation::Points;
  const int stencil = shock::MeshStencilRings(points, ShockFilterInternals::MakeParameters(this));
  return this->Rings->Start(controller, input, stencil, 2, this->GhostLevels);
}

void vtkPolyDataShockAdvectionFilter::ResetMeasurements()
{
  this->Superclass::ResetMeasurements();
  this->LastGhostLevels = 0;
  this->LastRingAttempts = 0;
}

namespace
{
/**
 * The sums of GlobalMeanEdgeLength, read straight from the cells when every
 * polygon is a triangle and there are no strips (the same triangles, in the
 * same order, as ExtractTriangles gives: the same sums); false otherwise.
 */
bool TriangleEdgeSums(vtkPolyData* piece, double sums[2])
{
  vtkCellArray* polys = piece->GetPolys();
  if (!polys || !piece->GetPoints() || (piece->GetStrips() && piece->GetStrips()->GetNumberOfCells() > 0) ||
    polys->GetNumberOfConnectivityIds() != 3 * polys->GetNumberOfCells())
  {
    return false;
  }
  // Every polygon has three points (offsets 0, 3, 6, ...): the connectivity is the triangles' corners in turn.
  const vtkIdType nt = polys->GetNumberOfCells();
  for (vtkIdType f = 0; f <= nt; ++f)
  {
    const vtkIdType offset = polys->IsStorage64Bit()
      ? static_cast<vtkIdType>(polys->GetOffsetsArray64()->GetValue(f))
      : static_cast<vtkIdType>(polys->GetOffsetsArray32()->GetValue(f));
    if (offset != 3 * f)
    {
      return false; // polygons of other sizes: ExtractTriangles's way
    }
  }
  // The coordinates as doubles: read in place when they are doubles in one block.
  vtkDataArray* coordinates = piece->GetPoints()->GetData();
  std::vector<double> copied;
  const double* points = nullptr;
  if (coordinates->GetDataType() == VTK_DOUBLE && coordinates->HasStandardMemoryLayout())
  {
    points = static_cast<const double*>(coordinates->GetVoidPointer(0));
  }
  else
  {
    copied.resize(static_cast<size_t>(3 * piece->GetNumberOfPoints()));
    if (coordinates->GetDataType() == VTK_FLOAT && coordinates->HasStandardMemoryLayout())
    {
      const float* from = static_cast<const float*>(coordinates->GetVoidPointer(0));
      std::copy(from, from + copied.size(), copied.begin()); // exact, as GetTuple's conversion
    }
    else
    {
      for (vtkIdType p = 0; p < piece->GetNumberOfPoints(); ++p)
      {
        coordinates->GetTuple(p, copied.data() + 3 * p);
      }
    }
    points = copied.data();
  }
  vtkUnsignedCharArray* ghosts = piece->GetCellGhostArray();
  const vtkIdType first = piece->GetNumberOfVerts() + piece->GetNumberOfLines(); // polygons' cell ids start here
  const auto sum = [&](const auto* ids) {
    for (vtkIdType f = 0; f < nt; ++f)
    {
      if (ghosts && (ghosts->GetValue(first + f) & vtkDataSetAttributes::DUPLICATECELL))
      {
        continue;
      }
      const std::int64_t corners[3] = { ids[3 * f], ids[3 * f + 1], ids[3 * f + 2] };
      sums[0] += shock::TrianglePerimeter(points, corners);
      sums[1] += 3.0;
    }
  };
  if (polys->IsStorage64Bit())
  {
    sum(polys->GetConnectivityArray64()->GetPointer(0));
  }
  else
  {
    sum(polys->GetConnectivityArray32()->GetPointer(0));
  }
  return true;
}
}

double vtkPolyDataShockAdvectionFilter::GlobalScales(
  vtkMultiProcessController* controller, vtkPolyData* piece, vtkInformationVector** inputVector)
{
  vtkLogScopeF(TRACE, "shock: global scales");
  this->ParallelValueScale = this->GlobalValueScale(controller, inputVector);
  const double unit = ShockPolyDataInternals::MeshUnit(controller, piece, this->NumberOfThreads);
  this->ParallelLengthScale =
    this->GlobalMeanEdgeLength(controller, piece, this->ParallelTriangles) / (unit > 0.0 ? unit : 1.0);
  return unit;
}

double vtkPolyDataShockAdvectionFilter::GlobalMeanEdgeLength(
  vtkMultiProcessController* controller, vtkPolyData* piece, double& wholeTriangles)
{
  wholeTriangles = 0.0;
  if (!controller)
  {
    return 0.0;
  }
  double sums[2] = { 0.0, 0.0 }; // edge lengths, edges
  if (piece && TriangleEdgeSums(piece, sums))
  {
    ShockParallel::Sum(controller, sums, 2);
    wholeTriangles = sums[1] / 3.0;
    return sums[1] > 0.0 && sums[0] > 0.0 ? sums[0] / sums[1] : 0.0;
  }
  ShockPolyDataInternals::Triangles triangles;
  std::string error;
  if (piece && ShockPolyDataInternals::ExtractTriangles(piece, triangles, error))
  {
    vtkUnsignedCharArray* ghosts = piece->GetCellGhostArray();
    for (size_t f = 0; f < triangles.sourceCell.size(); ++f)
    {
      if (!ghosts || !(ghosts->GetValue(triangles.sourceCell[f]) & vtkDataSetAttributes::DUPLICATECELL))
      {
        sums[0] += shock::TrianglePerimeter(triangles.points.data(), &triangles.triangles[3 * f]);
        sums[1] += 3.0;
      }
    }
  }
  ShockParallel::Sum(controller, sums, 2);
  wholeTriangles = sums[1] / 3.0;
  return sums[1] > 0.0 && sums[0] > 0.0 ? sums[0] / sums[1] : 0.0;
}

namespace
{
/// The selected array as the piece (with ghost cells) has it, or nullptr (`error` says why).
vtkDataArray* PieceArray(vtkPolyData* input, vtkDataArray* selected, bool cellData, std::string& error)
{
  vtkDataSetAttributes* inputAttributes =
    cellData ? static_cast<vtkDataSetAttributes*>(input->GetCellData()) : input->GetPointData();
  vtkDataArray* array =
    selected->GetName() ? inputAttributes->GetArray(selected->GetName()) : inputAttributes->GetScalars();
  const vtkIdType expected = cellData ? input->GetNumberOfCells() : input->GetNumberOfPoints();
  if (array && array->GetNumberOfTuples() == expected)
  {
    return array;
  }
  error = std::string("Array '") + (selected->GetName() ? selected->GetName() : "(unnamed)") + "' has " +
    std::to_string(array ? array->GetNumberOfTuples() : 0) + " tuples, the mesh has " + std::to_string(expected) +
    (cellData ? " cells." : " points.");
  return nullptr;
}

/// Why a cell array on `cells` polygons that are not triangles (or strips) is refused.
std::string NotOnTrianglesError(vtkDataArray* selected, vtkIdType cells)
{
  return std::string("Cell array '") + (selected->GetName() ? selected->GetName() : "(unnamed)") + "' lives on " +
    std::to_string(cells) +
    " polygons with more than 3 points or triangle strips: cell data is only filtered on triangles. Triangulate "
    "the mesh first (vtkTriangleFilter, or ParaView's Triangulate filter).";
}

/// A blanked sample's row and its own values.
using HiddenSample = std::pair<vtkIdType, std::vector<double>>;

/**
 * Blanked samples (vtkGhostType HIDDENPOINT, or HIDDENCELL for cell data)
 * neither feed nor receive values: NaN in `values` for the kernel (no flow,
 * never interpolated); their own values are returned for the output.
 */
std::vector<HiddenSample> HideBlankedSamples(
  vtkPolyData* input, vtkDataArray* array, bool cellData, std::vector<double>& values)
{
  std::vector<HiddenSample> hidden;
  const int components = array->GetNumberOfComponents();
  vtkUnsignedCharArray* ghosts = cellData ? input->GetCellGhostArray() : input->GetPointGhostArray();
  const int mark = cellData ? static_cast<int>(vtkDataSetAttributes::HIDDENCELL)
                            : static_cast<int>(vtkDataSetAttributes::HIDDENPOINT);
  for (vtkIdType t = 0;
       ghosts && ghosts->GetNumberOfTuples() == array->GetNumberOfTuples() && t < array->GetNumberOfTuples(); ++t)
  {
    if (ghosts->GetValue(t) & mark)
    {
      double* row = &values[static_cast<size_t>(t * components)];
      hidden.emplace_back(t, std::vector<double>(row, row + components));
      std::fill(row, row + components, std::numeric_limits<double>::quiet_NaN());
    }
  }
  return hidden;
}

/**
 * The signal the kernel sees: one value per triangle (cell data; other cells
 * keep theirs), or the point values in the mesh's numbering (`values` is
 * taken over).
 */
std::vector<double> ToMeshSignal(const ShockPolyDataInternals::PreparedMesh& prepared, bool cellData, int components,
  std::vector<double>& values, int threads)
{
  if (!cellData)
  {
    return prepared.ToMeshPoints(std::move(values), components, threads);
  }
  const std::int64_t nt = prepared.mesh.NumberOfTriangles();
  std::vector<double> signal(static_cast<size_t>(nt * components));
  for (std::int64_t f = 0; f < nt; ++f)
  {
    const double* row =
      &values[static_cast<size_t>(prepared.triangles.sourceCell[static_cast<size_t>(f)] * components)];
    std::copy(row, row + components, &signal[static_cast<size_t>(f * components)]);
  }
  return signal;
}

/**
 * The kernel's results back in the array's rows: each triangle's value into
 * its cell's row of `values` (the other cells keep theirs), or the points
 * back from the mesh's numbering.
 */
std::vector<double> FromMeshSignal(const ShockPolyDataInternals::PreparedMesh& prepared, bool cellData,
  int components, std::vector<double> filtered, std::vector<double>& values, int threads)
{
  if (!cellData)
  {
    return prepared.FromMeshPoints(std::move(filtered), components, threads);
  }
  for (std::int64_t f = 0; f < prepared.mesh.NumberOfTriangles(); ++f)
  {
    const double* row = &filtered[static_cast<size_t>(f * components)];
    std::copy(row, row + components,
      &values[static_cast<size_t>(prepared.triangles.sourceCell[static_cast<size_t>(f)] * components)]);
  }
  return std::move(values);
}
}

bool vtkPolyDataShockAdvectionFilter::FilterSurface(vtkPolyData* input, vtkDataArray* selected, int association,
  vtkPolyData* output, double unit, ShockPolyDataInternals::PieceReach* reach)
{
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  std::string error;
  vtkDataArray* array = PieceArray(input, selected, cellData, error);
  if (!array)
  {
    vtkErrorMacro(<< error);
    return false;
  }
  // The mesh as prepared for the last execution, unless the points or cells changed.
  const ShockPolyDataInternals::PreparedMesh* prepared =
    this->PreparedMeshes->Get(input, false, this->NumberOfThreads, error, &this->LastSetupSeconds, unit, true);
  if (!prepared || (cellData && prepared->triangles.nonTriangleCells > 0))
  {
    vtkErrorMacro(<< (prepared ? NotOnTrianglesError(selected, prepared->triangles.nonTriangleCells) : error));
    return false;
  }
  const ShockPolyDataInternals::Triangles& triangles = prepared->triangles;
  const shock::TriangleMesh& mesh = prepared->mesh;

  // Everything checked: the output starts as the input, arrays shared.
  output->ShallowCopy(input);
  if (mesh.NumberOfTriangles() == 0)
  {
    vtkWarningMacro("The mesh has no polygons: nothing to filter.");
    return true;
  }

  const int components = array->GetNumberOfComponents();
  std::vector<double> values(static_cast<size_t>(array->GetNumberOfValues()));
  ShockFilterInternals::ToDoubles(
    array, values.data(), shock::ThreadsForWork(this->NumberOfThreads, array->GetNumberOfTuples()));
  const std::vector<HiddenSample> hidden = HideBlankedSamples(input, array, cellData, values);
  std::vector<double> signal = ToMeshSignal(*prepared, cellData, components, values, this->NumberOfThreads);
  shock::MeshSignal meshSignal;
  meshSignal.location = cellData ? shock::MeshLocation::Triangles : shock::MeshLocation::Points;
  meshSignal.components = components;
  meshSignal.values = signal.data();
  meshSignal.valueScale = this->ParallelValueScale; // 0 (own range) unless a parallel piece
  meshSignal.lengthScale = this->ParallelLengthScale; // likewise for the mean edge length
  meshSignal.wholeTriangles = static_cast<std::int64_t>(this->ParallelTriangles); // and the trace cap
  // A piece with ghost rings: each triangle's ring, so that the run reports how deep its own flow lines read.
  std::vector<unsigned char> triangleRing;
  if (reach && reach->cellRing)
  {
    triangleRing.resize(static_cast<size_t>(mesh.NumberOfTriangles()));
    for (std::int64_t f = 0; f < mesh.NumberOfTriangles(); ++f)
    {
      const vtkIdType cell = triangles.sourceCell[static_cast<size_t>(f)];
      triangleRing[static_cast<size_t>(f)] = cell < static_cast<vtkIdType>(reach->cellRing->size())
        ? (*reach->cellRing)[static_cast<size_t>(cell)]
        : std::numeric_limits<unsigned char>::max();
    }
    meshSignal.triangleRing = triangleRing.data();
  }
  const shock::AdvectionParameters parameters = ShockFilterInternals::MakeParameters(this);
  std::vector<double> filtered(signal.size());
  shock::AdvectionReport report;
  shock::MeshFlowFields fields;
  const shock::Status status = shock::AdvectMeshSignal(mesh, meshSignal, filtered.data(), parameters, &report,
    this->GenerateFlowArrays ? &fields : nullptr,
    [this](double fraction) { return this->ReportProgress(fraction, "tracing the flow lines on the surface"); });
  if (!status.Ok())
  {
    vtkErrorMacro("Shock filter failed: " << status.error);
    return false;
  }
  if (reach)
  {
    reach->deepest = report.deepestRing;
    reach->stencil = shock::MeshStencilRings(meshSignal, parameters);
    reach->aborted = report.aborted;
  }
  this->RecordRun(report.flowSeconds, report.advectionSeconds, report.traceSteps, report.truncatedTraces);
  if (report.aborted)
  {
    return true; // aborted: the output holds the unfiltered input
  }
  filtered = FromMeshSignal(*prepared, cellData, components, std::move(filtered), values, this->NumberOfThreads);
  for (const auto& sample : hidden)
  {
    std::copy(sample.second.begin(), sample.second.end(), &filtered[static_cast<size_t>(sample.first * components)]);
  }
  vtkDataSetAttributes* attributes =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetCellData()) : output->GetPointData();
  ShockFilterInternals::ReplaceArray(
    attributes, array, ShockFilterInternals::FromDoubles(array, filtered.data(),
      shock::ThreadsForWork(this->NumberOfThreads, array->GetNumberOfTuples())));
  if (this->GenerateFlowArrays)
  {
    fields.potential = prepared->FromMeshPoints(std::move(fields.potential), 1, this->NumberOfThreads);
    ShockPolyDataInternals::AttachFlowArrays(output, output->GetNumberOfCells(), mesh, triangles, fields);
  }
  return true;
}

bool vtkPolyDataShockAdvectionFilter::LocalValueRange(
  vtkInformationVector** inputVector, double range[2])
{
  int association = -1;
  vtkDataArray* array = this->FindArrayToFilter(inputVector, association);
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
  vtkUnsignedCharArray* ghosts = input->GetCellGhostArray();
  for (vtkIdType c = 0; c < cells; ++c)
  {
    if (ghosts && ghosts->GetNumberOfTuples() > c && (ghosts->GetValue(c) & vtkDataSetAttributes::HIDDENCELL))
    {
      continue; // blanked: no part in the range, as in the kernel
    }
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
  os << indent << "NumberOfMeshPreparations: " << this->GetNumberOfMeshPreparations() << "\n";
  os << indent << "LastGhostLevels: " << this->LastGhostLevels << "\n";
  os << indent << "LastRingAttempts: " << this->LastRingAttempts << "\n";
}
