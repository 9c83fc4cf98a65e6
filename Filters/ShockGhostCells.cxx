/**
 * @file ShockGhostCells.cxx
 * @brief ShockParallel::WithGhostCells: a surface piece with rings of its
 * neighbours' cells, in the four steps of ShockGhostCells.h; step 4, the
 * assembly of the piece with its rings, is here.
 */
#include "ShockGhostCells.h"
#include "ShockParallel.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace ShockParallel
{
namespace
{
using ghost::Cells;
using ghost::Numbering;
using ghost::Rings;

/**
 * `to` holds `from`'s arrays (attributes kept) with `total` tuples: rows
 * [0, leading) are `from`'s first rows; any other row r comes from
 * rowOf(r) = (array holder, row), or `from`'s row when the holder is null.
 * Returns false when a holder lacks an array of `from` (name, type and
 * components).
 */
template <typename RowOf>
bool ExtendAttributes(vtkDataSetAttributes* to, vtkDataSetAttributes* from, vtkIdType total, vtkIdType leading,
  RowOf rowOf)
{
  to->ShallowCopy(from); // the attribute roles; each named array is replaced below
  for (int k = 0; k < from->GetNumberOfArrays(); ++k)
  {
    const char* name = from->GetArrayName(k);
    vtkAbstractArray* source = from->GetAbstractArray(k);
    if (!name || !source)
    {
      continue; // unnamed arrays are refused before the rings are built
    }
    auto target = vtk::TakeSmartPointer(source->NewInstance());
    target->SetName(name);
    target->SetNumberOfComponents(source->GetNumberOfComponents());
    target->CopyComponentNames(source);
    target->CopyInformation(source->GetInformation(), 1);
    target->SetNumberOfTuples(total);
    ghost::CopyRowBlock(target, 0, source, 0, std::min(leading, source->GetNumberOfTuples()));
    vtkDataSetAttributes* lastHolder = nullptr; // rows come packet by packet: one lookup per packet
    vtkAbstractArray* other = nullptr;
    for (vtkIdType r = leading; r < total; ++r)
    {
      vtkDataSetAttributes* holder = nullptr;
      vtkIdType row = -1;
      rowOf(r, holder, row);
      if (!holder)
      {
        if (row >= 0 && row < source->GetNumberOfTuples())
        {
          target->SetTuple(r, row, source);
        }
        continue;
      }
      if (holder != lastHolder)
      {
        lastHolder = holder;
        other = holder->GetAbstractArray(name);
        if (!other || other->GetDataType() != source->GetDataType() ||
          other->GetNumberOfComponents() != source->GetNumberOfComponents())
        {
          return false;
        }
      }
      target->SetTuple(r, row, other);
    }
    to->AddArray(target); // same name: replaced at its index, its attribute role kept
  }
  return true;
}

/**
 * The points of the piece with its rings: own points then ghost points, with
 * the point data, the global ids, and DUPLICATEPOINT on every point this
 * process does not own. False when a packet lacks a point array of the piece.
 */
bool AssemblePoints(vtkPolyData* piece, const Numbering& n, const Rings& rings, vtkPolyData* result)
{
  const vtkIdType np = n.np;
  const vtkIdType total = np + static_cast<vtkIdType>(rings.ghostPoints.size());
  vtkNew<vtkPoints> points;
  points->SetDataType(piece->GetPoints()->GetDataType());
  points->SetNumberOfPoints(total);
  ghost::CopyRowBlock(points->GetData(), 0, piece->GetPoints()->GetData(), 0, np);
  for (size_t g = 0; g < rings.ghostPoints.size(); ++g)
  {
    const Rings::Row& from = rings.ghostPoints[g];
    points->GetData()->SetTuple(np + static_cast<vtkIdType>(g), from.row,
      rings.packets[static_cast<size_t>(from.packet)]->GetPoints()->GetData());
  }
  result->SetPoints(points);
  // Point data: the piece's arrays, then the ghost points' rows of the same arrays.
  vtkPointData* pointData = result->GetPointData();
  const bool complete = ExtendAttributes(pointData, piece->GetPointData(), total, np,
    [&](vtkIdType r, vtkDataSetAttributes*& holder, vtkIdType& row) {
      const Rings::Row& ghostRow = rings.ghostPoints[static_cast<size_t>(r - np)];
      holder = rings.packets[static_cast<size_t>(ghostRow.packet)]->GetPointData();
      row = ghostRow.row;
    });
  // Blanked points (HIDDENPOINT) keep their mark; the rest is the owners' marks below.
  auto* givenGhosts = vtkUnsignedCharArray::SafeDownCast(pointData->GetArray(vtkDataSetAttributes::GhostArrayName()));
  std::vector<unsigned char> hiddenPoints(static_cast<size_t>(total), 0);
  for (vtkIdType p = 0; givenGhosts && givenGhosts->GetNumberOfTuples() == total && p < total; ++p)
  {
    hiddenPoints[static_cast<size_t>(p)] = givenGhosts->GetValue(p) & vtkDataSetAttributes::HIDDENPOINT;
  }
  pointData->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("vtkShockGlobalPointIds"); // a name no user array is likely to have
  ids->SetNumberOfTuples(total);
  vtkNew<vtkUnsignedCharArray> pointGhosts;
  pointGhosts->SetName(vtkDataSetAttributes::GhostArrayName());
  pointGhosts->SetNumberOfTuples(total);
  for (vtkIdType p = 0; p < total; ++p)
  {
    // A point no cell uses stays its piece's own (it is no other piece's).
    const bool owned = p < np && n.ownerOf[static_cast<size_t>(p)] == n.me;
    ids->SetValue(p, p < np ? n.gid[static_cast<size_t>(p)] : rings.ghostPointIds[static_cast<size_t>(p - np)]);
    pointGhosts->SetValue(p, static_cast<unsigned char>(
      (owned ? 0 : vtkDataSetAttributes::DUPLICATEPOINT) | hiddenPoints[static_cast<size_t>(p)]));
  }
  if (n.givenIds && n.givenIds->GetName())
  {
    pointData->RemoveArray(n.givenIds->GetName()); // replaced by the same ids of every point
    ids->SetName(n.givenIds->GetName());
  }
  pointData->SetGlobalIds(ids);
  pointData->AddArray(pointGhosts);
  return complete;
}

/// Offsets and connectivity of `kind`'s cells (own first, then ghost) in arrays of `Array` (32- or 64-bit ids).
template <typename Array>
vtkSmartPointer<vtkCellArray> FillKind(unsigned char kind, const Cells& own, const Cells& ghost, vtkIdType cells,
  vtkIdType ids, std::vector<std::pair<int, vtkIdType>>& order)
{
  using Id = typename Array::ValueType;
  vtkNew<Array> offsets, connectivity;
  offsets->SetNumberOfTuples(cells + 1);
  connectivity->SetNumberOfTuples(ids);
  Id* offset = offsets->GetPointer(0);
  Id* to = connectivity->GetPointer(0);
  *offset = 0;
  for (int which = 0; which < 2; ++which)
  {
    const Cells& from = which == 0 ? own : ghost;
    for (vtkIdType c = 0; c < from.Size(); ++c)
    {
      if (from.kind[static_cast<size_t>(c)] != kind)
      {
        continue;
      }
      const vtkIdType* begin = &from.points[static_cast<size_t>(from.offsets[static_cast<size_t>(c)])];
      const vtkIdType* end = from.points.data() + from.offsets[static_cast<size_t>(c) + 1];
      for (const vtkIdType* p = begin; p < end; ++p)
      {
        *to++ = static_cast<Id>(*p);
      }
      offset[1] = static_cast<Id>(offset[0] + (end - begin));
      ++offset;
      order.emplace_back(which, c);
    }
  }
  auto array = vtkSmartPointer<vtkCellArray>::New();
  array->SetData(offsets, connectivity);
  return array;
}

/**
 * The cells of kind `kind` (0 verts .. 3 strips) of `own` then `ghost`, as
 * one cell array filled as offsets and connectivity (not a call per cell);
 * `order` gets (0 own / 1 ghost, index) of each, in that order. Stored with
 * 32-bit ids when the piece's points and the kind's ids allow (`points`: the
 * assembled piece's point count): half the memory of 64-bit ids, which the
 * piece holds until its output is made.
 */
vtkSmartPointer<vtkCellArray> KindCells(unsigned char kind, const Cells& own, const Cells& ghost,
  vtkIdType points, std::vector<std::pair<int, vtkIdType>>& order)
{
  vtkIdType cells = 0, ids = 0;
  for (const Cells* from : { &own, &ghost })
  {
    for (vtkIdType c = 0; c < from->Size(); ++c)
    {
      if (from->kind[static_cast<size_t>(c)] == kind)
      {
        ++cells;
        ids += from->offsets[static_cast<size_t>(c) + 1] - from->offsets[static_cast<size_t>(c)];
      }
    }
  }
  const vtkIdType limit = std::numeric_limits<vtkTypeInt32>::max();
  return points < limit && ids < limit ? FillKind<vtkTypeInt32Array>(kind, own, ghost, cells, ids, order)
                                       : FillKind<vtkTypeInt64Array>(kind, own, ghost, cells, ids, order);
}

/**
 * The cells of the piece with its rings, kind by kind, own then ghost, with
 * the cell data in that order and DUPLICATECELL on the ghost cells (and, when
 * asked, each cell's ring: 0 for the own cells). False when a packet lacks a
 * cell array of the piece.
 */
bool AssembleCells(vtkPolyData* piece, const Numbering& n, const Rings& rings, vtkPolyData* result,
  std::vector<unsigned char>* cellRings)
{
  std::vector<std::pair<int, vtkIdType>> order; // (0 own / 1 ghost, index)
  order.reserve(static_cast<size_t>(n.own.Size() + rings.ghost.Size()));
  vtkSmartPointer<vtkCellArray> kindCells[4];
  for (unsigned char kind = 0; kind < 4; ++kind)
  {
    kindCells[kind] = KindCells(kind, n.own, rings.ghost, result->GetNumberOfPoints(), order);
  }
  result->SetVerts(kindCells[0]);
  result->SetLines(kindCells[1]);
  result->SetPolys(kindCells[2]);
  result->SetStrips(kindCells[3]);
  const vtkIdType cellTotal = static_cast<vtkIdType>(order.size());
  // Own cells keep their numbers when their kinds come in order (e.g. polygons only).
  vtkIdType leadingCells = 0;
  while (leadingCells < cellTotal && order[static_cast<size_t>(leadingCells)].first == 0 &&
    order[static_cast<size_t>(leadingCells)].second == leadingCells)
  {
    ++leadingCells;
  }
  const bool complete = ExtendAttributes(result->GetCellData(), piece->GetCellData(), cellTotal, leadingCells,
    [&](vtkIdType c, vtkDataSetAttributes*& holder, vtkIdType& row) {
      const auto& entry = order[static_cast<size_t>(c)];
      if (entry.first == 0)
      {
        row = entry.second;
        return;
      }
      const Rings::Row& ghostRow = rings.ghostCellRows[static_cast<size_t>(entry.second)];
      holder = rings.packets[static_cast<size_t>(ghostRow.packet)]->GetCellData();
      row = ghostRow.row;
    });
  vtkCellData* cellData = result->GetCellData();
  auto* givenCellGhosts = vtkUnsignedCharArray::SafeDownCast(cellData->GetArray(vtkDataSetAttributes::GhostArrayName()));
  vtkNew<vtkUnsignedCharArray> cellGhosts;
  cellGhosts->SetName(vtkDataSetAttributes::GhostArrayName());
  cellGhosts->SetNumberOfTuples(cellTotal);
  for (vtkIdType c = 0; c < cellTotal; ++c)
  {
    const unsigned char hiddenCell = givenCellGhosts && givenCellGhosts->GetNumberOfTuples() == cellTotal
      ? givenCellGhosts->GetValue(c) & vtkDataSetAttributes::HIDDENCELL
      : 0; // blanked cells keep their mark
    cellGhosts->SetValue(c, static_cast<unsigned char>(
      (order[static_cast<size_t>(c)].first == 0 ? 0 : vtkDataSetAttributes::DUPLICATECELL) | hiddenCell));
  }
  cellData->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  cellData->AddArray(cellGhosts);
  if (cellRings)
  {
    cellRings->resize(static_cast<size_t>(cellTotal));
    for (vtkIdType c = 0; c < cellTotal; ++c)
    {
      const auto& entry = order[static_cast<size_t>(c)];
      (*cellRings)[static_cast<size_t>(c)] =
        entry.first == 0 ? 0 : rings.ghostCellRing[static_cast<size_t>(entry.second)];
    }
  }
  return complete;
}
}

vtkSmartPointer<vtkPolyData> WithGhostCells(vtkMultiProcessController* controller, vtkPolyData* piece, int layers,
  std::string& error, std::vector<unsigned char>* cellRings)
{
  vtkNew<vtkPolyData> emptyPiece;
  if (!piece->GetPoints())
  {
    // An empty piece: no points object at all.
    vtkNew<vtkPoints> none;
    emptyPiece->SetPoints(none);
    piece = emptyPiece;
  }
  Numbering numbering;
  if (!ghost::NumberPoints(controller, piece, numbering, error))
  {
    return nullptr;
  }
  Rings rings;
  {
    vtkLogScopeF(TRACE, "shock: rings");
    ghost::GrowRings(controller, piece, layers, numbering, rings);
  }
  vtkLogScopeF(TRACE, "shock: assemble the piece with its rings");
  auto result = vtkSmartPointer<vtkPolyData>::New();
  const bool pointsComplete = AssemblePoints(piece, numbering, rings, result);
  const bool cellsComplete = AssembleCells(piece, numbering, rings, result, cellRings);
  result->GetFieldData()->ShallowCopy(piece->GetFieldData());
  const bool missing = !pointsComplete || !cellsComplete;
  if (missing)
  {
    error = "the pieces' point or cell arrays differ (names, types or components)";
  }
  if (AnyFailed(controller, missing, error))
  {
    return nullptr;
  }
  return result;
}

namespace ghost
{
void CopyRowBlock(vtkAbstractArray* to, vtkIdType toRow, vtkAbstractArray* from, vtkIdType fromRow, vtkIdType count)
{
  auto* target = vtkDataArray::SafeDownCast(to);
  auto* source = vtkDataArray::SafeDownCast(from);
  if (count <= 0)
  {
    return;
  }
  if (target && source && target->HasStandardMemoryLayout() && source->HasStandardMemoryLayout() &&
    target->GetDataType() == source->GetDataType() && source->GetDataTypeSize() > 0 && // not bits
    target->GetDataType() != VTK_BIT && target->GetNumberOfComponents() == source->GetNumberOfComponents())
  {
    const size_t row = static_cast<size_t>(source->GetNumberOfComponents()) *
      static_cast<size_t>(source->GetDataTypeSize());
    std::memcpy(static_cast<char*>(target->GetVoidPointer(0)) + row * static_cast<size_t>(toRow),
      static_cast<const char*>(source->GetVoidPointer(0)) + row * static_cast<size_t>(fromRow),
      row * static_cast<size_t>(count));
    return;
  }
  to->InsertTuples(toRow, count, fromRow, from);
}
}
}
