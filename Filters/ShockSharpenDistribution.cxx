/**
 * @file ShockSharpenDistribution.cxx
 * @brief ShockParallel::Distribute (ShockSharpenDistribution.h).
 */
#include "ShockSharpenDistribution.h"

#include "MeshSharpening.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
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
#include <numeric>
#include <sstream>


namespace ShockParallel
{
void Distribute(vtkMultiProcessController* controller, vtkPolyData* piece,
  const ShockPolyDataInternals::PreparedMesh& prepared, Distribution& out)
{
  const shock::TriangleMesh& mesh = prepared.mesh;
  const std::int64_t np = mesh.NumberOfPoints();
  const std::int64_t nt = mesh.NumberOfTriangles();
  vtkUnsignedCharArray* pointGhosts = ShockParallel::PointGhosts(piece);
  vtkUnsignedCharArray* cellGhosts = piece->GetCellGhostArray();
  shock::MeshPartition& partition = out.partition;
  partition.ownedPoints.assign(static_cast<size_t>(np), 1);
  partition.ownedTriangles.assign(static_cast<size_t>(nt), 1);
  // Mesh point p is the piece's point inputPoint(p) (the mesh may be renumbered for locality).
  const auto inputPoint = [&prepared](std::int64_t p) {
    return prepared.pointOrder.empty() ? p : static_cast<std::int64_t>(prepared.pointOrder[static_cast<size_t>(p)]);
  };
  for (std::int64_t p = 0; pointGhosts && p < np; ++p)
  {
    partition.ownedPoints[static_cast<size_t>(p)] =
      (pointGhosts->GetValue(inputPoint(p)) & vtkDataSetAttributes::DUPLICATEPOINT) ? 0 : 1;
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
        prepared.triangles.points.data(), mesh.Corners(f));
      lengths[1] += 3.0;
    }
  }
  // The piece's own vertex and line cells write their points too: the owners' positions of those
  // that another piece owns (a point of a line here may lie inside the other piece's triangles).
  vtkCellArray* loose[2] = { piece->GetVerts(), piece->GetLines() };
  if ((loose[0] && loose[0]->GetNumberOfCells() > 0) || (loose[1] && loose[1]->GetNumberOfCells() > 0))
  {
    std::vector<std::int64_t> meshPoint(static_cast<size_t>(np));
    for (std::int64_t p = 0; p < np; ++p)
    {
      meshPoint[static_cast<size_t>(inputPoint(p))] = p;
    }
    vtkIdType cell = 0; // vtkPolyData numbers verts, then lines
    for (vtkCellArray* cells : loose)
    {
      if (!cells)
      {
        continue;
      }
      auto iterator = vtk::TakeSmartPointer(cells->NewIterator());
      for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++cell)
      {
        if (cellGhosts && (cellGhosts->GetValue(cell) & vtkDataSetAttributes::DUPLICATECELL))
        {
          continue;
        }
        vtkIdType size;
        const vtkIdType* ids;
        iterator->GetCurrentCell(size, ids);
        for (vtkIdType k = 0; k < size; ++k)
        {
          const size_t m = static_cast<size_t>(meshPoint[static_cast<size_t>(ids[k])]);
          needed[m] |= partition.ownedPoints[m] ? 0 : 1;
        }
      }
    }
  }
  ShockParallel::Sum(controller, lengths, 2);
  out.meanEdgeLength = lengths[1] > 0.0 ? lengths[0] / lengths[1] : 0.0;
  out.wholeTriangles = lengths[1] / 3.0;
  vtkDataArray* ids = piece->GetPointData()->GetGlobalIds();
  std::vector<vtkIdType> globalIds(static_cast<size_t>(np), -1);
  for (std::int64_t p = 0; ids && p < np; ++p)
  {
    globalIds[static_cast<size_t>(p)] = static_cast<vtkIdType>(ids->GetTuple1(inputPoint(p)));
  }
  out.exchange.Setup(controller, globalIds.data(), partition.ownedPoints, needed);
  partition.sharedPoints = out.exchange.SentMask(np);
  // What a piece costs: its ghost layers, and the traffic of one CG iteration
  // (one exchange of 3 doubles per point, two global sums of 3 and 6 doubles).
  std::int64_t ownedPoints = 0;
  for (char owned : partition.ownedPoints)
  {
    ownedPoints += owned;
  }
  vtkLogF(1,
    "vtkPolyDataShockSharpenFilter piece %d of %d: %lld points (%lld owned, %lld in ghost "
    "layers), %lld triangles; per CG iteration %lld bytes sent and %lld received point to "
    "point, 72 bytes reduced",
    controller->GetLocalProcessId(), controller->GetNumberOfProcesses(), static_cast<long long>(np),
    static_cast<long long>(ownedPoints), static_cast<long long>(np - ownedPoints),
    static_cast<long long>(nt), static_cast<long long>(24 * out.exchange.SentPoints()),
    static_cast<long long>(24 * out.exchange.ReceivedPoints()));
  partition.globalSum = [controller](double* values, int count) {
    ShockParallel::Sum(controller, values, count);
  };
  partition.exchangePoints = [&out](double* values) { out.exchange.Exchange(values); };
  partition.anyStopped = [controller](bool stopped, int) { return ShockParallel::Count(controller, stopped) > 0; };
}
}
