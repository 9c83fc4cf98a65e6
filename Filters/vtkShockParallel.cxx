#include "vtkShockParallel.h"

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkGenerateGlobalIds.h"
#include "vtkGhostCellsGenerator.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
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

namespace vtkShockParallel
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
  double print[6] = { 0, 0, 0, 0, 0, 0 };
  if (input)
  {
    print[0] = static_cast<double>(input->GetNumberOfPoints());
    print[1] = static_cast<double>(input->GetNumberOfCells());
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
  double low[6], high[6], negated[6];
  for (int k = 0; k < 6; ++k)
  {
    negated[k] = -print[k];
  }
  controller->AllReduce(print, high, 6, vtkCommunicator::MAX_OP);
  controller->AllReduce(negated, low, 6, vtkCommunicator::MAX_OP);
  for (int k = 0; k < 6; ++k)
  {
    if (high[k] != -low[k])
    {
      return false;
    }
  }
  return high[0] > 0.0;
}

vtkSmartPointer<vtkPolyData> OwnedCells(vtkPolyData* piece)
{
  vtkUnsignedCharArray* ghosts = piece->GetCellGhostArray();
  if (!ghosts)
  {
    return piece;
  }
  // The own cells, type by type (vtkPolyData numbers verts, lines, polygons, strips in turn).
  vtkCellArray* inputCells[4] = { piece->GetVerts(), piece->GetLines(), piece->GetPolys(), piece->GetStrips() };
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  vtkCellArray* kept[4] = { verts, lines, polys, strips };
  vtkNew<vtkIdList> keptCells;
  std::vector<vtkIdType> newId(static_cast<size_t>(piece->GetNumberOfPoints()), -1);
  vtkIdType cell = 0;
  for (int kind = 0; kind < 4; ++kind)
  {
    auto iterator = vtk::TakeSmartPointer(inputCells[kind]->NewIterator());
    for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++cell)
    {
      if (ghosts->GetValue(cell) & vtkDataSetAttributes::DUPLICATECELL)
      {
        continue;
      }
      vtkIdType size;
      const vtkIdType* points;
      iterator->GetCurrentCell(size, points);
      kept[kind]->InsertNextCell(size, points);
      keptCells->InsertNextId(cell);
      for (vtkIdType k = 0; k < size; ++k)
      {
        newId[static_cast<size_t>(points[k])] = 0; // used
      }
    }
  }
  // The used points keep their order; their data (with the owners' marks) comes along.
  vtkNew<vtkIdList> keptPoints;
  for (size_t p = 0; p < newId.size(); ++p)
  {
    if (newId[p] == 0)
    {
      newId[p] = keptPoints->GetNumberOfIds();
      keptPoints->InsertNextId(static_cast<vtkIdType>(p));
    }
  }
  for (vtkCellArray* cells : kept)
  {
    vtkDataArray* connectivity = cells->GetConnectivityArray();
    for (vtkIdType k = 0; k < connectivity->GetNumberOfTuples(); ++k)
    {
      connectivity->SetTuple1(k, static_cast<double>(newId[static_cast<size_t>(connectivity->GetTuple1(k))]));
    }
  }
  auto owned = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataType(piece->GetPoints()->GetDataType());
  piece->GetPoints()->GetPoints(keptPoints, points);
  owned->SetPoints(points);
  owned->SetVerts(verts);
  owned->SetLines(lines);
  owned->SetPolys(polys);
  owned->SetStrips(strips);
  owned->GetFieldData()->ShallowCopy(piece->GetFieldData());
  owned->GetPointData()->CopyAllocate(piece->GetPointData(), keptPoints->GetNumberOfIds());
  for (vtkIdType k = 0; k < keptPoints->GetNumberOfIds(); ++k)
  {
    owned->GetPointData()->CopyData(piece->GetPointData(), keptPoints->GetId(k), k);
  }
  owned->GetCellData()->CopyAllocate(piece->GetCellData(), keptCells->GetNumberOfIds());
  for (vtkIdType k = 0; k < keptCells->GetNumberOfIds(); ++k)
  {
    owned->GetCellData()->CopyData(piece->GetCellData(), keptCells->GetId(k), k);
  }
  owned->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName()); // no ghost cell left
  return owned;
}

vtkSmartPointer<vtkPolyData> OwnedPiece(vtkPolyData* filtered, vtkPolyData* input)
{
  vtkSmartPointer<vtkPolyData> owned = OwnedCells(filtered);
  for (vtkDataSetAttributes* attributes :
    { static_cast<vtkDataSetAttributes*>(owned->GetPointData()), static_cast<vtkDataSetAttributes*>(owned->GetCellData()) })
  {
    vtkDataArray* made = attributes->GetGlobalIds();
    vtkDataSetAttributes* given = attributes == owned->GetPointData()
      ? static_cast<vtkDataSetAttributes*>(input->GetPointData())
      : static_cast<vtkDataSetAttributes*>(input->GetCellData());
    if (made && made->GetName() && !given->GetGlobalIds())
    {
      attributes->RemoveArray(made->GetName());
    }
  }
  return owned;
}

vtkSmartPointer<vtkPolyData> WithGhostCells(
  vtkMultiProcessController* controller, vtkPolyData* piece, int layers, std::string& error)
{
  vtkNew<vtkPolyData> tagged;
  tagged->ShallowCopy(piece);
  vtkSmartPointer<vtkDataObject> source = tagged.GetPointer();
  vtkNew<vtkGenerateGlobalIds> ids;
  if (!piece->GetPointData()->GetGlobalIds())
  {
    ids->SetController(controller);
    ids->SetInputData(tagged);
    ids->Update();
    source = ids->GetOutputDataObject(0);
  }
  vtkNew<vtkGhostCellsGenerator> generator;
  generator->SetController(controller);
  generator->BuildIfRequiredOff();
  generator->SetNumberOfGhostLayers(layers);
  generator->SetInputData(source);
  generator->Update();
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(generator->GetOutputDataObject(0));

  if (result->GetNumberOfCells() < piece->GetNumberOfCells())
  {
    error = "the ghost cells generator lost cells of the piece";
    return nullptr;
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

void MarkPointOwners(vtkMultiProcessController* controller, vtkPolyData* piece)
{
  const vtkIdType np = piece->GetNumberOfPoints();
  vtkDataArray* ids = piece->GetPointData()->GetGlobalIds();
  vtkUnsignedCharArray* cellGhosts = piece->GetCellGhostArray();
  // Which points the piece's own cells use, and which its ghost cells use.
  std::vector<char> inOwned(static_cast<size_t>(np), 0), inGhost(static_cast<size_t>(np), 0);
  std::map<std::pair<vtkIdType, vtkIdType>, int> ownedEdges; // polygon edges of the own cells
  vtkIdType cell = 0;
  for (vtkCellArray* cells : { piece->GetVerts(), piece->GetLines(), piece->GetPolys(), piece->GetStrips() })
  {
    auto iterator = vtk::TakeSmartPointer(cells->NewIterator());
    for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++cell)
    {
      vtkIdType size;
      const vtkIdType* points;
      iterator->GetCurrentCell(size, points);
      const bool ghost = cellGhosts && (cellGhosts->GetValue(cell) & vtkDataSetAttributes::DUPLICATECELL);
      for (vtkIdType k = 0; k < size; ++k)
      {
        (ghost ? inGhost : inOwned)[static_cast<size_t>(points[k])] = 1;
        if (!ghost && cells == piece->GetPolys() && size > 1)
        {
          const vtkIdType a = points[k], b = points[(k + 1) % size];
          ++ownedEdges[{ std::min(a, b), std::max(a, b) }];
        }
      }
    }
  }
  // A point on the border of several pieces' own cells belongs to the lowest process among them.
  // The border: points next to ghost cells, and ends of edges only one own polygon has
  // (pieces may touch at corners only, where no ghost cell was made).
  for (const auto& edge : ownedEdges)
  {
    if (edge.second == 1)
    {
      inGhost[static_cast<size_t>(edge.first.first)] = inGhost[static_cast<size_t>(edge.first.second)] = 1;
    }
  }
  std::vector<vtkIdType> border;
  for (vtkIdType p = 0; ids && p < np; ++p)
  {
    if (inOwned[static_cast<size_t>(p)] && inGhost[static_cast<size_t>(p)])
    {
      border.push_back(static_cast<vtkIdType>(ids->GetTuple1(p)));
    }
  }
  std::vector<vtkIdType> counts, offsets;
  const std::vector<vtkIdType> all = AllGather(controller, border, counts, offsets);
  const int me = controller->GetLocalProcessId();
  std::unordered_map<vtkIdType, int> lowest;
  for (int r = 0; r < me; ++r)
  {
    for (vtkIdType k = 0; k < counts[static_cast<size_t>(r)]; ++k)
    {
      lowest.emplace(all[static_cast<size_t>(offsets[static_cast<size_t>(r)] + k)], r);
    }
  }
  vtkNew<vtkUnsignedCharArray> marks;
  marks->SetName(vtkDataSetAttributes::GhostArrayName());
  marks->SetNumberOfTuples(np);
  vtkUnsignedCharArray* old = PointGhosts(piece);
  for (vtkIdType p = 0; p < np; ++p)
  {
    const bool owned = inOwned[static_cast<size_t>(p)] &&
      !(ids && inGhost[static_cast<size_t>(p)] && lowest.count(static_cast<vtkIdType>(ids->GetTuple1(p))));
    const unsigned char other = old ? (old->GetValue(p) & ~vtkDataSetAttributes::DUPLICATEPOINT) : 0;
    marks->SetValue(p, static_cast<unsigned char>(other | (owned ? 0 : vtkDataSetAttributes::DUPLICATEPOINT)));
  }
  piece->GetPointData()->AddArray(marks); // replaces the generator's marks
}

bool AnyFailed(vtkMultiProcessController* controller, bool failed, std::string& error)
{
  const int failures = Count(controller, failed);
  if (failures > 0 && !failed)
  {
    error = "another process could not filter its piece (its message says why)";
  }
  return failures > 0;
}

bool PrepareSurfacePiece(vtkMultiProcessController* controller, vtkPolyData* input,
  const std::string& localError, int layers, SurfacePiece& piece, std::string& error)
{
  piece = SurfacePiece();
  piece.work = input;
  error = localError;
  if (!controller)
  {
    return error.empty();
  }
  if (AnyFailed(controller, !error.empty(), error))
  {
    return false;
  }
  if (Replicated(controller, input))
  {
    piece.skip = controller->GetLocalProcessId() != 0;
    return true; // process 0 filters the whole data set as in serial
  }
  piece.controller = controller;
  vtkNew<vtkPolyData> none;
  piece.work = WithGhostCells(controller, input ? OwnedCells(input).GetPointer() : none.GetPointer(),
    layers, error);
  if (AnyFailed(controller, !piece.work, error))
  {
    return false;
  }
  MarkPointOwners(controller, piece.work);
  return true;
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

  // Answer the needs this process owns: which local points, at which slots of the asker's list.
  std::unordered_map<vtkIdType, vtkIdType> ownedByGlobal;
  for (size_t p = 0; p < owned.size(); ++p)
  {
    if (owned[p])
    {
      ownedByGlobal.emplace(globalIds[p], static_cast<vtkIdType>(p));
    }
  }
  this->SendPoints.assign(static_cast<size_t>(processes), {});
  this->ReceivePoints.assign(static_cast<size_t>(processes), {});
  std::vector<std::vector<vtkIdType>> slots(static_cast<size_t>(processes));
  std::vector<vtkIdType> sendCounts(static_cast<size_t>(processes), 0);
  for (int r = 0; r < processes; ++r)
  {
    if (r == me)
    {
      continue;
    }
    for (vtkIdType k = 0; k < counts[static_cast<size_t>(r)]; ++k)
    {
      const auto found = ownedByGlobal.find(all[static_cast<size_t>(offsets[static_cast<size_t>(r)] + k)]);
      if (found != ownedByGlobal.end())
      {
        this->SendPoints[static_cast<size_t>(r)].push_back(found->second);
        slots[static_cast<size_t>(r)].push_back(k);
      }
    }
    sendCounts[static_cast<size_t>(r)] = static_cast<vtkIdType>(slots[static_cast<size_t>(r)].size());
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
