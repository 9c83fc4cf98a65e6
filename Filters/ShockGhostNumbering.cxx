/**
 * @file ShockGhostNumbering.cxx
 * @brief Steps 1 and 2 of the ghost rings (ShockGhostCells.h): the border
 * points of a piece, their keys gathered from every piece, and the global ids
 * and owners of the piece's points.
 */
#include "ShockGhostCells.h"
#include "ShockParallel.h"

#include "vtkCellArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkLogger.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace ShockParallel
{
namespace ghost
{
namespace
{
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
 * A cell of a grid of cubes of side `size`: coordinates matched within a
 * tolerance of `size` lie in one of the 27 cells around a point (Around(0..26),
 * the first axis slowest).
 */
struct GridCell
{
  std::int64_t i, j, k;
  static GridCell Of(const double* x, double size)
  {
    return { static_cast<std::int64_t>(std::floor(x[0] / size)), static_cast<std::int64_t>(std::floor(x[1] / size)),
      static_cast<std::int64_t>(std::floor(x[2] / size)) };
  }
  GridCell Around(int d) const { return { i + d / 9 - 1, j + (d / 3) % 3 - 1, k + d % 3 - 1 }; }
  bool operator==(const GridCell& o) const { return i == o.i && j == o.j && k == o.k; }
};

struct GridCellHash
{
  size_t operator()(const GridCell& c) const
  {
    return static_cast<size_t>((static_cast<std::uint64_t>(c.i) * 73856093u) ^
      (static_cast<std::uint64_t>(c.j) * 19349663u) ^ (static_cast<std::uint64_t>(c.k) * 83492791u));
  }
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
  std::unordered_map<GridCell, std::vector<size_t>, GridCellHash> grid;
  std::vector<Key> keys(n);
  for (size_t item = 0; item < n; ++item)
  {
    const double* p = &x[3 * item];
    const GridCell cell = GridCell::Of(p, tolerance);
    size_t match = item;
    for (int d = 0; d < 27 && match == item; ++d)
    {
      const auto found = grid.find(cell.Around(d));
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

/// What steps 1 and 2 pass on: the gathered border points of every piece.
struct Gathered
{
  std::vector<vtkIdType> borderCounts; ///< border points per process
  std::vector<vtkIdType> pointCounts;  ///< points per process
  std::vector<std::uint64_t> words;    ///< 3 words per border point, in process order
  std::vector<Key> keys;               ///< the key of each gathered border point
  std::vector<char> shared;            ///< the piece's first occurrence of its key
  std::unordered_map<Key, vtkIdType, KeyHash> sharedIds; ///< key -> global id (coordinate keys)
  std::vector<vtkIdType> firstId;      ///< the first global id each process makes
};

/**
 * Point global ids count when every piece with points has them (one
 * reduction: some with and some without is an error on every process).
 */
bool GivenIdsAgree(vtkMultiProcessController* controller, Numbering& n, std::string& error)
{
  const int local[2] = { n.np > 0 && n.givenIds ? 1 : 0, n.np > 0 && !n.givenIds ? 1 : 0 };
  int global[2] = { 0, 0 };
  controller->AllReduce(local, global, 2, vtkCommunicator::MAX_OP);
  if (global[0] && global[1])
  {
    error = "some pieces have point global ids and others do not: give every piece its ids, or none";
    return false; // the same decision on every process
  }
  n.idsGiven = global[0] != 0; // the same on every process, empty pieces too
  return true;
}

/**
 * The key of own point p: its given global id, with the point's coordinates
 * rounded to float (to check that the ids mean the same points), or its
 * coordinates.
 */
Key KeyOf(vtkPolyData* piece, vtkDataArray* givenIds, vtkIdType p)
{
  double x[3];
  piece->GetPoint(p, x);
  if (!givenIds)
  {
    return CoordinateKey(x);
  }
  Key key;
  key.a = static_cast<std::uint64_t>(static_cast<vtkIdType>(givenIds->GetTuple1(p)));
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

/// The keys of the piece's points `points`, as doubles' bits (3 per point; the controller has no uint64 gather of this form).
std::vector<double> KeyBits(vtkPolyData* piece, const Numbering& n, const std::vector<vtkIdType>& points)
{
  std::vector<std::uint64_t> words;
  words.reserve(3 * points.size());
  for (vtkIdType p : points)
  {
    const Key key = KeyOf(piece, n.givenIds, p);
    words.insert(words.end(), { key.a, key.b, key.c });
  }
  std::vector<double> bits(words.size());
  std::memcpy(bits.data(), words.data(), 8 * words.size());
  return bits;
}

/**
 * Step 1b, when some piece has points on vertex or line cells (LoosePoints):
 * the piece's points inside its polygons that another piece holds that way
 * become border points too, so that both pieces see the point shared (without
 * it, each would own it). Candidates are the points within a generous
 * tolerance of the other pieces' loose points (or with their given global
 * id); MatchKeys decides which are the same point.
 */
void AddPointsHeldLooseElsewhere(
  vtkMultiProcessController* controller, vtkPolyData* piece, Numbering& n, const std::vector<vtkIdType>& loose)
{
  std::vector<vtkIdType> counts;
  const std::vector<double> all = GatherItems(controller, KeyBits(piece, n, loose), 3, counts);
  // The largest coordinate magnitude of every piece: MatchKeys' tolerance is
  // relative to the gathered border points', never larger than this.
  double bounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  if (n.np > 0)
  {
    piece->GetPoints()->GetBounds(bounds);
  }
  double localLargest = 0.0;
  for (double b : bounds)
  {
    localLargest = std::max(localLargest, std::abs(b));
  }
  double largest = 0.0;
  controller->AllReduce(&localLargest, &largest, 1, vtkCommunicator::MAX_OP);
  size_t mineBegin = 0;
  for (int r = 0; r < n.me; ++r)
  {
    mineBegin += 3 * static_cast<size_t>(counts[static_cast<size_t>(r)]);
  }
  const size_t mineEnd = mineBegin + 3 * loose.size();
  std::vector<Key> others; // the other pieces' loose keys
  for (size_t w = 0; w + 2 < all.size(); w += 3)
  {
    if (w < mineBegin || w >= mineEnd)
    {
      Key key;
      std::memcpy(&key.a, &all[w], 8);
      std::memcpy(&key.b, &all[w + 1], 8);
      std::memcpy(&key.c, &all[w + 2], 8);
      others.push_back(key);
    }
  }
  if (others.empty() || n.np == 0)
  {
    return;
  }
  // The piece's points inside its polygons: the candidates.
  std::vector<char> isBorder(static_cast<size_t>(n.np), 0);
  for (vtkIdType p : n.border)
  {
    isBorder[static_cast<size_t>(p)] = 1;
  }
  std::vector<vtkIdType> inner;
  for (vtkIdType p = 0; p < n.np; ++p)
  {
    if (!isBorder[static_cast<size_t>(p)])
    {
      inner.push_back(p);
    }
  }
  if (inner.empty())
  {
    return; // e.g. a point cloud: every point is a border point already
  }
  std::vector<vtkIdType> added;
  if (n.idsGiven)
  {
    std::unordered_set<std::uint64_t> ids;
    for (const Key& key : others)
    {
      ids.insert(key.a);
    }
    for (vtkIdType p : inner)
    {
      if (ids.count(static_cast<std::uint64_t>(static_cast<vtkIdType>(n.givenIds->GetTuple1(p)))))
      {
        added.push_back(p);
      }
    }
  }
  else
  {
    // Cells of a grid of a tolerance above MatchKeys' (16 float ulps of the
    // largest magnitude, against 4 at most): a candidate lies in one of the 27
    // cells around a loose point. The smaller side fills the 27 cells.
    std::vector<double> x(3 * others.size());
    std::memcpy(x.data(), others.data(), 8 * x.size());
    const double tolerance = largest > 0.0 ? 16.0 * 0x1p-23 * largest : std::numeric_limits<double>::min();
    const auto cellOf = [tolerance](const double* q) { return GridCell::Of(q, tolerance); };
    std::vector<char> near(inner.size(), 0);
    if (27 * others.size() <= inner.size())
    {
      std::unordered_set<GridCell, GridCellHash> cells; // around the loose points
      for (size_t k = 0; k < others.size(); ++k)
      {
        for (int d = 0; d < 27; ++d)
        {
          cells.insert(cellOf(&x[3 * k]).Around(d));
        }
      }
      for (size_t i = 0; i < inner.size(); ++i)
      {
        double q[3];
        piece->GetPoint(inner[i], q);
        near[i] = cells.count(cellOf(q)) ? 1 : 0;
      }
    }
    else
    {
      std::unordered_multimap<GridCell, size_t, GridCellHash> points; // the candidates by cell
      points.reserve(inner.size());
      for (size_t i = 0; i < inner.size(); ++i)
      {
        double q[3];
        piece->GetPoint(inner[i], q);
        points.emplace(cellOf(q), i);
      }
      for (size_t k = 0; k < others.size(); ++k)
      {
        for (int d = 0; d < 27; ++d)
        {
          const auto range = points.equal_range(cellOf(&x[3 * k]).Around(d));
          for (auto it = range.first; it != range.second; ++it)
          {
            near[it->second] = 1;
          }
        }
      }
    }
    for (size_t i = 0; i < inner.size(); ++i)
    {
      if (near[i])
      {
        added.push_back(inner[i]);
      }
    }
  }
  n.border.insert(n.border.end(), added.begin(), added.end());
  std::sort(n.border.begin(), n.border.end());
}

/// Step 1: the piece's border points, and every piece's border keys and point counts.
void GatherBorders(vtkMultiProcessController* controller, vtkPolyData* piece, Numbering& n, Gathered& g)
{
  n.border = BorderPoints(n.own, n.np);
  const std::vector<vtkIdType> loose = LoosePoints(n.own, n.np);
  // Every piece's points, and its loose points (one gather).
  const vtkIdType mine[2] = { n.np, static_cast<vtkIdType>(loose.size()) };
  std::vector<vtkIdType> counts(2 * static_cast<size_t>(n.processes));
  controller->AllGather(mine, counts.data(), 2);
  g.pointCounts.resize(static_cast<size_t>(n.processes));
  vtkIdType anyLoose = 0;
  for (int r = 0; r < n.processes; ++r)
  {
    g.pointCounts[static_cast<size_t>(r)] = counts[2 * static_cast<size_t>(r)];
    anyLoose += counts[2 * static_cast<size_t>(r) + 1];
  }
  if (anyLoose > 0) // the same decision on every process
  {
    AddPointsHeldLooseElsewhere(controller, piece, n, loose);
  }
  const std::vector<double> allBits = GatherItems(controller, KeyBits(piece, n, n.border), 3, g.borderCounts);
  g.words.resize(allBits.size());
  std::memcpy(g.words.data(), allBits.data(), 8 * allBits.size());
}

/**
 * The key of each gathered item: its global id, or the first gathered point
 * within a tolerance of its coordinates (pieces a source or reader cut itself
 * may compute their shared points to the last bit differently). The
 * tolerance: 1e-12 of the largest coordinate magnitude, or 4 units in the
 * last place of a float when any piece holds float points (they round there).
 */
bool MatchKeys(vtkMultiProcessController* controller, vtkPolyData* piece, const Numbering& n, Gathered& g,
  std::string& error)
{
  int floatPoints = piece->GetPoints()->GetDataType() == VTK_FLOAT && n.np > 0 ? 1 : 0;
  int any = 0;
  controller->AllReduce(&floatPoints, &any, 1, vtkCommunicator::MAX_OP);
  g.keys = n.idsGiven ? GivenKeys(g.words) : MergedCoordinateKeys(g.words, any ? 4.0 * 0x1p-23 : 1e-12);
  if (!n.idsGiven)
  {
    return true;
  }
  // One global id, one point: every process sees the same gathered borders, so all decide alike.
  std::unordered_map<std::uint64_t, const Key*> pointOf;
  for (const Key& key : g.keys)
  {
    const auto inserted = pointOf.emplace(key.a, &key);
    if (!inserted.second && !(*inserted.first->second == key))
    {
      error = "the pieces' point global ids disagree: global id " + std::to_string(static_cast<vtkIdType>(key.a)) +
        " names points at different coordinates on different pieces (remove the point global ids to have them made)";
      return false;
    }
  }
  return true;
}

/**
 * Step 2a: holders and owners. A key repeated within one piece (coincident
 * points of that piece) is shared through its first occurrence only; the
 * others are points of their own. Each process owns all its points but the
 * shared ones a lower process holds, and numbers them after the processes
 * before it.
 */
void FindOwners(Numbering& n, Gathered& g)
{
  g.shared.assign(g.words.size() / 3, 0);
  size_t item = 0;
  for (int r = 0; r < n.processes; ++r)
  {
    for (vtkIdType k = 0; k < g.borderCounts[static_cast<size_t>(r)]; ++k, ++item)
    {
      Holders& h = n.holders[g.keys[item]];
      if (h.empty() || h.back() != r)
      {
        h.push_back(r);
        g.shared[item] = 1;
      }
    }
  }
  g.firstId.assign(static_cast<size_t>(n.processes) + 1, 0);
  item = 0;
  for (int r = 0; r < n.processes; ++r)
  {
    vtkIdType owned = g.pointCounts[static_cast<size_t>(r)];
    vtkIdType ownedBorder = 0;
    for (vtkIdType k = 0; k < g.borderCounts[static_cast<size_t>(r)]; ++k, ++item)
    {
      const Key& key = g.keys[item];
      const bool mineToOwn = !g.shared[item] || n.holders[key].front() == r;
      if (!mineToOwn)
      {
        --owned;
      }
      else if (g.shared[item] && !n.idsGiven)
      {
        g.sharedIds[key] = g.firstId[static_cast<size_t>(r)] + ownedBorder;
      }
      ownedBorder += mineToOwn ? 1 : 0;
    }
    g.firstId[static_cast<size_t>(r) + 1] = g.firstId[static_cast<size_t>(r)] + owned;
  }
}

/// Step 2b: this piece's global ids and owners: owned border points first (in border order), then the rest.
void AssignGlobalIds(Numbering& n, Gathered& g)
{
  n.gid.assign(static_cast<size_t>(n.np), -1);
  n.ownerOf.assign(static_cast<size_t>(n.np), n.me);
  size_t item = 0;
  for (int r = 0; r < n.me; ++r)
  {
    item += static_cast<size_t>(g.borderCounts[static_cast<size_t>(r)]);
  }
  vtkIdType next = g.firstId[static_cast<size_t>(n.me)];
  std::vector<char> isBorder(static_cast<size_t>(n.np), 0);
  for (size_t k = 0; k < n.border.size(); ++k, ++item)
  {
    const vtkIdType p = n.border[k];
    isBorder[static_cast<size_t>(p)] = 1;
    const Key& key = g.keys[item];
    const int owner = g.shared[item] ? n.holders[key].front() : n.me;
    n.ownerOf[static_cast<size_t>(p)] = owner;
    if (n.givenIds)
    {
      n.gid[static_cast<size_t>(p)] = static_cast<vtkIdType>(key.a);
    }
    else if (owner == n.me)
    {
      n.gid[static_cast<size_t>(p)] = next++;
    }
    else
    {
      n.gid[static_cast<size_t>(p)] = g.sharedIds[key];
    }
  }
  for (vtkIdType p = 0; p < n.np; ++p)
  {
    if (!isBorder[static_cast<size_t>(p)])
    {
      n.gid[static_cast<size_t>(p)] = n.givenIds ? static_cast<vtkIdType>(n.givenIds->GetTuple1(p)) : next++;
    }
  }
}

/// Step 2c: the holders of the points shared by several pieces, by global id (for the points the rings bring).
void IndexHolders(Numbering& n, Gathered& g)
{
  size_t item = 0;
  for (int r = 0; r < n.processes; ++r)
  {
    for (vtkIdType k = 0; k < g.borderCounts[static_cast<size_t>(r)]; ++k, ++item)
    {
      if (!g.shared[item])
      {
        continue;
      }
      const Key& key = g.keys[item];
      const Holders& h = n.holders[key];
      if (h.size() > 1)
      {
        n.holdersById.emplace(n.idsGiven ? static_cast<vtkIdType>(key.a) : g.sharedIds[key], &h);
      }
    }
  }
}
}

bool LocalPoints::Build(const std::vector<vtkIdType>& gid, bool madeIds, vtkIdType first, vtkIdType end)
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

vtkIdType LocalPoints::Find(vtkIdType id, vtkIdType next, bool& added)
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

bool NumberPoints(vtkMultiProcessController* controller, vtkPolyData* piece, Numbering& n, std::string& error)
{
  n.me = controller->GetLocalProcessId();
  n.processes = controller->GetNumberOfProcesses();
  n.np = piece->GetNumberOfPoints();
  {
    vtkLogScopeF(TRACE, "shock: cells and links");
    n.own = ReadCells(piece);
    PointLinks(n.own, n.np, n.linkStart, n.links);
  }
  Gathered g;
  {
    vtkLogScopeF(TRACE, "shock: border points");
    n.givenIds = n.np > 0 ? piece->GetPointData()->GetGlobalIds() : nullptr;
    if (!GivenIdsAgree(controller, n, error))
    {
      return false;
    }
    GatherBorders(controller, piece, n, g);
  }
  vtkLogScopeF(TRACE, "shock: global ids");
  if (!MatchKeys(controller, piece, n, g, error))
  {
    return false;
  }
  FindOwners(n, g);
  AssignGlobalIds(n, g);
  IndexHolders(n, g);
  const bool duplicateIds = !n.local.Build(
    n.gid, !n.givenIds, g.firstId[static_cast<size_t>(n.me)], g.firstId[static_cast<size_t>(n.me) + 1]);
  if (duplicateIds)
  {
    error = "the piece's point global ids are not unique";
  }
  return !AnyFailed(controller, duplicateIds, error);
}
}
}
