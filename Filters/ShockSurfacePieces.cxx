/**
 * @file ShockSurfacePieces.cxx
 * @brief A surface piece's own cells (OwnedCells) and the output of its own
 * cells after filtering with ghost cells (OwnedPiece).
 */
#include "ShockGhostCells.h"
#include "ShockParallel.h"

#include "vtkAlgorithm.h"
#include "vtkAbstractArray.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkLogger.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

namespace ShockParallel
{
namespace
{
/// The cells of one kind that are not marked DUPLICATECELL, as offsets and connectivity (input point ids).
struct KindCells
{
  std::vector<vtkIdType> offsets{ 0 };
  std::vector<vtkIdType> connectivity;
};

/**
 * Calls visit(cell number, ghost, size, points) for every cell of `piece`,
 * kind by kind (vtkPolyData numbers verts, lines, polygons, strips in turn).
 */
template <typename Visit>
void ForEachCell(vtkPolyData* piece, vtkUnsignedCharArray* ghosts, Visit visit)
{
  vtkCellArray* inputCells[4] = { piece->GetVerts(), piece->GetLines(), piece->GetPolys(), piece->GetStrips() };
  vtkIdType cell = 0;
  for (int kind = 0; kind < 4; ++kind)
  {
    if (!inputCells[kind])
    {
      continue;
    }
    auto iterator = vtk::TakeSmartPointer(inputCells[kind]->NewIterator());
    for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++cell)
    {
      vtkIdType size;
      const vtkIdType* points;
      iterator->GetCurrentCell(size, points);
      visit(kind, cell, (ghosts->GetValue(cell) & vtkDataSetAttributes::DUPLICATECELL) != 0, size, points);
    }
  }
}

/**
 * The points the own cells keep: those they use, with the points no cell
 * uses (nobody else's), in their order; `newId` maps each kept point to its
 * row in the result (others -1).
 */
vtkSmartPointer<vtkIdList> KeptPoints(vtkPolyData* piece, vtkUnsignedCharArray* ghosts, std::vector<vtkIdType>& newId)
{
  std::vector<char> usedByOwn(static_cast<size_t>(piece->GetNumberOfPoints()), 0);
  std::vector<char> usedByGhost(usedByOwn.size(), 0);
  ForEachCell(piece, ghosts, [&](int, vtkIdType, bool ghost, vtkIdType size, const vtkIdType* points) {
    std::vector<char>& used = ghost ? usedByGhost : usedByOwn;
    for (vtkIdType k = 0; k < size; ++k)
    {
      used[static_cast<size_t>(points[k])] = 1;
    }
  });
  auto kept = vtkSmartPointer<vtkIdList>::New();
  newId.assign(usedByOwn.size(), -1);
  for (size_t p = 0; p < usedByOwn.size(); ++p)
  {
    if (usedByOwn[p] || !usedByGhost[p])
    {
      newId[p] = kept->GetNumberOfIds();
      kept->InsertNextId(static_cast<vtkIdType>(p));
    }
  }
  return kept;
}

/// `cells` of kind `kind` (0 verts .. 3 strips) renumbered by `newId`, set on `owned`.
void SetKindCells(vtkPolyData* owned, int kind, const KindCells& cells, const std::vector<vtkIdType>& newId)
{
  vtkNew<vtkIdTypeArray> offsetArray, connectivityArray;
  offsetArray->SetNumberOfTuples(static_cast<vtkIdType>(cells.offsets.size()));
  std::copy(cells.offsets.begin(), cells.offsets.end(), offsetArray->GetPointer(0));
  connectivityArray->SetNumberOfTuples(static_cast<vtkIdType>(cells.connectivity.size()));
  vtkIdType* to = connectivityArray->GetPointer(0);
  for (vtkIdType p : cells.connectivity)
  {
    *to++ = newId[static_cast<size_t>(p)];
  }
  vtkNew<vtkCellArray> array;
  array->SetData(offsetArray, connectivityArray);
  switch (kind)
  {
    case 0: owned->SetVerts(array); break;
    case 1: owned->SetLines(array); break;
    case 2: owned->SetPolys(array); break;
    default: owned->SetStrips(array); break;
  }
}

}

vtkSmartPointer<vtkIdList> Sequence(vtkIdType n)
{
  auto ids = vtkSmartPointer<vtkIdList>::New();
  ids->SetNumberOfIds(n);
  for (vtkIdType k = 0; k < n; ++k)
  {
    ids->SetId(k, k);
  }
  return ids;
}

vtkSmartPointer<vtkPolyData> OwnedCells(vtkPolyData* piece)
{
  vtkUnsignedCharArray* ghosts = piece->GetCellGhostArray();
  if (!ghosts || !piece->GetPoints() || ghosts->GetNumberOfTuples() < piece->GetNumberOfCells())
  {
    return piece;
  }
  // The own cells, kind by kind, and the points they keep.
  KindCells cells[4];
  vtkNew<vtkIdList> keptCells;
  ForEachCell(piece, ghosts, [&](int kind, vtkIdType cell, bool ghost, vtkIdType size, const vtkIdType* points) {
    if (!ghost)
    {
      cells[kind].connectivity.insert(cells[kind].connectivity.end(), points, points + size);
      cells[kind].offsets.push_back(static_cast<vtkIdType>(cells[kind].connectivity.size()));
      keptCells->InsertNextId(cell);
    }
  });
  std::vector<vtkIdType> newId;
  const vtkSmartPointer<vtkIdList> keptPoints = KeptPoints(piece, ghosts, newId);
  auto owned = vtkSmartPointer<vtkPolyData>::New();
  for (int kind = 0; kind < 4; ++kind)
  {
    SetKindCells(owned, kind, cells[kind], newId);
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(piece->GetPoints()->GetDataType());
  piece->GetPoints()->GetPoints(keptPoints, points);
  owned->SetPoints(points);
  owned->GetFieldData()->ShallowCopy(piece->GetFieldData());
  // Their data (with the owners' marks): each array's rows in one call (not one call per row).
  owned->GetPointData()->CopyGlobalIdsOn(); // CopyAllocate leaves them out otherwise
  owned->GetCellData()->CopyGlobalIdsOn();
  owned->GetPointData()->CopyAllocate(piece->GetPointData(), keptPoints->GetNumberOfIds());
  owned->GetPointData()->CopyData(piece->GetPointData(), keptPoints, Sequence(keptPoints->GetNumberOfIds()));
  owned->GetCellData()->CopyAllocate(piece->GetCellData(), keptCells->GetNumberOfIds());
  owned->GetCellData()->CopyData(piece->GetCellData(), keptCells, Sequence(keptCells->GetNumberOfIds()));
  owned->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName()); // no ghost cell left
  return owned;
}

namespace
{
/// A run of rows: `count` rows from `first`.
struct RowRun
{
  vtkIdType first;
  vtkIdType count;
};

/// `array`'s rows of `runs`, one after the other, as a new array.
vtkSmartPointer<vtkAbstractArray> Rows(vtkAbstractArray* array, const std::vector<RowRun>& runs)
{
  auto picked = vtk::TakeSmartPointer(array->NewInstance());
  picked->SetName(array->GetName());
  picked->SetNumberOfComponents(array->GetNumberOfComponents());
  picked->CopyComponentNames(array);
  vtkIdType total = 0;
  for (const RowRun& run : runs)
  {
    total += run.count;
  }
  picked->SetNumberOfTuples(total);
  vtkIdType to = 0;
  for (const RowRun& run : runs)
  {
    ghost::CopyRowBlock(picked, to, array, run.first, run.count);
    to += run.count;
  }
  return picked;
}

/**
 * `result`'s arrays (those of the owned piece) updated from `filtered`: an
 * array the filter made or replaced (not the same array in `work`) becomes
 * its rows `runs` (replacing the owned array of that name, else added), as
 * does the point ghost array (the owners' marks); the arrays the filter left
 * alone stay the owned piece's own (the same values, without a copy); the
 * attribute roles the filter changed follow it.
 */
void TakeFilteredArrays(vtkDataSetAttributes* result, vtkDataSetAttributes* filtered, vtkDataSetAttributes* work,
  const std::vector<RowRun>& runs, bool points)
{
  for (int k = 0; k < filtered->GetNumberOfArrays(); ++k)
  {
    vtkAbstractArray* array = filtered->GetAbstractArray(k);
    if (!array || !array->GetName())
    {
      continue;
    }
    const bool marks = points && std::strcmp(array->GetName(), vtkDataSetAttributes::GhostArrayName()) == 0;
    if (!marks && work->GetAbstractArray(array->GetName()) == array)
    {
      continue; // left alone by the filter: the owned piece's array (or one the rings made)
    }
    result->AddArray(Rows(array, runs)); // same name: replaced at its index
  }
  for (int a = 0; a < vtkDataSetAttributes::NUM_ATTRIBUTES; ++a)
  {
    vtkAbstractArray* role = filtered->GetAbstractAttribute(a);
    if (role == work->GetAbstractAttribute(a))
    {
      continue;
    }
    if (role && role->GetName() && result->GetAbstractArray(role->GetName()))
    {
      result->SetActiveAttribute(role->GetName(), a);
    }
    else
    {
      result->SetActiveAttribute(-1, a);
    }
  }
}
}

vtkSmartPointer<vtkPolyData> OwnedPiece(vtkPolyData* filtered, const SurfacePiece& piece)
{
  // WithGhostCells put the piece's own points first, in their order, and each
  // kind's own cells before its ghost cells: the owned piece is those rows.
  vtkPolyData* work = piece.work;
  vtkPolyData* owned = piece.owned;
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(owned); // its cells, and the arrays the filter leaves alone
  const vtkIdType np = owned->GetNumberOfPoints();
  if (filtered->GetPoints() && (piece.released || filtered->GetPoints() != work->GetPoints()))
  {
    vtkNew<vtkPoints> points;
    points->SetData(vtkDataArray::SafeDownCast(Rows(filtered->GetPoints()->GetData(), { { 0, np } })));
    result->SetPoints(points);
  }
  TakeFilteredArrays(result->GetPointData(), filtered->GetPointData(), work->GetPointData(), { { 0, np } }, true);
  vtkCellArray* ownCells[4] = { owned->GetVerts(), owned->GetLines(), owned->GetPolys(), owned->GetStrips() };
  vtkCellArray* allCells[4] = { filtered->GetVerts(), filtered->GetLines(), filtered->GetPolys(), filtered->GetStrips() };
  std::vector<RowRun> cellRows; // each kind's own cells: the leading run of its cells
  vtkIdType first = 0;
  for (int kind = 0; kind < 4; ++kind)
  {
    const vtkIdType own = ownCells[kind] ? ownCells[kind]->GetNumberOfCells() : 0;
    if (own > 0)
    {
      cellRows.push_back({ first, own });
    }
    first += piece.released ? piece.workCells[static_cast<size_t>(kind)]
                            : (allCells[kind] ? allCells[kind]->GetNumberOfCells() : 0);
  }
  TakeFilteredArrays(result->GetCellData(), filtered->GetCellData(), work->GetCellData(), cellRows, false);
  result->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName()); // no ghost cell left
  return result;
}

bool ReleaseGeometry(SurfacePiece& piece)
{
  vtkPolyData* work = piece.work;
  if (!piece.controller || !work || work == piece.owned || piece.released || !work->GetPoints())
  {
    return false; // serial, or the piece itself (WithGhostCells made no copy)
  }
  piece.workPoints = work->GetNumberOfPoints();
  piece.workPointType = work->GetPoints()->GetDataType();
  vtkCellArray* cells[4] = { work->GetVerts(), work->GetLines(), work->GetPolys(), work->GetStrips() };
  for (int kind = 0; kind < 4; ++kind)
  {
    piece.workCells[static_cast<size_t>(kind)] = cells[kind] ? cells[kind]->GetNumberOfCells() : 0;
  }
  // The copy is this filter's own object (never the input): its arrays stay.
  work->SetPoints(nullptr);
  work->SetVerts(nullptr);
  work->SetLines(nullptr);
  work->SetPolys(nullptr);
  work->SetStrips(nullptr);
  piece.released = true;
  return true;
}

vtkSmartPointer<vtkPolyData> Carrying(vtkPolyData* owned, const CarriedArrays& carried)
{
  if (carried.all)
  {
    return owned;
  }
  auto slim = vtkSmartPointer<vtkPolyData>::New();
  slim->CopyStructure(owned); // points and cells, shared
  const auto keep = [](vtkDataSetAttributes* to, vtkDataSetAttributes* from, const std::vector<std::string>& names,
                      bool points) {
    for (int k = 0; k < from->GetNumberOfArrays(); ++k)
    {
      vtkAbstractArray* array = from->GetAbstractArray(k);
      const char* name = array ? array->GetName() : nullptr;
      if (name &&
        (std::find(names.begin(), names.end(), name) != names.end() ||
          std::strcmp(name, vtkDataSetAttributes::GhostArrayName()) == 0 || // blanked samples
          (points && array == from->GetGlobalIds()))) // the given ids number the points
      {
        to->AddArray(array);
      }
    }
    for (int a = 0; a < vtkDataSetAttributes::NUM_ATTRIBUTES; ++a)
    {
      vtkAbstractArray* role = from->GetAbstractAttribute(a);
      if (role && role->GetName() && to->GetAbstractArray(role->GetName()) == role)
      {
        to->SetActiveAttribute(role->GetName(), a);
      }
    }
  };
  keep(slim->GetPointData(), owned->GetPointData(), carried.point, true);
  keep(slim->GetCellData(), owned->GetCellData(), carried.cell, false);
  return slim;
}
}
