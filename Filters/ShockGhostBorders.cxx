/**
 * @file ShockGhostBorders.cxx
 * @brief The piece's own cells and point links, and step 1's border test of
 * the ghost rings (ShockGhostCells.h): which points another piece may share.
 */
#include "ShockGhostCells.h"

#include "vtkCellArray.h"
#include "vtkPolyData.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include <algorithm>

namespace ShockParallel
{
namespace ghost
{
namespace
{
/// The offsets and connectivity of `cells` appended to `to` as cells of kind `k`.
template <typename Offset>
void AppendKind(unsigned char k, vtkIdType n, const Offset* offsets, const Offset* connectivity, Cells& to)
{
  const vtkIdType base = static_cast<vtkIdType>(to.points.size());
  to.kind.insert(to.kind.end(), static_cast<size_t>(n), k);
  for (vtkIdType c = 1; c <= n; ++c)
  {
    to.offsets.push_back(base + static_cast<vtkIdType>(offsets[c]));
  }
  to.points.insert(to.points.end(), connectivity, connectivity + offsets[n]);
}

/**
 * Calls edge(a, b) for every side of the polygons (a, b consecutive around
 * the loop, the last with the first) and of the strips' triangles, and
 * loose(p) for every point of a vertex or line cell and of a polygon or
 * strip with fewer than 3 points.
 */
template <typename Edge, typename Loose>
void ForEachSide(const Cells& cells, Edge edge, Loose loose)
{
  for (vtkIdType c = 0; c < cells.Size(); ++c)
  {
    const vtkIdType* ids = &cells.points[static_cast<size_t>(cells.offsets[static_cast<size_t>(c)])];
    const vtkIdType n = cells.offsets[static_cast<size_t>(c) + 1] - cells.offsets[static_cast<size_t>(c)];
    const unsigned char kind = cells.kind[static_cast<size_t>(c)];
    if (kind < 2 || n < 3)
    {
      std::for_each(ids, ids + n, loose);
    }
    else if (kind == 2) // polygon: its loop
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        edge(ids[i], ids[i + 1 == n ? 0 : i + 1]);
      }
    }
    else // strip: the sides of the triangles (j, j+1, j+2)
    {
      for (vtkIdType j = 0; j + 2 < n; ++j)
      {
        edge(ids[j], ids[j + 1]);
        edge(ids[j + 1], ids[j + 2]);
        edge(ids[j], ids[j + 2]);
      }
    }
  }
}

}

/**
 * The points another piece may share, ascending: those on a vertex or line
 * cell (or a polygon or strip of fewer than 3 points), and both ends of every
 * edge that exactly one side of the polygons and strip triangles has (an
 * edge used twice or more is inside the piece; an edge from a point to
 * itself is no edge). The edges are bucketed by their lower point (a counting
 * sort over the cells in order), so that each bucket's few entries are
 * counted where they lie together instead of walking every point's cells.
 */
std::vector<vtkIdType> BorderPoints(const Cells& cells, vtkIdType np)
{
  std::vector<char> onBorder(static_cast<size_t>(np), 0);
  std::vector<vtkIdType> start(static_cast<size_t>(np) + 1, 0);
  const auto none = [](vtkIdType) {};
  ForEachSide(
    cells,
    [&](vtkIdType a, vtkIdType b) {
      if (a != b)
      {
        ++start[static_cast<size_t>(std::min(a, b)) + 1];
      }
    },
    [&](vtkIdType p) { onBorder[static_cast<size_t>(p)] = 1; });
  for (size_t p = 0; p < static_cast<size_t>(np); ++p)
  {
    start[p + 1] += start[p];
  }
  std::vector<vtkIdType> higher(static_cast<size_t>(start.back()));
  std::vector<vtkIdType> fill(start.begin(), start.end() - 1);
  ForEachSide(
    cells,
    [&](vtkIdType a, vtkIdType b) {
      if (a != b)
      {
        higher[static_cast<size_t>(fill[static_cast<size_t>(std::min(a, b))]++)] = std::max(a, b);
      }
    },
    none);
  for (size_t p = 0; p < static_cast<size_t>(np); ++p)
  {
    vtkIdType* first = higher.data() + start[p];
    vtkIdType* last = higher.data() + start[p + 1];
    for (vtkIdType* i = first + 1; i < last; ++i) // a few entries: insertion sort
    {
      const vtkIdType value = *i;
      vtkIdType* j = i;
      for (; j > first && *(j - 1) > value; --j)
      {
        *j = *(j - 1);
      }
      *j = value;
    }
    for (vtkIdType* k = first; k < last;)
    {
      vtkIdType* end = k + 1;
      while (end < last && *end == *k)
      {
        ++end;
      }
      if (end - k == 1) // an edge of one side only
      {
        onBorder[p] = 1;
        onBorder[static_cast<size_t>(*k)] = 1;
      }
      k = end;
    }
  }
  std::vector<vtkIdType> border;
  for (vtkIdType p = 0; p < np; ++p)
  {
    if (onBorder[static_cast<size_t>(p)])
    {
      border.push_back(p);
    }
  }
  return border;
}

std::vector<vtkIdType> LoosePoints(const Cells& cells, vtkIdType np)
{
  std::vector<char> loose(static_cast<size_t>(np), 0);
  ForEachSide(
    cells, [](vtkIdType, vtkIdType) {}, [&](vtkIdType p) { loose[static_cast<size_t>(p)] = 1; });
  std::vector<vtkIdType> points;
  for (vtkIdType p = 0; p < np; ++p)
  {
    if (loose[static_cast<size_t>(p)])
    {
      points.push_back(p);
    }
  }
  return points;
}

Cells ReadCells(vtkPolyData* piece)
{
  Cells cells;
  vtkCellArray* arrays[4] = { piece->GetVerts(), piece->GetLines(), piece->GetPolys(), piece->GetStrips() };
  size_t size = 0, count = 0;
  for (vtkCellArray* array : arrays)
  {
    size += array ? static_cast<size_t>(array->GetNumberOfConnectivityIds()) : 0;
    count += array ? static_cast<size_t>(array->GetNumberOfCells()) : 0;
  }
  cells.kind.reserve(count);
  cells.offsets.reserve(count + 1);
  cells.points.reserve(size);
  for (unsigned char k = 0; k < 4; ++k)
  {
    vtkCellArray* array = arrays[k];
    const vtkIdType n = array ? array->GetNumberOfCells() : 0;
    if (n == 0)
    {
      continue;
    }
    // The cell array's own offsets and connectivity, read in place.
    if (array->IsStorage64Bit())
    {
      AppendKind(k, n, array->GetOffsetsArray64()->GetPointer(0), array->GetConnectivityArray64()->GetPointer(0),
        cells);
    }
    else
    {
      AppendKind(k, n, array->GetOffsetsArray32()->GetPointer(0), array->GetConnectivityArray32()->GetPointer(0),
        cells);
    }
  }
  return cells;
}

/// Point -> cells (CSR) of `cells` over `np` points.
void PointLinks(const Cells& cells, vtkIdType np, std::vector<vtkIdType>& start, std::vector<vtkIdType>& list)
{
  start.assign(static_cast<size_t>(np) + 1, 0);
  for (vtkIdType p : cells.points)
  {
    ++start[static_cast<size_t>(p) + 1];
  }
  for (size_t p = 0; p < static_cast<size_t>(np); ++p)
  {
    start[p + 1] += start[p];
  }
  list.resize(cells.points.size());
  std::vector<vtkIdType> fill(start.begin(), start.end() - 1);
  for (vtkIdType c = 0; c < cells.Size(); ++c)
  {
    for (vtkIdType k = cells.offsets[static_cast<size_t>(c)]; k < cells.offsets[static_cast<size_t>(c) + 1]; ++k)
    {
      list[static_cast<size_t>(fill[static_cast<size_t>(cells.points[static_cast<size_t>(k)])]++)] = c;
    }
  }
}
}
}
