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
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

namespace ShockParallel
{
namespace
{
constexpr int ExchangeTag = 84651;

/**
 * Point-to-point messages in one global order of (sender, receiver) pairs, the
 * same on every process, so blocking sends and receives cannot deadlock.
 * send(r) / receive(s) are called for the pairs that carry data.
 */
template <typename SendTo, typename ReceiveFrom>
void OrderedPairs(vtkMultiProcessController* controller, const std::vector<vtkIdType>& sendCounts,
  const std::vector<vtkIdType>& receiveCounts, SendTo send, ReceiveFrom receive)
{
  const int me = controller->GetLocalProcessId();
  const int processes = controller->GetNumberOfProcesses();
  for (int a = 0; a < processes; ++a)
  {
    for (int b = 0; b < processes; ++b)
    {
      if (a == me && b != me && sendCounts[static_cast<size_t>(b)] > 0)
      {
        send(b);
      }
      else if (b == me && a != me && receiveCounts[static_cast<size_t>(a)] > 0)
      {
        receive(a);
      }
    }
  }
}
}

vtkUnsignedCharArray* PointGhosts(vtkDataSet* data)
{
  return vtkUnsignedCharArray::SafeDownCast(
    data->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
}

bool UpstreamIsComposite(vtkAlgorithm* filter)
{
  // The upstream's own output stays composite while the pipeline hands the filter its blocks.
  vtkAlgorithmOutput* connection =
    filter->GetNumberOfInputConnections(0) > 0 ? filter->GetInputConnection(0, 0) : nullptr;
  vtkDataObject* upstream = connection && connection->GetProducer()
    ? connection->GetProducer()->GetOutputDataObject(connection->GetIndex())
    : nullptr;
  return vtkCompositeDataSet::SafeDownCast(upstream) != nullptr;
}

std::string ArraysFingerprintText(vtkDataSet* piece)
{
  if (!piece || piece->GetNumberOfPoints() == 0)
  {
    return "";
  }
  std::string text;
  for (vtkDataSetAttributes* data : { static_cast<vtkDataSetAttributes*>(piece->GetPointData()),
         static_cast<vtkDataSetAttributes*>(piece->GetCellData()) })
  {
    const char* where = data == piece->GetPointData() ? "point" : "cell";
    std::vector<std::string> names;
    for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    {
      vtkAbstractArray* array = data->GetAbstractArray(k);
      const char* name = array && array->GetName() ? array->GetName() : "(unnamed)";
      if (std::string(name) == vtkDataSetAttributes::GhostArrayName())
      {
        continue; // made and replaced by the distribution
      }
      names.push_back(std::string(where) + " array '" + name + "' (" + array->GetDataTypeAsString() + ", " +
        std::to_string(array->GetNumberOfComponents()) + " component" +
        (array->GetNumberOfComponents() == 1 ? "" : "s") + ")");
    }
    std::sort(names.begin(), names.end());
    for (const std::string& name : names)
    {
      text += name + ";";
    }
  }
  return text.empty() ? std::string("no point or cell arrays;") : text;
}

vtkMultiProcessController* PieceController(
  vtkAlgorithm* filter, vtkMultiProcessController* controller, vtkInformation* outInfo, bool& unknown)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  unknown = false;
  const int pieces = outInfo && outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES())
    : 1;
  if (pieces <= 1)
  {
    return nullptr;
  }
  if (UpstreamIsComposite(filter))
  {
    return nullptr;
  }
  if (!controller || controller->GetNumberOfProcesses() != pieces)
  {
    unknown = true;
    return nullptr;
  }
  return controller;
}

void Sum(vtkMultiProcessController* controller, double* values, int count)
{
  std::vector<double> local(values, values + count);
  controller->AllReduce(local.data(), values, count, vtkCommunicator::SUM_OP);
}

int Count(vtkMultiProcessController* controller, bool flag)
{
  const int local = flag ? 1 : 0;
  int total = 0;
  controller->AllReduce(&local, &total, 1, vtkCommunicator::SUM_OP);
  return total;
}

double GlobalRangeWidth(vtkMultiProcessController* controller, bool has, const double range[2])
{
  const double lowest = -std::numeric_limits<double>::max();
  const double local[2] = { has ? -range[0] : lowest, has ? range[1] : lowest };
  double global[2] = { 0.0, 0.0 };
  controller->AllReduce(local, global, 2, vtkCommunicator::MAX_OP);
  const double width = global[1] + global[0]; // high - low
  return std::isfinite(width) && width > 0.0 ? width : 0.0;
}

bool Replicated(vtkMultiProcessController* controller, vtkDataSet* input)
{
  // A fingerprint: sizes, and sums of the coordinates weighted two ways (so
  // that a permutation or a different piece shows).
  double print[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
  if (input)
  {
    print[0] = static_cast<double>(input->GetNumberOfPoints());
    print[1] = static_cast<double>(input->GetNumberOfCells());
    // The cells too, weighted by position (same points, other cells: not replicated).
    if (auto* polyData = vtkPolyData::SafeDownCast(input))
    {
      vtkIdType position = 0;
      for (vtkCellArray* cells : { polyData->GetVerts(), polyData->GetLines(), polyData->GetPolys(), polyData->GetStrips() })
      {
        auto iterator = vtk::TakeSmartPointer(cells->NewIterator());
        for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
        {
          vtkIdType size;
          const vtkIdType* ids;
          iterator->GetCurrentCell(size, ids);
          for (vtkIdType k = 0; k < size; ++k, ++position)
          {
            print[6] += static_cast<double>(ids[k]);
            print[7] += static_cast<double>(ids[k]) * (1.0 + static_cast<double>(position % 7919) / 7919.0);
          }
        }
      }
    }
    for (vtkIdType p = 0; p < input->GetNumberOfPoints(); ++p)
    {
      double x[3];
      input->GetPoint(p, x);
      const double w = 1.0 + static_cast<double>(p % 7919) / 7919.0;
      print[2] += x[0] + x[1] + x[2];
      print[3] += w * x[0];
      print[4] += w * x[1];
      print[5] += w * x[2];
    }
  }
  double low[8], high[8], negated[8];
  for (int k = 0; k < 8; ++k)
  {
    negated[k] = -print[k];
  }
  controller->AllReduce(print, high, 8, vtkCommunicator::MAX_OP);
  controller->AllReduce(negated, low, 8, vtkCommunicator::MAX_OP);
  for (int k = 0; k < 8; ++k)
  {
    if (high[k] != -low[k])
    {
      return false;
    }
  }
  return high[0] > 0.0;
}

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

/// The rows 0 .. n-1.
vtkSmartPointer<vtkIdList> FirstRows(vtkIdType n)
{
  auto rows = vtkSmartPointer<vtkIdList>::New();
  rows->SetNumberOfIds(n);
  for (vtkIdType k = 0; k < n; ++k)
  {
    rows->SetId(k, k);
  }
  return rows;
}
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
  owned->GetPointData()->CopyData(piece->GetPointData(), keptPoints, FirstRows(keptPoints->GetNumberOfIds()));
  owned->GetCellData()->CopyAllocate(piece->GetCellData(), keptCells->GetNumberOfIds());
  owned->GetCellData()->CopyData(piece->GetCellData(), keptCells, FirstRows(keptCells->GetNumberOfIds()));
  owned->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName()); // no ghost cell left
  return owned;
}

namespace
{
/// `array`'s rows `rows` (all of its first `count` rows when `rows` is null) as a new array.
vtkSmartPointer<vtkAbstractArray> Rows(vtkAbstractArray* array, vtkIdType count, vtkIdList* rows)
{
  auto picked = vtk::TakeSmartPointer(array->NewInstance());
  picked->SetName(array->GetName());
  picked->SetNumberOfComponents(array->GetNumberOfComponents());
  picked->CopyComponentNames(array);
  if (rows)
  {
    picked->SetNumberOfTuples(rows->GetNumberOfIds());
    vtkNew<vtkIdList> to;
    to->SetNumberOfIds(rows->GetNumberOfIds());
    for (vtkIdType k = 0; k < rows->GetNumberOfIds(); ++k)
    {
      to->SetId(k, k);
    }
    picked->InsertTuples(to, rows, array);
  }
  else
  {
    picked->SetNumberOfTuples(count);
    picked->InsertTuples(0, count, 0, array);
  }
  return picked;
}

/// Replace every array of `attributes` (taken from `from`) by its rows, attributes kept.
void KeepRows(vtkDataSetAttributes* attributes, vtkDataSetAttributes* from, vtkIdType count, vtkIdList* rows)
{
  attributes->ShallowCopy(from);
  for (int k = 0; k < from->GetNumberOfArrays(); ++k)
  {
    vtkAbstractArray* array = from->GetAbstractArray(k);
    if (array && array->GetName())
    {
      attributes->AddArray(Rows(array, count, rows)); // same name: replaced at its index
    }
  }
}
}

vtkSmartPointer<vtkPolyData> OwnedPiece(vtkPolyData* filtered, vtkPolyData* owned, vtkPolyData* input)
{
  // WithGhostCells put the piece's own points first, in their order, and each
  // kind's own cells before its ghost cells: the owned piece is those rows.
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(owned); // its cells
  const vtkIdType np = owned->GetNumberOfPoints();
  if (filtered->GetPoints() && filtered->GetPoints() != owned->GetPoints())
  {
    vtkNew<vtkPoints> points;
    points->SetData(vtkDataArray::SafeDownCast(Rows(filtered->GetPoints()->GetData(), np, nullptr)));
    result->SetPoints(points);
  }
  KeepRows(result->GetPointData(), filtered->GetPointData(), np, nullptr);
  vtkCellArray* ownCells[4] = { owned->GetVerts(), owned->GetLines(), owned->GetPolys(), owned->GetStrips() };
  vtkCellArray* allCells[4] = { filtered->GetVerts(), filtered->GetLines(), filtered->GetPolys(), filtered->GetStrips() };
  vtkNew<vtkIdList> cellRows;
  vtkIdType first = 0;
  for (int kind = 0; kind < 4; ++kind)
  {
    const vtkIdType own = ownCells[kind] ? ownCells[kind]->GetNumberOfCells() : 0;
    for (vtkIdType c = 0; c < own; ++c)
    {
      cellRows->InsertNextId(first + c);
    }
    first += allCells[kind] ? allCells[kind]->GetNumberOfCells() : 0;
  }
  KeepRows(result->GetCellData(), filtered->GetCellData(), cellRows->GetNumberOfIds(), cellRows);
  result->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName()); // no ghost cell left
  for (vtkDataSetAttributes* attributes : { static_cast<vtkDataSetAttributes*>(result->GetPointData()),
         static_cast<vtkDataSetAttributes*>(result->GetCellData()) })
  {
    vtkDataArray* made = attributes->GetGlobalIds();
    vtkDataSetAttributes* given = attributes == result->GetPointData()
      ? static_cast<vtkDataSetAttributes*>(input->GetPointData())
      : static_cast<vtkDataSetAttributes*>(input->GetCellData());
    if (made && made->GetName() && !given->GetGlobalIds())
    {
      attributes->RemoveArray(made->GetName());
    }
  }
  return result;
}

namespace
{
/// Everyone's `mine`, concatenated in process order; counts and offsets per process.
std::vector<vtkIdType> AllGather(vtkMultiProcessController* controller,
  const std::vector<vtkIdType>& mine, std::vector<vtkIdType>& counts, std::vector<vtkIdType>& offsets)
{
  const int processes = controller->GetNumberOfProcesses();
  vtkIdType count = static_cast<vtkIdType>(mine.size());
  counts.assign(static_cast<size_t>(processes), 0);
  offsets.assign(static_cast<size_t>(processes), 0);
  controller->AllGather(&count, counts.data(), 1);
  for (int r = 1; r < processes; ++r)
  {
    offsets[static_cast<size_t>(r)] = offsets[static_cast<size_t>(r - 1)] + counts[static_cast<size_t>(r - 1)];
  }
  std::vector<vtkIdType> all(static_cast<size_t>(offsets.back() + counts.back()) + 1);
  controller->AllGatherV(mine.data(), all.data(), count, counts.data(), offsets.data());
  all.pop_back();
  return all;
}
}

namespace
{
/// `text` of process `root`, on every process (collective).
std::string BroadcastText(vtkMultiProcessController* controller, const std::string& text, int root)
{
  vtkIdType length = static_cast<vtkIdType>(text.size());
  controller->Broadcast(&length, 1, root);
  std::vector<char> buffer(static_cast<size_t>(length) + 1, '\0');
  if (controller->GetLocalProcessId() == root)
  {
    std::copy(text.begin(), text.end(), buffer.begin());
  }
  controller->Broadcast(buffer.data(), length + 1, root);
  return std::string(buffer.data(), static_cast<size_t>(length));
}

/// A 62-bit FNV-1a hash of `text` (non-negative, so that its negation fits).
vtkIdType Fingerprint(const std::string& text)
{
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text)
  {
    hash = (hash ^ c) * 1099511628211ull;
  }
  return static_cast<vtkIdType>(hash >> 2);
}

/// "name=value" entries of a "name=value;name=value;..." text.
std::vector<std::string> Entries(const std::string& text)
{
  std::vector<std::string> entries;
  size_t start = 0;
  while (start < text.size())
  {
    const size_t end = text.find(';', start);
    entries.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    start = end == std::string::npos ? text.size() : end + 1;
  }
  return entries;
}

/// The first entry that differs between `mine` and `reference`, as "mine" / "reference".
void FirstDifference(const std::string& mine, const std::string& reference, std::string& ours, std::string& theirs)
{
  const std::vector<std::string> a = Entries(mine), b = Entries(reference);
  for (size_t k = 0; k < std::max(a.size(), b.size()); ++k)
  {
    ours = k < a.size() ? a[k] : "(nothing)";
    theirs = k < b.size() ? b[k] : "(nothing)";
    if (ours != theirs)
    {
      return;
    }
  }
}
}

bool AnyFailed(vtkMultiProcessController* controller, bool failed, std::string& error)
{
  const int processes = controller->GetNumberOfProcesses();
  const vtkIdType mine = failed ? processes - controller->GetLocalProcessId() : 0;
  vtkIdType lowest = 0;
  controller->AllReduce(&mine, &lowest, 1, vtkCommunicator::MAX_OP);
  if (lowest == 0)
  {
    return false;
  }
  // Every process reports the first failing process's reason.
  const int first = static_cast<int>(processes - lowest);
  error = "Process " + std::to_string(first) + " of " + std::to_string(processes) + " cannot filter its piece: " +
    BroadcastText(controller, error, first);
  return true;
}

bool Agree(vtkMultiProcessController* controller, const std::string& localError,
  const std::string& parameters, const std::string& arrays, std::string& error)
{
  // One reduction: the first failing process, and whether the fingerprints of
  // the parameters and of the arrays (processes with data only) are the same everywhere.
  const int me = controller->GetLocalProcessId();
  const int processes = controller->GetNumberOfProcesses();
  const vtkIdType none = std::numeric_limits<vtkIdType>::min() / 2;
  const vtkIdType p = Fingerprint(parameters);
  const vtkIdType a = arrays.empty() ? none : Fingerprint(arrays);
  const vtkIdType local[5] = { localError.empty() ? 0 : processes - me, p, -p, a, a == none ? none : -a };
  vtkIdType global[5];
  controller->AllReduce(local, global, 5, vtkCommunicator::MAX_OP);
  if (global[0] > 0)
  {
    const int first = static_cast<int>(processes - global[0]);
    error = "Process " + std::to_string(first) + " of " + std::to_string(processes) +
      " cannot filter its piece: " + BroadcastText(controller, localError, first);
    return false;
  }
  const bool sameParameters = global[1] == -global[2];
  const bool sameArrays = global[3] == none || global[3] == -global[4];
  if (sameParameters && sameArrays)
  {
    return true;
  }
  // Name the first process that differs from the reference (process 0's
  // parameters; the arrays of the first process with data) and what differs.
  const std::string& mineText = sameParameters ? arrays : parameters;
  const vtkIdType hasData = arrays.empty() ? processes : me;
  vtkIdType reference = 0;
  if (!sameParameters)
  {
    reference = 0;
  }
  else
  {
    controller->AllReduce(&hasData, &reference, 1, vtkCommunicator::MIN_OP);
  }
  reference = std::min<vtkIdType>(reference, processes - 1);
  const std::string referenceText = BroadcastText(controller, mineText, static_cast<int>(reference));
  const vtkIdType differs = (!mineText.empty() && mineText != referenceText) ? me : processes;
  vtkIdType firstDiffering = processes;
  controller->AllReduce(&differs, &firstDiffering, 1, vtkCommunicator::MIN_OP);
  firstDiffering = std::min<vtkIdType>(firstDiffering, processes - 1);
  std::string ours, theirs;
  FirstDifference(mineText, referenceText, ours, theirs);
  const std::string detail = BroadcastText(controller,
    "process " + std::to_string(me) + " has " + ours + " where process " + std::to_string(reference) + " has " + theirs,
    static_cast<int>(firstDiffering));
  error = std::string("The processes disagree on the filter's ") +
    (sameParameters ? "arrays" : "parameters") + ": " + detail +
    (sameParameters ? "; every piece must hold the same point and cell arrays (names, types, components) and filter the same one."
                    : "; every process must run the filter with the same parameters.");
  return false;
}

bool PrepareSurfacePiece(vtkMultiProcessController* controller, vtkPolyData* input,
  const std::string& localError, const std::string& parameters, const std::string& selection, int layers,
  SurfacePiece& piece, std::string& error)
{
  piece = SurfacePiece();
  piece.work = input;
  error = localError;
  if (!controller)
  {
    return error.empty();
  }
  const std::string arrays = ArraysFingerprintText(input);
  std::string local = localError;
  if (local.empty() && arrays.find("'(unnamed)'") != std::string::npos)
  {
    local = "a point or cell array has no name: name it (the pieces exchange their arrays by name)";
  }
  if (!Agree(controller, local, parameters, arrays.empty() ? arrays : arrays + selection, error))
  {
    return false;
  }
  vtkLogScopeF(TRACE, "shock: distribute the surface");
  if (Replicated(controller, input))
  {
    piece.skip = controller->GetLocalProcessId() != 0;
    return true; // process 0 filters the whole data set as in serial
  }
  piece.controller = controller;
  vtkNew<vtkPolyData> none;
  piece.owned = input ? OwnedCells(input) : vtkSmartPointer<vtkPolyData>(none);
  vtkLogStartScope(TRACE, "shock: ghost rings");
  piece.work = WithGhostCells(controller, piece.owned, layers, error);
  vtkLogEndScope("shock: ghost rings");
  return piece.work != nullptr; // its failures are agreed by every process already
}

namespace
{
/**
 * The needs this process owns: per asker, (slot in the asker's list, local
 * point). The asked ids (a halo) go into a table, which the owned points are
 * looked up in (a table of every owned point would be a piece).
 */
std::vector<std::vector<std::pair<vtkIdType, vtkIdType>>> OwnedAnswers(int me, int processes,
  const std::vector<vtkIdType>& all, const std::vector<vtkIdType>& counts, const std::vector<vtkIdType>& offsets,
  const vtkIdType* globalIds, const std::vector<char>& owned)
{
  std::unordered_map<vtkIdType, std::vector<std::pair<int, vtkIdType>>> wanted; // id -> (asker, slot)
  for (int r = 0; r < processes; ++r)
  {
    for (vtkIdType k = 0; r != me && k < counts[static_cast<size_t>(r)]; ++k)
    {
      wanted[all[static_cast<size_t>(offsets[static_cast<size_t>(r)] + k)]].emplace_back(r, k);
    }
  }
  std::vector<std::vector<std::pair<vtkIdType, vtkIdType>>> answers(static_cast<size_t>(processes));
  for (size_t p = 0; p < owned.size() && !wanted.empty(); ++p)
  {
    if (!owned[p])
    {
      continue;
    }
    const auto found = wanted.find(globalIds[p]);
    if (found != wanted.end())
    {
      for (const auto& asker : found->second)
      {
        answers[static_cast<size_t>(asker.first)].emplace_back(asker.second, static_cast<vtkIdType>(p));
      }
    }
  }
  return answers;
}
}

void PointExchange::Setup(vtkMultiProcessController* controller, const vtkIdType* globalIds,
  const std::vector<char>& owned, const std::vector<char>& needed)
{
  this->Controller = controller;
  const int me = controller->GetLocalProcessId();
  const int processes = controller->GetNumberOfProcesses();
  std::vector<vtkIdType> neededLocal, neededGlobal;
  for (size_t p = 0; p < needed.size(); ++p)
  {
    if (needed[p])
    {
      neededLocal.push_back(static_cast<vtkIdType>(p));
      neededGlobal.push_back(globalIds[p]);
    }
  }
  // Everyone learns everyone's needs (the ghost points only).
  std::vector<vtkIdType> counts, offsets;
  const std::vector<vtkIdType> all = AllGather(controller, neededGlobal, counts, offsets);

  auto answers = OwnedAnswers(me, processes, all, counts, offsets, globalIds, owned);
  this->SendPoints.assign(static_cast<size_t>(processes), {});
  this->ReceivePoints.assign(static_cast<size_t>(processes), {});
  std::vector<std::vector<vtkIdType>> slots(static_cast<size_t>(processes));
  std::vector<vtkIdType> sendCounts(static_cast<size_t>(processes), 0);
  for (int r = 0; r < processes; ++r)
  {
    auto& list = answers[static_cast<size_t>(r)];
    std::sort(list.begin(), list.end()); // in the asker's order
    for (const auto& answer : list)
    {
      slots[static_cast<size_t>(r)].push_back(answer.first);
      this->SendPoints[static_cast<size_t>(r)].push_back(answer.second);
    }
    sendCounts[static_cast<size_t>(r)] = static_cast<vtkIdType>(list.size());
  }
  // Who sends how much to whom, then the slots themselves.
  std::vector<vtkIdType> matrix(static_cast<size_t>(processes * processes));
  controller->AllGather(sendCounts.data(), matrix.data(), processes);
  std::vector<vtkIdType> receiveCounts(static_cast<size_t>(processes));
  for (int s = 0; s < processes; ++s)
  {
    receiveCounts[static_cast<size_t>(s)] = matrix[static_cast<size_t>(s * processes + me)];
  }
  OrderedPairs(controller, sendCounts, receiveCounts,
    [&](int r) {
      controller->Send(slots[static_cast<size_t>(r)].data(), sendCounts[static_cast<size_t>(r)], r, ExchangeTag);
    },
    [&](int s) {
      std::vector<vtkIdType> received(static_cast<size_t>(receiveCounts[static_cast<size_t>(s)]));
      controller->Receive(received.data(), receiveCounts[static_cast<size_t>(s)], s, ExchangeTag);
      for (vtkIdType slot : received)
      {
        this->ReceivePoints[static_cast<size_t>(s)].push_back(neededLocal[static_cast<size_t>(slot)]);
      }
    });
  this->Sent = std::accumulate(sendCounts.begin(), sendCounts.end(), std::int64_t(0));
  this->Received = std::accumulate(receiveCounts.begin(), receiveCounts.end(), std::int64_t(0));
}

void PointExchange::Exchange(double* values)
{
  vtkMultiProcessController* controller = this->Controller;
  const int processes = controller->GetNumberOfProcesses();
  std::vector<vtkIdType> sendCounts(static_cast<size_t>(processes)), receiveCounts(static_cast<size_t>(processes));
  for (int r = 0; r < processes; ++r)
  {
    sendCounts[static_cast<size_t>(r)] = static_cast<vtkIdType>(this->SendPoints[static_cast<size_t>(r)].size());
    receiveCounts[static_cast<size_t>(r)] = static_cast<vtkIdType>(this->ReceivePoints[static_cast<size_t>(r)].size());
  }
  std::vector<double> buffer;
  OrderedPairs(controller, sendCounts, receiveCounts,
    [&](int r) {
      const auto& points = this->SendPoints[static_cast<size_t>(r)];
      buffer.resize(3 * points.size());
      for (size_t k = 0; k < points.size(); ++k)
      {
        std::copy(values + 3 * points[k], values + 3 * points[k] + 3, &buffer[3 * k]);
      }
      controller->Send(buffer.data(), static_cast<vtkIdType>(buffer.size()), r, ExchangeTag + 1);
    },
    [&](int s) {
      const auto& points = this->ReceivePoints[static_cast<size_t>(s)];
      buffer.resize(3 * points.size());
      controller->Receive(buffer.data(), static_cast<vtkIdType>(buffer.size()), s, ExchangeTag + 1);
      for (size_t k = 0; k < points.size(); ++k)
      {
        std::copy(&buffer[3 * k], &buffer[3 * k] + 3, values + 3 * points[k]);
      }
    });
}
}
