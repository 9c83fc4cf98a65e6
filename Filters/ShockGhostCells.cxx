/**
 * @file ShockGhostCells.cxx
 * @brief Global point ids and ghost-cell rings of a distributed surface, grown
 * with the piece's own connectivity, one exchange per ring.
 *
 * What VTK's vtkGenerateGlobalIds and vtkGhostCellsGenerator do for a
 * surface, in the steps the shock filters need, and at the cost of the
 * piece's boundary instead of its volume:
 *
 * 1. Border points. A point another piece can share lies on a border edge of
 *    this piece's own polygons (an edge of one polygon only), or on a vertex
 *    or line cell. Only those are exchanged (AllGatherV of their keys).
 * 2. Keys and global ids. The key of a point is its global id when the input
 *    has point global ids, else its coordinates (exactly coincident points of
 *    different pieces, as sources and partitioned files repeat them on the
 *    seams, are one point). A shared point is owned by the lowest process that
 *    holds it; every process numbers its owned points after those of the
 *    processes before it. Everything is computed from the gathered borders and
 *    the point counts, the same on every process.
 * 3. Rings. Ring 1 is every other process's cells that use a point of this
 *    piece's own cells; ring k the cells that use a point first received in
 *    ring k-1. Each ring: a process asks the holders of its new points (the
 *    gathered borders name them; a point not on any border has one holder,
 *    the process that sent it) for their own cells around those points, in
 *    one round of requests and one of answers (the cells with their points,
 *    point data and cell data, as vtkPolyData).
 */
#include "ShockParallel.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace ShockParallel
{
namespace
{
constexpr int RequestTag = 84661;
constexpr int AnswerTag = 84662;
const char* const PacketPointIds = "vtkShockGhostPointIds";
const char* const PacketCellIds = "vtkShockGhostCellIds";
const char* const PacketCellKinds = "vtkShockGhostCellKinds";
const char* const PacketBudgets = "vtkShockGhostBudgets";

/// The four cell arrays of a vtkPolyData, in its cell numbering order.
struct Cells
{
  std::vector<unsigned char> kind;   ///< 0 vertex, 1 line, 2 polygon, 3 strip
  std::vector<vtkIdType> offsets{ 0 }; ///< into `points`, one more than cells
  std::vector<vtkIdType> points;     ///< local point ids

  vtkIdType Size() const { return static_cast<vtkIdType>(kind.size()); }
  void Append(unsigned char k, vtkIdType n, const vtkIdType* ids)
  {
    this->kind.push_back(k);
    this->points.insert(this->points.end(), ids, ids + n);
    this->offsets.push_back(static_cast<vtkIdType>(this->points.size()));
  }
};

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

/**
 * Whether point p may be shared with another piece: it is on a vertex or line
 * cell, or on an edge that exactly one of its polygons (or strip triangles) has.
 */
bool OnBorder(const Cells& cells, const std::vector<vtkIdType>& start, const std::vector<vtkIdType>& list,
  vtkIdType p, std::vector<vtkIdType>& scratch)
{
  scratch.clear();
  for (vtkIdType k = start[static_cast<size_t>(p)]; k < start[static_cast<size_t>(p) + 1]; ++k)
  {
    const vtkIdType c = list[static_cast<size_t>(k)];
    const vtkIdType* ids = &cells.points[static_cast<size_t>(cells.offsets[static_cast<size_t>(c)])];
    const vtkIdType n = cells.offsets[static_cast<size_t>(c) + 1] - cells.offsets[static_cast<size_t>(c)];
    const unsigned char kind = cells.kind[static_cast<size_t>(c)];
    if (kind < 2 || n < 3)
    {
      return true;
    }
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (ids[i] != p)
      {
        continue;
      }
      if (kind == 2) // polygon: the neighbours along its loop
      {
        scratch.push_back(ids[i + 1 == n ? 0 : i + 1]);
        scratch.push_back(ids[i == 0 ? n - 1 : i - 1]);
      }
      else // strip: the edges of the triangles (j, j+1, j+2) that hold i
      {
        for (vtkIdType j = std::max<vtkIdType>(0, i - 2); j <= std::min(i, n - 3); ++j)
        {
          for (vtkIdType q = j; q < j + 3; ++q)
          {
            if (q != i)
            {
              scratch.push_back(ids[q]);
            }
          }
        }
      }
    }
  }
  // Few entries (two per polygon around p): an insertion sort beats std::sort here.
  if (scratch.size() > 64)
  {
    std::sort(scratch.begin(), scratch.end());
  }
  for (size_t i = 1; i < scratch.size(); ++i)
  {
    const vtkIdType value = scratch[i];
    size_t j = i;
    for (; j > 0 && scratch[j - 1] > value; --j)
    {
      scratch[j] = scratch[j - 1];
    }
    scratch[j] = value;
  }
  for (size_t k = 0; k < scratch.size();)
  {
    size_t end = k;
    while (end < scratch.size() && scratch[end] == scratch[k])
    {
      ++end;
    }
    if (end - k == 1 && scratch[k] != p)
    {
      return true;
    }
    k = end;
  }
  return false;
}

/// A point key: the global id, or the coordinates' bits.
struct Key
{
  std::uint64_t a = 0, b = 0, c = 0;
  bool operator==(const Key& o) const { return a == o.a && b == o.b && c == o.c; }
};
struct KeyHash
{
  size_t operator()(const Key& k) const
  {
    std::uint64_t h = k.a * 0x9E3779B97F4A7C15ull;
    h ^= (k.b + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2));
    h ^= (k.c + 0x8CB92BA72F3D8DD7ull + (h << 6) + (h >> 2));
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

Key CoordinateKey(const double x[3])
{
  Key key;
  // +0.0 and -0.0 are the same point.
  const double y[3] = { x[0] == 0.0 ? 0.0 : x[0], x[1] == 0.0 ? 0.0 : x[1], x[2] == 0.0 ? 0.0 : x[2] };
  std::memcpy(&key.a, &y[0], 8);
  std::memcpy(&key.b, &y[1], 8);
  std::memcpy(&key.c, &y[2], 8);
  return key;
}

/**
 * Global id -> local point of one piece: its own points (through a table over
 * the ids this process made, or a hash of the given ids) and the ghost points
 * received in the rings.
 */
class LocalPoints
{
public:
  /// The piece's points by `gid`; made ids in [first, end) are this process's
  /// (a table), any other id is hashed. False when two points share an id.
  bool Build(const std::vector<vtkIdType>& gid, bool madeIds, vtkIdType first, vtkIdType end)
  {
    this->First = madeIds ? first : 0;
    this->Table.assign(madeIds ? static_cast<size_t>(end - first) : 0, -1);
    bool unique = true;
    for (size_t p = 0; p < gid.size(); ++p)
    {
      const vtkIdType id = gid[p];
      if (madeIds && id >= first && id < end)
      {
        vtkIdType& slot = this->Table[static_cast<size_t>(id - first)];
        unique = unique && slot < 0;
        slot = static_cast<vtkIdType>(p);
      }
      else
      {
        unique = this->Others.emplace(id, static_cast<vtkIdType>(p)).second && unique;
      }
    }
    return unique;
  }
  /// The own point with global id `id`, or -1.
  vtkIdType Own(vtkIdType id) const
  {
    const vtkIdType k = id - this->First;
    if (k >= 0 && k < static_cast<vtkIdType>(this->Table.size()))
    {
      return this->Table[static_cast<size_t>(k)];
    }
    const auto found = this->Others.find(id);
    return found == this->Others.end() ? -1 : found->second;
  }
  /// The local point of `id`: an own point, a ghost point, or `next` as a new ghost point (`added`).
  vtkIdType Find(vtkIdType id, vtkIdType next, bool& added)
  {
    added = false;
    const vtkIdType own = this->Own(id);
    if (own >= 0)
    {
      return own;
    }
    const auto inserted = this->Ghosts.emplace(id, next);
    added = inserted.second;
    return inserted.first->second;
  }

private:
  vtkIdType First = 0;
  std::vector<vtkIdType> Table;
  std::unordered_map<vtkIdType, vtkIdType> Others, Ghosts;
};

/// Everyone's `mine` (`width` values per item), concatenated in process order; items per process.
template <typename T>
std::vector<T> GatherItems(vtkMultiProcessController* controller, const std::vector<T>& mine, int width,
  std::vector<vtkIdType>& items)
{
  const int processes = controller->GetNumberOfProcesses();
  std::vector<vtkIdType> counts(static_cast<size_t>(processes)), offsets(static_cast<size_t>(processes), 0);
  vtkIdType count = static_cast<vtkIdType>(mine.size());
  controller->AllGather(&count, counts.data(), 1);
  for (int r = 1; r < processes; ++r)
  {
    offsets[static_cast<size_t>(r)] = offsets[static_cast<size_t>(r - 1)] + counts[static_cast<size_t>(r - 1)];
  }
  std::vector<T> all(static_cast<size_t>(offsets.back() + counts.back()) + 1);
  controller->AllGatherV(mine.data(), all.data(), count, counts.data(), offsets.data());
  all.pop_back();
  items.resize(static_cast<size_t>(processes));
  for (int r = 0; r < processes; ++r)
  {
    items[static_cast<size_t>(r)] = counts[static_cast<size_t>(r)] / width;
  }
  return all;
}

/// The ids 0 .. n-1.
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

/// `from`'s first `count` rows into `to`'s first rows: one copy when both hold their values contiguously.
void CopyLeadingRows(vtkAbstractArray* to, vtkAbstractArray* from, vtkIdType count)
{
  auto* target = vtkDataArray::SafeDownCast(to);
  auto* source = vtkDataArray::SafeDownCast(from);
  if (count <= 0)
  {
    return;
  }
  if (target && source && target->HasStandardMemoryLayout() && source->HasStandardMemoryLayout() &&
    target->GetDataType() == source->GetDataType() && source->GetDataTypeSize() > 0 && // not bits
    target->GetDataType() != VTK_BIT &&
    target->GetNumberOfComponents() == source->GetNumberOfComponents())
  {
    std::memcpy(target->GetVoidPointer(0), source->GetVoidPointer(0),
      static_cast<size_t>(count) * static_cast<size_t>(source->GetNumberOfComponents()) *
        static_cast<size_t>(source->GetDataTypeSize()));
    return;
  }
  to->InsertTuples(0, count, 0, from);
}

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
    CopyLeadingRows(target, source, std::min(leading, source->GetNumberOfTuples()));
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

/// The keys of gathered global ids (3 words per item, the id first).
std::vector<Key> GivenKeys(const std::vector<std::uint64_t>& all)
{
  std::vector<Key> keys(all.size() / 3);
  for (size_t k = 0; k < keys.size(); ++k)
  {
    keys[k] = Key{ all[3 * k], all[3 * k + 1], all[3 * k + 2] };
  }
  return keys;
}

/**
 * The keys of gathered coordinates (3 doubles' bits per item): each item takes
 * the key of the first item (in gathered order) within `relativeTolerance` of
 * the largest coordinate magnitude in every axis, else its own. The same on
 * every process.
 */
std::vector<Key> MergedCoordinateKeys(const std::vector<std::uint64_t>& all, double relativeTolerance)
{
  const size_t n = all.size() / 3;
  std::vector<double> x(all.size());
  std::memcpy(x.data(), all.data(), 8 * all.size());
  double largest = 0.0;
  for (double v : x)
  {
    largest = std::max(largest, std::abs(v));
  }
  const double tolerance = largest > 0.0 ? relativeTolerance * largest : std::numeric_limits<double>::min();
  // Items by grid cell of the tolerance's size: a match lies in one of the 27 cells around.
  struct Cell
  {
    std::int64_t i, j, k;
    bool operator==(const Cell& o) const { return i == o.i && j == o.j && k == o.k; }
  };
  struct CellHash
  {
    size_t operator()(const Cell& c) const
    {
      return static_cast<size_t>((static_cast<std::uint64_t>(c.i) * 73856093u) ^
        (static_cast<std::uint64_t>(c.j) * 19349663u) ^ (static_cast<std::uint64_t>(c.k) * 83492791u));
    }
  };
  std::unordered_map<Cell, std::vector<size_t>, CellHash> grid;
  std::vector<Key> keys(n);
  for (size_t item = 0; item < n; ++item)
  {
    const double* p = &x[3 * item];
    const Cell cell{ static_cast<std::int64_t>(std::floor(p[0] / tolerance)),
      static_cast<std::int64_t>(std::floor(p[1] / tolerance)), static_cast<std::int64_t>(std::floor(p[2] / tolerance)) };
    size_t match = item;
    for (std::int64_t di = -1; di <= 1 && match == item; ++di)
    {
      for (std::int64_t dj = -1; dj <= 1 && match == item; ++dj)
      {
        for (std::int64_t dk = -1; dk <= 1 && match == item; ++dk)
        {
          const auto found = grid.find(Cell{ cell.i + di, cell.j + dj, cell.k + dk });
          if (found == grid.end())
          {
            continue;
          }
          for (size_t other : found->second)
          {
            const double* q = &x[3 * other];
            if (std::abs(p[0] - q[0]) <= tolerance && std::abs(p[1] - q[1]) <= tolerance &&
              std::abs(p[2] - q[2]) <= tolerance)
            {
              match = other;
              break;
            }
          }
        }
      }
    }
    if (match == item)
    {
      grid[cell].push_back(item);
      keys[item] = CoordinateKey(p);
    }
    else
    {
      keys[item] = keys[match];
    }
  }
  return keys;
}

/// The ranks that hold a border point, lowest first (the owner).
using Holders = std::vector<int>;

/**
 * Point-to-point messages in one global order of (sender, receiver) pairs, the
 * same on every process, so that blocking sends and receives cannot deadlock.
 */
template <typename SendTo, typename ReceiveFrom>
void InPairOrder(int me, int processes, const std::vector<vtkIdType>& matrix, SendTo send, ReceiveFrom receive)
{
  for (int a = 0; a < processes; ++a)
  {
    for (int b = 0; b < processes; ++b)
    {
      if (a == b || matrix[static_cast<size_t>(a * processes + b)] == 0)
      {
        continue;
      }
      if (a == me)
      {
        send(b);
      }
      else if (b == me)
      {
        receive(a);
      }
    }
  }
}
}

vtkSmartPointer<vtkPolyData> WithGhostCells(
  vtkMultiProcessController* controller, vtkPolyData* piece, int layers, std::string& error)
{
  const int me = controller->GetLocalProcessId();
  const int processes = controller->GetNumberOfProcesses();
  vtkNew<vtkPolyData> emptyPiece;
  if (!piece->GetPoints())
  {
    // An empty piece: no points object at all.
    vtkNew<vtkPoints> none;
    emptyPiece->SetPoints(none);
    piece = emptyPiece;
  }
  const vtkIdType np = piece->GetNumberOfPoints();
  vtkLogStartScope(TRACE, "shock: cells and links");
  const Cells own = ReadCells(piece);
  std::vector<vtkIdType> linkStart, links;
  PointLinks(own, np, linkStart, links);
  vtkLogEndScope("shock: cells and links");

  vtkLogStartScope(TRACE, "shock: border points");
  // 1. Border points and their keys.
  // Point global ids count when every piece with points has them (one
  // reduction: some with and some without is an error on every process).
  vtkDataArray* givenIds = np > 0 ? piece->GetPointData()->GetGlobalIds() : nullptr;
  {
    const int local[2] = { np > 0 && givenIds ? 1 : 0, np > 0 && !givenIds ? 1 : 0 };
    int global[2] = { 0, 0 };
    controller->AllReduce(local, global, 2, vtkCommunicator::MAX_OP);
    if (global[0] && global[1])
    {
      error = "some pieces have point global ids and others do not: give every piece its ids, or none";
      return nullptr; // the same decision on every process
    }
  }
  std::vector<vtkIdType> border;
  {
    std::vector<vtkIdType> scratch;
    for (vtkIdType p = 0; p < np; ++p)
    {
      if (linkStart[static_cast<size_t>(p) + 1] > linkStart[static_cast<size_t>(p)] &&
        OnBorder(own, linkStart, links, p, scratch))
      {
        border.push_back(p);
      }
    }
  }
  auto keyOf = [&](vtkIdType p) {
    if (givenIds)
    {
      Key key;
      key.a = static_cast<std::uint64_t>(static_cast<vtkIdType>(givenIds->GetTuple1(p)));
      // With the point's coordinates, rounded to float, to check that the ids mean the same points.
      double x[3];
      piece->GetPoint(p, x);
      float rounded[3] = { static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2]) };
      for (float& v : rounded)
      {
        v = v == 0.0f ? 0.0f : v; // -0 is +0
      }
      std::uint32_t bits[3];
      std::memcpy(bits, rounded, sizeof(bits));
      key.b = (static_cast<std::uint64_t>(bits[0]) << 32) | bits[1];
      key.c = bits[2];
      return key;
    }
    double x[3];
    piece->GetPoint(p, x);
    return CoordinateKey(x);
  };
  std::vector<std::uint64_t> mine;
  mine.reserve(3 * border.size());
  for (vtkIdType p : border)
  {
    const Key key = keyOf(p);
    mine.insert(mine.end(), { key.a, key.b, key.c });
  }
  // The uint64 keys travel as doubles' bits (the controller has no uint64 gather of this form).
  std::vector<double> mineBits(mine.size());
  std::memcpy(mineBits.data(), mine.data(), 8 * mine.size());
  std::vector<vtkIdType> borderCounts;
  const std::vector<double> allBits = GatherItems(controller, mineBits, 3, borderCounts);
  std::vector<std::uint64_t> all(allBits.size());
  std::memcpy(all.data(), allBits.data(), 8 * allBits.size());
  std::vector<vtkIdType> pointCounts(static_cast<size_t>(processes));
  {
    vtkIdType count = np;
    controller->AllGather(&count, pointCounts.data(), 1);
  }

  vtkLogEndScope("shock: border points");
  vtkLogStartScope(TRACE, "shock: global ids");
  // The key of each gathered item: its global id, or the first gathered
  // point within a tolerance of its coordinates (pieces a source or reader cut
  // itself may compute their shared points to the last bit differently).
  // The tolerance: 1e-12 of the largest coordinate magnitude, or 4 units in the
  // last place of a float when any piece holds float points (they round there).
  int floatPoints = piece->GetPoints()->GetDataType() == VTK_FLOAT && np > 0 ? 1 : 0;
  {
    int any = 0;
    controller->AllReduce(&floatPoints, &any, 1, vtkCommunicator::MAX_OP);
    floatPoints = any;
  }
  const std::vector<Key> keys =
    givenIds ? GivenKeys(all) : MergedCoordinateKeys(all, floatPoints ? 4.0 * 0x1p-23 : 1e-12);
  if (givenIds)
  {
    // One global id, one point: every process sees the same gathered borders, so all decide alike.
    std::unordered_map<std::uint64_t, const Key*> pointOf;
    for (const Key& key : keys)
    {
      const auto inserted = pointOf.emplace(key.a, &key);
      if (!inserted.second && !(*inserted.first->second == key))
      {
        error = "the pieces' point global ids disagree: global id " +
          std::to_string(static_cast<vtkIdType>(key.a)) +
          " names points at different coordinates on different pieces (remove the point global ids to have them made)";
        return nullptr;
      }
    }
  }

  // 2. Holders, owners and global ids. A key repeated within one piece
  // (coincident points of that piece) is shared through its first occurrence
  // only; the others are points of their own.
  std::unordered_map<Key, Holders, KeyHash> holders;
  std::vector<char> shared(all.size() / 3, 0); // the piece's first occurrence of its key
  {
    size_t item = 0;
    for (int r = 0; r < processes; ++r)
    {
      for (vtkIdType k = 0; k < borderCounts[static_cast<size_t>(r)]; ++k, ++item)
      {
        const Key& key = keys[item];
        Holders& h = holders[key];
        if (h.empty() || h.back() != r)
        {
          h.push_back(r);
          shared[item] = 1;
        }
      }
    }
  }
  // Owned points per process: all but the shared ones a lower process holds.
  std::vector<vtkIdType> firstId(static_cast<size_t>(processes) + 1, 0);
  std::unordered_map<Key, vtkIdType, KeyHash> sharedIds; // key -> global id (coordinate keys)
  {
    size_t item = 0;
    for (int r = 0; r < processes; ++r)
    {
      vtkIdType owned = pointCounts[static_cast<size_t>(r)];
      vtkIdType ownedBorder = 0;
      for (vtkIdType k = 0; k < borderCounts[static_cast<size_t>(r)]; ++k, ++item)
      {
        const Key& key = keys[item];
        const bool mineToOwn = !shared[item] || holders[key].front() == r;
        if (!mineToOwn)
        {
          --owned;
        }
        else if (shared[item] && !givenIds)
        {
          sharedIds[key] = firstId[static_cast<size_t>(r)] + ownedBorder;
        }
        ownedBorder += mineToOwn ? 1 : 0;
      }
      firstId[static_cast<size_t>(r) + 1] = firstId[static_cast<size_t>(r)] + owned;
    }
  }
  // This piece's global ids: owned border points first (in border order), then the rest.
  std::vector<vtkIdType> gid(static_cast<size_t>(np), -1);
  std::vector<int> ownerOf(static_cast<size_t>(np), me);
  {
    size_t item = 0;
    for (int r = 0; r < me; ++r)
    {
      item += static_cast<size_t>(borderCounts[static_cast<size_t>(r)]);
    }
    vtkIdType next = firstId[static_cast<size_t>(me)];
    std::vector<char> isBorder(static_cast<size_t>(np), 0);
    for (size_t k = 0; k < border.size(); ++k, ++item)
    {
      const vtkIdType p = border[k];
      isBorder[static_cast<size_t>(p)] = 1;
      const Key& key = keys[item];
      const int owner = shared[item] ? holders[key].front() : me;
      ownerOf[static_cast<size_t>(p)] = owner;
      if (givenIds)
      {
        gid[static_cast<size_t>(p)] = static_cast<vtkIdType>(key.a);
      }
      else if (owner == me)
      {
        gid[static_cast<size_t>(p)] = next++;
      }
      else
      {
        gid[static_cast<size_t>(p)] = sharedIds[key];
      }
    }
    for (vtkIdType p = 0; p < np; ++p)
    {
      if (!isBorder[static_cast<size_t>(p)])
      {
        gid[static_cast<size_t>(p)] =
          givenIds ? static_cast<vtkIdType>(givenIds->GetTuple1(p)) : next++;
      }
    }
  }
  // Holders by global id, for the points that arrive in rings.
  std::unordered_map<vtkIdType, const Holders*> holdersById;
  {
    size_t item = 0;
    for (int r = 0; r < processes; ++r)
    {
      for (vtkIdType k = 0; k < borderCounts[static_cast<size_t>(r)]; ++k, ++item)
      {
        if (!shared[item])
        {
          continue;
        }
        const Key& key = keys[item];
        const Holders& h = holders[key];
        if (h.size() > 1)
        {
          holdersById.emplace(givenIds ? static_cast<vtkIdType>(key.a) : sharedIds[key], &h);
        }
      }
    }
  }
  LocalPoints local; // global id -> local point (own and ghost)
  const bool duplicateIds =
    !local.Build(gid, !givenIds, firstId[static_cast<size_t>(me)], firstId[static_cast<size_t>(me) + 1]);
  if (duplicateIds)
  {
    error = "the piece's point global ids are not unique";
  }
  if (AnyFailed(controller, duplicateIds, error))
  {
    return nullptr;
  }

  vtkLogEndScope("shock: global ids");
  vtkLogStartScope(TRACE, "shock: rings");
  // 3. Rings, as a breadth-first search over all pieces' cells from the own
  // ones: a point at ring distance k from them has a budget of layers - k,
  // and a cell is a ghost cell when one of its points has a budget >= 1. A
  // process asks the holders of a point for their own cells within its
  // budget; each searches its own piece from all the points it was asked
  // about at once and answers with the cells and their points' budgets. A
  // point whose budget grows is asked of its other holders, until nothing
  // grows: one round for most pieces (a piece's neighbours' cells within
  // `layers` rings), more where the rings cross a third piece.
  std::vector<vtkIdType> firstCell(static_cast<size_t>(processes) + 1, 0);
  {
    std::vector<vtkIdType> cellCounts(static_cast<size_t>(processes));
    vtkIdType count = own.Size();
    controller->AllGather(&count, cellCounts.data(), 1);
    for (int r = 0; r < processes; ++r)
    {
      firstCell[static_cast<size_t>(r) + 1] = firstCell[static_cast<size_t>(r)] + cellCounts[static_cast<size_t>(r)];
    }
  }
  // Received ghost points and cells: which packet, which row.
  std::vector<vtkSmartPointer<vtkPolyData>> packets;
  struct Row
  {
    int packet;
    vtkIdType row;
  };
  std::vector<Row> ghostPoints, ghostCellRows;
  std::vector<int> ghostPointSource; // the process that sent each ghost point
  std::vector<vtkIdType> ghostPointIds; // their global ids
  Cells ghost;                        // ghost cells, local point ids
  std::unordered_set<vtkIdType> heldCells;
  std::vector<int> budget(static_cast<size_t>(np), layers); // per local point (own: all)
  // The points whose budget grew, with the process whose answer made it grow (me: the own points).
  std::vector<std::pair<vtkIdType, int>> grown;
  for (vtkIdType p : border)
  {
    grown.emplace_back(p, me);
  }
  // The responder's search, reused across requesters (reset through the touched lists).
  std::vector<int> best(static_cast<size_t>(np), -1);
  std::vector<int> cellTaken(static_cast<size_t>(own.Size()), 0);
  const int maxRounds = layers * processes + 2; // budgets only grow: a bound, never reached
  for (int round = 0; round < maxRounds && layers > 0; ++round)
  {
    // Requests: (global id, budget) of each grown point to its other holders.
    std::vector<std::vector<vtkIdType>> requests(static_cast<size_t>(processes));
    for (const auto& entry : grown)
    {
      const vtkIdType p = entry.first;
      const int b = budget[static_cast<size_t>(p)];
      if (b <= 0)
      {
        continue;
      }
      const vtkIdType key = p < np ? gid[static_cast<size_t>(p)] : ghostPointIds[static_cast<size_t>(p - np)];
      const int source = p < np ? me : ghostPointSource[static_cast<size_t>(p - np)];
      const auto found = holdersById.find(key);
      auto ask = [&](int h) {
        if (h != me && h != entry.second)
        {
          requests[static_cast<size_t>(h)].insert(requests[static_cast<size_t>(h)].end(), { key, b });
        }
      };
      if (found != holdersById.end())
      {
        for (int h : *found->second)
        {
          ask(h);
        }
      }
      else
      {
        ask(source);
      }
    }
    grown.clear();
    std::vector<vtkIdType> counts(static_cast<size_t>(processes));
    for (int r = 0; r < processes; ++r)
    {
      counts[static_cast<size_t>(r)] = static_cast<vtkIdType>(requests[static_cast<size_t>(r)].size());
    }
    std::vector<vtkIdType> matrix(static_cast<size_t>(processes * processes));
    controller->AllGather(counts.data(), matrix.data(), processes);
    if (std::all_of(matrix.begin(), matrix.end(), [](vtkIdType v) { return v == 0; }))
    {
      break; // every piece has all its rings
    }
    std::vector<std::vector<vtkIdType>> asked(static_cast<size_t>(processes));
    InPairOrder(me, processes, matrix,
      [&](int r) {
        controller->Send(requests[static_cast<size_t>(r)].data(), counts[static_cast<size_t>(r)], r, RequestTag);
      },
      [&](int s) {
        auto& list = asked[static_cast<size_t>(s)];
        list.resize(static_cast<size_t>(matrix[static_cast<size_t>(s * processes + me)]));
        controller->Receive(list.data(), static_cast<vtkIdType>(list.size()), s, RequestTag);
      });
    std::vector<vtkIdType> transposed(matrix.size());
    for (int a = 0; a < processes; ++a)
    {
      for (int b = 0; b < processes; ++b)
      {
        transposed[static_cast<size_t>(b * processes + a)] = matrix[static_cast<size_t>(a * processes + b)];
      }
    }
    std::vector<vtkSmartPointer<vtkPolyData>> answers(static_cast<size_t>(processes));
    for (int s = 0; s < processes; ++s)
    {
      if (asked[static_cast<size_t>(s)].empty())
      {
        continue;
      }
      // Breadth-first from the asked points, the largest budgets first (a bucket per budget).
      std::vector<std::vector<vtkIdType>> buckets(static_cast<size_t>(layers) + 1);
      std::vector<vtkIdType> touched, chosen;
      const auto& list = asked[static_cast<size_t>(s)];
      for (size_t k = 0; k + 1 < list.size(); k += 2)
      {
        const vtkIdType p = local.Own(list[k]);
        const int b = static_cast<int>(std::min<vtkIdType>(list[k + 1], layers));
        if (p < 0 || b <= best[static_cast<size_t>(p)])
        {
          continue; // not an own point here (a ghost's cells come from its owner), or no gain
        }
        if (best[static_cast<size_t>(p)] < 0)
        {
          touched.push_back(p);
        }
        best[static_cast<size_t>(p)] = b;
        buckets[static_cast<size_t>(b)].push_back(p);
      }
      for (int b = layers; b >= 1; --b)
      {
        for (size_t k = 0; k < buckets[static_cast<size_t>(b)].size(); ++k)
        {
          const vtkIdType p = buckets[static_cast<size_t>(b)][k];
          if (best[static_cast<size_t>(p)] != b)
          {
            continue; // reached again with a larger budget
          }
          for (vtkIdType l = linkStart[static_cast<size_t>(p)]; l < linkStart[static_cast<size_t>(p) + 1]; ++l)
          {
            const vtkIdType c = links[static_cast<size_t>(l)];
            if (cellTaken[static_cast<size_t>(c)])
            {
              continue; // taken with a budget at least b
            }
            cellTaken[static_cast<size_t>(c)] = 1;
            chosen.push_back(c);
            for (vtkIdType i = own.offsets[static_cast<size_t>(c)]; i < own.offsets[static_cast<size_t>(c) + 1]; ++i)
            {
              const vtkIdType q = own.points[static_cast<size_t>(i)];
              if (best[static_cast<size_t>(q)] < b - 1)
              {
                if (best[static_cast<size_t>(q)] < 0)
                {
                  touched.push_back(q);
                }
                best[static_cast<size_t>(q)] = b - 1;
                buckets[static_cast<size_t>(b - 1)].push_back(q);
              }
            }
          }
        }
      }
      // The packet: the chosen cells (as polygons of any size, their kinds in cell data)
      // and their points with their budgets.
      std::unordered_map<vtkIdType, vtkIdType> row;
      vtkNew<vtkIdList> pointRows;
      vtkNew<vtkCellArray> polys;
      for (vtkIdType c : chosen)
      {
        const vtkIdType begin = own.offsets[static_cast<size_t>(c)], end = own.offsets[static_cast<size_t>(c) + 1];
        polys->InsertNextCell(end - begin);
        for (vtkIdType k = begin; k < end; ++k)
        {
          const vtkIdType p = own.points[static_cast<size_t>(k)];
          const auto inserted = row.emplace(p, pointRows->GetNumberOfIds());
          if (inserted.second)
          {
            pointRows->InsertNextId(p);
          }
          polys->InsertCellPoint(inserted.first->second);
        }
      }
      auto packet = vtkSmartPointer<vtkPolyData>::New();
      vtkNew<vtkPoints> points;
      points->SetDataType(piece->GetPoints()->GetDataType());
      piece->GetPoints()->GetPoints(pointRows, points);
      packet->SetPoints(points);
      packet->SetPolys(polys);
      packet->GetPointData()->CopyGlobalIdsOn(); // CopyAllocate leaves them out otherwise
      packet->GetPointData()->CopyAllocate(piece->GetPointData(), pointRows->GetNumberOfIds());
      packet->GetPointData()->CopyData(piece->GetPointData(), pointRows, Sequence(pointRows->GetNumberOfIds()));
      vtkNew<vtkIdTypeArray> pointIds;
      pointIds->SetName(PacketPointIds);
      pointIds->SetNumberOfTuples(pointRows->GetNumberOfIds());
      vtkNew<vtkIntArray> budgets;
      budgets->SetName(PacketBudgets);
      budgets->SetNumberOfTuples(pointRows->GetNumberOfIds());
      for (vtkIdType k = 0; k < pointRows->GetNumberOfIds(); ++k)
      {
        pointIds->SetValue(k, gid[static_cast<size_t>(pointRows->GetId(k))]);
        budgets->SetValue(k, std::max(0, best[static_cast<size_t>(pointRows->GetId(k))]));
      }
      packet->GetPointData()->AddArray(pointIds);
      packet->GetPointData()->AddArray(budgets);
      vtkNew<vtkIdList> cellRows;
      for (vtkIdType c : chosen)
      {
        cellRows->InsertNextId(c);
      }
      packet->GetCellData()->CopyGlobalIdsOn();
      packet->GetCellData()->CopyAllocate(piece->GetCellData(), cellRows->GetNumberOfIds());
      packet->GetCellData()->CopyData(piece->GetCellData(), cellRows, Sequence(cellRows->GetNumberOfIds()));
      vtkNew<vtkIdTypeArray> cellIds;
      cellIds->SetName(PacketCellIds);
      vtkNew<vtkUnsignedCharArray> kinds;
      kinds->SetName(PacketCellKinds);
      for (vtkIdType c : chosen)
      {
        cellIds->InsertNextValue(firstCell[static_cast<size_t>(me)] + c);
        kinds->InsertNextValue(own.kind[static_cast<size_t>(c)]);
        cellTaken[static_cast<size_t>(c)] = 0;
      }
      for (vtkIdType p : touched)
      {
        best[static_cast<size_t>(p)] = -1;
      }
      packet->GetCellData()->AddArray(cellIds);
      packet->GetCellData()->AddArray(kinds);
      answers[static_cast<size_t>(s)] = packet;
    }
    // Every process marshals its answers before the exchange and reads what it
    // received after it, so that no process waits for another's marshalling.
    std::vector<vtkSmartPointer<vtkCharArray>> sendBuffers(static_cast<size_t>(processes));
    for (int r = 0; r < processes; ++r)
    {
      if (answers[static_cast<size_t>(r)])
      {
        sendBuffers[static_cast<size_t>(r)] = vtkSmartPointer<vtkCharArray>::New();
        vtkCommunicator::MarshalDataObject(answers[static_cast<size_t>(r)], sendBuffers[static_cast<size_t>(r)]);
      }
    }
    std::vector<int> arrived;
    std::vector<vtkSmartPointer<vtkCharArray>> receiveBuffers;
    InPairOrder(me, processes, transposed,
      [&](int r) {
        vtkCharArray* buffer = sendBuffers[static_cast<size_t>(r)];
        vtkIdType size = buffer->GetNumberOfValues();
        controller->Send(&size, 1, r, AnswerTag);
        controller->Send(buffer->GetPointer(0), size, r, AnswerTag + 1);
      },
      [&](int s) {
        vtkIdType size = 0;
        controller->Receive(&size, 1, s, AnswerTag);
        auto buffer = vtkSmartPointer<vtkCharArray>::New();
        buffer->SetNumberOfValues(size);
        controller->Receive(buffer->GetPointer(0), size, s, AnswerTag + 1);
        receiveBuffers.push_back(buffer);
        arrived.push_back(s);
      });
    // Append the new cells; the points whose budget grew are asked of their other holders next.
    for (size_t a = 0; a < arrived.size(); ++a)
    {
      auto packet = vtkSmartPointer<vtkPolyData>::New();
      vtkCommunicator::UnMarshalDataObject(receiveBuffers[a], packet);
      const int packetIndex = static_cast<int>(packets.size());
      packets.push_back(packet);
      auto* pointIds = vtkIdTypeArray::SafeDownCast(packet->GetPointData()->GetArray(PacketPointIds));
      auto* budgets = vtkIntArray::SafeDownCast(packet->GetPointData()->GetArray(PacketBudgets));
      auto* cellIds = vtkIdTypeArray::SafeDownCast(packet->GetCellData()->GetArray(PacketCellIds));
      auto* kinds = vtkUnsignedCharArray::SafeDownCast(packet->GetCellData()->GetArray(PacketCellKinds));
      if (!pointIds || !budgets || !cellIds || !kinds)
      {
        continue;
      }
      // Points: new ones join, and every budget is the largest known.
      std::vector<vtkIdType> localOf(static_cast<size_t>(pointIds->GetNumberOfTuples()));
      for (vtkIdType k = 0; k < pointIds->GetNumberOfTuples(); ++k)
      {
        const vtkIdType id = pointIds->GetValue(k);
        bool added = false;
        const vtkIdType p = local.Find(id, np + static_cast<vtkIdType>(ghostPoints.size()), added);
        if (added)
        {
          ghostPoints.push_back({ packetIndex, k });
          ghostPointSource.push_back(arrived[a]);
          ghostPointIds.push_back(id);
          budget.push_back(-1);
        }
        localOf[static_cast<size_t>(k)] = p;
        if (budgets->GetValue(k) > budget[static_cast<size_t>(p)])
        {
          budget[static_cast<size_t>(p)] = budgets->GetValue(k);
          grown.emplace_back(p, arrived[a]);
        }
      }
      vtkCellArray* polys = packet->GetPolys();
      auto iterator = vtk::TakeSmartPointer(polys->NewIterator());
      vtkIdType c = 0;
      std::vector<vtkIdType> ids;
      for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++c)
      {
        if (!heldCells.insert(cellIds->GetValue(c)).second)
        {
          continue;
        }
        vtkIdType n;
        const vtkIdType* rows;
        iterator->GetCurrentCell(n, rows);
        ids.resize(static_cast<size_t>(n));
        for (vtkIdType k = 0; k < n; ++k)
        {
          ids[static_cast<size_t>(k)] = localOf[static_cast<size_t>(rows[k])];
        }
        ghost.Append(kinds->GetValue(c), n, ids.data());
        ghostCellRows.push_back({ packetIndex, c });
      }
    }
  }
  vtkLogEndScope("shock: rings");
  vtkLogScopeF(TRACE, "shock: assemble the piece with its rings");
  // 4. The piece with its rings: own points then ghost points, each kind of
  // cell with its own cells first; owners' marks and global ids.
  const vtkIdType total = np + static_cast<vtkIdType>(ghostPoints.size());
  auto result = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataType(piece->GetPoints()->GetDataType());
  points->SetNumberOfPoints(total);
  CopyLeadingRows(points->GetData(), piece->GetPoints()->GetData(), np);
  for (size_t g = 0; g < ghostPoints.size(); ++g)
  {
    points->GetData()->SetTuple(np + static_cast<vtkIdType>(g), ghostPoints[g].row,
      packets[static_cast<size_t>(ghostPoints[g].packet)]->GetPoints()->GetData());
  }
  result->SetPoints(points);
  // Point data: the piece's arrays, then the ghost points' rows of the same arrays.
  vtkPointData* pointData = result->GetPointData();
  bool missing = !ExtendAttributes(pointData, piece->GetPointData(), total, np,
    [&](vtkIdType r, vtkDataSetAttributes*& holder, vtkIdType& row) {
      const Row& ghostRow = ghostPoints[static_cast<size_t>(r - np)];
      holder = packets[static_cast<size_t>(ghostRow.packet)]->GetPointData();
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
    const bool owned = p < np && ownerOf[static_cast<size_t>(p)] == me;
    ids->SetValue(p, p < np ? gid[static_cast<size_t>(p)] : ghostPointIds[static_cast<size_t>(p - np)]);
    pointGhosts->SetValue(p,
      static_cast<unsigned char>((owned ? 0 : vtkDataSetAttributes::DUPLICATEPOINT) | hiddenPoints[static_cast<size_t>(p)]));
  }
  if (givenIds && givenIds->GetName())
  {
    pointData->RemoveArray(givenIds->GetName()); // replaced by the same ids of every point
    ids->SetName(givenIds->GetName());
  }
  pointData->SetGlobalIds(ids);
  pointData->AddArray(pointGhosts);

  // Cells, kind by kind: own then ghost; the cell data in that order. The
  // cell arrays are filled as offsets and connectivity, not a call per cell.
  std::vector<std::pair<int, vtkIdType>> order; // (0 own / 1 ghost, index)
  order.reserve(static_cast<size_t>(own.Size() + ghost.Size()));
  vtkSmartPointer<vtkCellArray> kindCells[4];
  for (unsigned char kind = 0; kind < 4; ++kind)
  {
    vtkIdType cells = 0, ids = 0;
    for (const Cells* from : { static_cast<const Cells*>(&own), static_cast<const Cells*>(&ghost) })
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
    vtkNew<vtkIdTypeArray> offsets, connectivity;
    offsets->SetNumberOfTuples(cells + 1);
    connectivity->SetNumberOfTuples(ids);
    vtkIdType* offset = offsets->GetPointer(0);
    vtkIdType* to = connectivity->GetPointer(0);
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
        to = std::copy(begin, end, to);
        offset[1] = offset[0] + (end - begin);
        ++offset;
        order.emplace_back(which, c);
      }
    }
    kindCells[kind] = vtkSmartPointer<vtkCellArray>::New();
    kindCells[kind]->SetData(offsets, connectivity);
  }
  result->SetVerts(kindCells[0]);
  result->SetLines(kindCells[1]);
  result->SetPolys(kindCells[2]);
  result->SetStrips(kindCells[3]);
  const vtkIdType cellTotal = static_cast<vtkIdType>(order.size());
  // Own cells keep their numbers when their kinds come in order (e.g. polygons only).
  vtkIdType leadingCells = 0; // own cells that keep their numbers
  while (leadingCells < cellTotal && order[static_cast<size_t>(leadingCells)].first == 0 &&
    order[static_cast<size_t>(leadingCells)].second == leadingCells)
  {
    ++leadingCells;
  }
  missing = !ExtendAttributes(result->GetCellData(), piece->GetCellData(), cellTotal, leadingCells,
    [&](vtkIdType c, vtkDataSetAttributes*& holder, vtkIdType& row) {
      const auto& entry = order[static_cast<size_t>(c)];
      if (entry.first == 0)
      {
        row = entry.second;
        return;
      }
      const Row& ghostRow = ghostCellRows[static_cast<size_t>(entry.second)];
      holder = packets[static_cast<size_t>(ghostRow.packet)]->GetCellData();
      row = ghostRow.row;
    }) || missing;
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
    cellGhosts->SetValue(c,
      static_cast<unsigned char>((order[static_cast<size_t>(c)].first == 0 ? 0 : vtkDataSetAttributes::DUPLICATECELL) | hiddenCell));
  }
  cellData->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  cellData->AddArray(cellGhosts);
  result->GetFieldData()->ShallowCopy(piece->GetFieldData());
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
}
