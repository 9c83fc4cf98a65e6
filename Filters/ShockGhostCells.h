/**
 * @file ShockGhostCells.h
 * @brief The steps of ShockParallel::WithGhostCells (private to the module):
 * global point ids of a distributed surface, then its ghost-cell rings grown
 * with the piece's own connectivity, one exchange per ring.
 *
 * What VTK's vtkGenerateGlobalIds and vtkGhostCellsGenerator do for a
 * surface, in the steps the shock filters need, and at the cost of the
 * piece's boundary instead of its volume:
 *
 * 1. Border points (ShockGhostNumbering.cxx). A point another piece can share
 *    lies on a border edge of this piece's own polygons (an edge of one
 *    polygon only), or on a vertex or line cell. Only those are exchanged
 *    (AllGatherV of their keys).
 * 2. Keys and global ids (ShockGhostNumbering.cxx). The key of a point is its
 *    global id when the input has point global ids, else its coordinates
 *    (coincident points of different pieces, as sources and partitioned files
 *    repeat them on the seams, are one point). A shared point is owned by the
 *    lowest process that holds it; every process numbers its owned points
 *    after those of the processes before it. Everything is computed from the
 *    gathered borders and the point counts, the same on every process.
 * 3. Rings (ShockGhostRings.cxx). Ring 1 is every other process's cells that
 *    use a point of this piece's own cells; ring k the cells that use a point
 *    first received in ring k-1. Each ring: a process asks the holders of its
 *    new points (the gathered borders name them; a point not on any border
 *    has one holder, the process that sent it) for their own cells around
 *    those points, in one round of requests and one of answers (the cells
 *    with their points and the piece's arrays (those the filter reads:
 *    ShockParallel::CarriedArrays), as vtkPolyData sent as raw blocks).
 * 4. Assembly (ShockGhostCells.cxx): the piece with its rings, owners' marks
 *    and global ids.
 */
#ifndef ShockGhostCells_h
#define ShockGhostCells_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

class vtkAbstractArray;
class vtkCharArray;
class vtkDataArray;
class vtkMultiProcessController;

namespace ShockParallel
{
namespace ghost
{
/// The four cell arrays of a vtkPolyData, in its cell numbering order.
struct Cells
{
  std::vector<unsigned char> kind;     ///< 0 vertex, 1 line, 2 polygon, 3 strip
  std::vector<vtkIdType> offsets{ 0 }; ///< into `points`, one more than cells
  std::vector<vtkIdType> points;       ///< local point ids

  vtkIdType Size() const { return static_cast<vtkIdType>(kind.size()); }
  void Append(unsigned char k, vtkIdType n, const vtkIdType* ids)
  {
    this->kind.push_back(k);
    this->points.insert(this->points.end(), ids, ids + n);
    this->offsets.push_back(static_cast<vtkIdType>(this->points.size()));
  }
};

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

/// The ranks that hold a border point, lowest first (the owner).
using Holders = std::vector<int>;

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
  bool Build(const std::vector<vtkIdType>& gid, bool madeIds, vtkIdType first, vtkIdType end);
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
  vtkIdType Find(vtkIdType id, vtkIdType next, bool& added);

private:
  vtkIdType First = 0;
  std::vector<vtkIdType> Table;
  std::unordered_map<vtkIdType, vtkIdType> Others, Ghosts;
};

/// Steps 1 and 2: the piece's cells, its border and the global numbering of its points.
/// Not copied: holdersById points into holders.
struct Numbering
{
  Numbering() = default;
  Numbering(const Numbering&) = delete;
  Numbering& operator=(const Numbering&) = delete;

  int me = 0;
  int processes = 1;
  vtkIdType np = 0;                         ///< the piece's points
  Cells own;                                ///< the piece's cells
  std::vector<vtkIdType> linkStart, links;  ///< point -> own cells (CSR)
  vtkDataArray* givenIds = nullptr;         ///< this piece's point global ids (given), if it has points
  bool idsGiven = false;                    ///< every piece with points has ids (the same on every process)
  std::vector<vtkIdType> border;            ///< points another piece may share, ascending
  std::vector<vtkIdType> gid;               ///< global id per own point
  std::vector<int> ownerOf;                 ///< owning process per own point
  std::unordered_map<Key, Holders, KeyHash> holders;              ///< by key, of every gathered border point
  std::unordered_map<vtkIdType, const Holders*> holdersById;      ///< shared points' holders by global id
  LocalPoints local;                        ///< global id -> local point (own, then the rings' ghosts)
};

/**
 * The points another piece may share, ascending (ShockGhostBorders.cxx):
 * those on a vertex or line cell, and both ends of every edge of the polygons
 * and strip triangles that exactly one side has.
 */
std::vector<vtkIdType> BorderPoints(const Cells& cells, vtkIdType np);

/**
 * The points on a vertex or line cell (or a polygon of fewer than 3 points),
 * ascending: another piece may hold such a point inside its polygons, where it
 * is no border point of that piece (ShockGhostBorders.cxx).
 */
std::vector<vtkIdType> LoosePoints(const Cells& cells, vtkIdType np);

/// Cells of `piece`, read in place from its four cell arrays.
Cells ReadCells(vtkPolyData* piece);

/**
 * Rows [fromRow, fromRow + count) of `from` into rows [toRow, toRow + count)
 * of `to` (allocated): one copy when both hold their values contiguously with
 * the same type and components, VTK's row copy otherwise.
 */
void CopyRowBlock(vtkAbstractArray* to, vtkIdType toRow, vtkAbstractArray* from, vtkIdType fromRow, vtkIdType count);

/// Point -> cells (CSR) of `cells` over `np` points.
void PointLinks(const Cells& cells, vtkIdType np, std::vector<vtkIdType>& start, std::vector<vtkIdType>& list);

/// Steps 1 and 2 (collective). False, with the same `error` on every process, when the pieces' ids disagree.
bool NumberPoints(vtkMultiProcessController* controller, vtkPolyData* piece, Numbering& numbering, std::string& error);

/// Step 3: the ghost points and cells received, in arrival order.
struct Rings
{
  struct Row
  {
    int packet;    ///< index into `packets`
    vtkIdType row; ///< point or cell row of that packet
  };
  std::vector<vtkSmartPointer<vtkPolyData>> packets;
  std::vector<Row> ghostPoints;          ///< local point np + g is ghostPoints[g]
  std::vector<vtkIdType> ghostPointIds;  ///< their global ids
  std::vector<Row> ghostCellRows;        ///< ghost cell g is ghostCellRows[g]
  Cells ghost;                           ///< ghost cells, local point ids
  /// The ring of each ghost cell: 1 + the fewest cells between one of its points and the piece's own cells.
  std::vector<unsigned char> ghostCellRing;
};

/**
 * A ring answer `packet` into `buffer` for sending (ShockGhostPackets.cxx):
 * its points, cells and arrays as raw blocks of memory (the processes of one
 * run are one build on one kind of machine) behind a tag, or VTK's
 * marshalling when an array does not hold its values in one block.
 */
void PackPacket(vtkPolyData* packet, vtkCharArray* buffer);

/// The packet PackPacket put in `buffer`; false when the buffer is damaged.
bool UnpackPacket(vtkCharArray* buffer, vtkPolyData* packet);

/// Step 3 (collective): `layers` rings of the other pieces' cells around the piece's own.
void GrowRings(vtkMultiProcessController* controller, vtkPolyData* piece, int layers, Numbering& numbering,
  Rings& rings);

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
}

#endif
