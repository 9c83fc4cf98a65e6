/**
 * @file ShockGhostRings.cxx
 * @brief Step 3 of the ghost rings (ShockGhostCells.h): the other pieces'
 * cells within `layers` rings of the piece's own, fetched from their holders,
 * one exchange of requests and one of answers per round.
 */
#include "ShockGhostCells.h"
#include "ShockParallel.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <unordered_set>

namespace ShockParallel
{
namespace ghost
{
namespace
{
constexpr int RequestTag = 84661;
constexpr int AnswerTag = 84662;
const char* const PacketPointIds = "vtkShockGhostPointIds";
const char* const PacketCellIds = "vtkShockGhostCellIds";
const char* const PacketCellKinds = "vtkShockGhostCellKinds";
const char* const PacketBudgets = "vtkShockGhostBudgets";


/**
 * The rings as a breadth-first search over all pieces' cells from the own
 * ones: a point at ring distance k from them has a budget of layers - k, and
 * a cell is a ghost cell when one of its points has a budget >= 1. A process
 * asks the holders of a point for their own cells within its budget; each
 * searches its own piece from all the points it was asked about at once and
 * answers with the cells and their points' budgets. A point whose budget
 * grows is asked of its other holders, until nothing grows: one round for
 * most pieces (a piece's neighbours' cells within `layers` rings), more where
 * the rings cross a third piece.
 */
class RingGrower
{
public:
  RingGrower(vtkMultiProcessController* controller, vtkPolyData* piece, int layers, Numbering& numbering,
    Rings& rings);
  void Run();
  /// After Run: the ring of every ghost cell (Rings::ghostCellRing), from its points' budgets.
  void RingsOfGhostCells();

private:
  using Lists = std::vector<std::vector<vtkIdType>>;
  /// (global id, budget) of each grown point, to each of its other holders.
  Lists Requests();
  /// Who asks whom for how many values: the matrix every process gathers (row: asker).
  std::vector<vtkIdType> RequestMatrix(const Lists& requests);
  /// The requests this process receives, by asker.
  Lists ExchangeRequests(const Lists& requests, const std::vector<vtkIdType>& matrix);
  /// The own cells within the asked budgets, largest budgets first; `touched`: the points searched.
  void ChooseCells(const std::vector<vtkIdType>& asked, std::vector<vtkIdType>& chosen,
    std::vector<vtkIdType>& touched);
  /// The answer: the chosen cells with their points, point and cell data, ids and budgets.
  vtkSmartPointer<vtkPolyData> Packet(const std::vector<vtkIdType>& chosen, const std::vector<vtkIdType>& touched);
  /// Sends each answer to its asker and receives this process's answers, marshalled (`arrived`: their senders).
  std::vector<vtkSmartPointer<vtkCharArray>> ExchangeAnswers(
    const std::vector<vtkSmartPointer<vtkPolyData>>& answers, const std::vector<vtkIdType>& transposed,
    std::vector<int>& arrived);
  /// Appends a packet's new points and cells; the points whose budget grew are asked of their other holders next.
  void TakePacket(vtkCharArray* buffer, int source);

  vtkMultiProcessController* Controller;
  vtkPolyData* Piece;
  const int Layers;
  Numbering& N;
  Rings& R;
  std::vector<vtkIdType> FirstCell;       ///< global number of each process's first cell
  std::vector<int> GhostPointSource;      ///< the process that sent each ghost point
  std::unordered_set<vtkIdType> HeldCells; ///< global numbers of the ghost cells held
  std::vector<int> Budget;                ///< per local point (own: all)
  /// The points whose budget grew, with the process whose answer made it grow (me: the own points).
  std::vector<std::pair<vtkIdType, int>> Grown;
  /// The responder's search, reused across askers (reset through the touched lists).
  std::vector<int> Best;
  std::vector<int> CellTaken;
};

RingGrower::RingGrower(
  vtkMultiProcessController* controller, vtkPolyData* piece, int layers, Numbering& numbering, Rings& rings)
  : Controller(controller)
  , Piece(piece)
  , Layers(layers)
  , N(numbering)
  , R(rings)
  , FirstCell(static_cast<size_t>(numbering.processes) + 1, 0)
  , Budget(static_cast<size_t>(numbering.np), layers)
  , Best(static_cast<size_t>(numbering.np), -1)
  , CellTaken(static_cast<size_t>(numbering.own.Size()), 0)
{
  std::vector<vtkIdType> cellCounts(static_cast<size_t>(this->N.processes));
  vtkIdType count = this->N.own.Size();
  this->Controller->AllGather(&count, cellCounts.data(), 1);
  for (int r = 0; r < this->N.processes; ++r)
  {
    this->FirstCell[static_cast<size_t>(r) + 1] =
      this->FirstCell[static_cast<size_t>(r)] + cellCounts[static_cast<size_t>(r)];
  }
  for (vtkIdType p : this->N.border)
  {
    this->Grown.emplace_back(p, this->N.me);
  }
}

void RingGrower::Run()
{
  const int processes = this->N.processes;
  const int maxRounds = this->Layers * processes + 2; // budgets only grow: a bound, never reached
  for (int round = 0; round < maxRounds && this->Layers > 0; ++round)
  {
    const Lists requests = this->Requests();
    const std::vector<vtkIdType> matrix = this->RequestMatrix(requests);
    if (std::all_of(matrix.begin(), matrix.end(), [](vtkIdType v) { return v == 0; }))
    {
      break; // every piece has all its rings
    }
    const Lists asked = this->ExchangeRequests(requests, matrix);
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
      if (!asked[static_cast<size_t>(s)].empty())
      {
        std::vector<vtkIdType> chosen, touched;
        this->ChooseCells(asked[static_cast<size_t>(s)], chosen, touched);
        answers[static_cast<size_t>(s)] = this->Packet(chosen, touched);
      }
    }
    std::vector<int> arrived;
    const std::vector<vtkSmartPointer<vtkCharArray>> received = this->ExchangeAnswers(answers, transposed, arrived);
    for (size_t a = 0; a < arrived.size(); ++a)
    {
      this->TakePacket(received[a], arrived[a]);
    }
  }
}

RingGrower::Lists RingGrower::Requests()
{
  Lists requests(static_cast<size_t>(this->N.processes));
  const vtkIdType np = this->N.np;
  for (const auto& entry : this->Grown)
  {
    const vtkIdType p = entry.first;
    const int b = this->Budget[static_cast<size_t>(p)];
    if (b <= 0)
    {
      continue;
    }
    const vtkIdType key =
      p < np ? this->N.gid[static_cast<size_t>(p)] : this->R.ghostPointIds[static_cast<size_t>(p - np)];
    const int source = p < np ? this->N.me : this->GhostPointSource[static_cast<size_t>(p - np)];
    auto ask = [&](int h) {
      if (h != this->N.me && h != entry.second)
      {
        requests[static_cast<size_t>(h)].insert(requests[static_cast<size_t>(h)].end(), { key, b });
      }
    };
    const auto found = this->N.holdersById.find(key);
    if (found != this->N.holdersById.end())
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
  this->Grown.clear();
  return requests;
}

std::vector<vtkIdType> RingGrower::RequestMatrix(const Lists& requests)
{
  const int processes = this->N.processes;
  std::vector<vtkIdType> counts(static_cast<size_t>(processes));
  for (int r = 0; r < processes; ++r)
  {
    counts[static_cast<size_t>(r)] = static_cast<vtkIdType>(requests[static_cast<size_t>(r)].size());
  }
  std::vector<vtkIdType> matrix(static_cast<size_t>(processes * processes));
  this->Controller->AllGather(counts.data(), matrix.data(), processes);
  return matrix;
}

RingGrower::Lists RingGrower::ExchangeRequests(const Lists& requests, const std::vector<vtkIdType>& matrix)
{
  const int me = this->N.me, processes = this->N.processes;
  Lists asked(static_cast<size_t>(processes));
  InPairOrder(me, processes, matrix,
    [&](int r) {
      const auto& list = requests[static_cast<size_t>(r)];
      this->Controller->Send(list.data(), static_cast<vtkIdType>(list.size()), r, RequestTag);
    },
    [&](int s) {
      auto& list = asked[static_cast<size_t>(s)];
      list.resize(static_cast<size_t>(matrix[static_cast<size_t>(s * processes + me)]));
      this->Controller->Receive(list.data(), static_cast<vtkIdType>(list.size()), s, RequestTag);
    });
  return asked;
}

void RingGrower::ChooseCells(
  const std::vector<vtkIdType>& asked, std::vector<vtkIdType>& chosen, std::vector<vtkIdType>& touched)
{
  const Cells& own = this->N.own;
  std::vector<int>& best = this->Best;
  // Breadth-first from the asked points, the largest budgets first (a bucket per budget).
  std::vector<std::vector<vtkIdType>> buckets(static_cast<size_t>(this->Layers) + 1);
  for (size_t k = 0; k + 1 < asked.size(); k += 2)
  {
    const vtkIdType p = this->N.local.Own(asked[k]);
    const int b = static_cast<int>(std::min<vtkIdType>(asked[k + 1], this->Layers));
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
  for (int b = this->Layers; b >= 1; --b)
  {
    for (size_t k = 0; k < buckets[static_cast<size_t>(b)].size(); ++k)
    {
      const vtkIdType p = buckets[static_cast<size_t>(b)][k];
      if (best[static_cast<size_t>(p)] != b)
      {
        continue; // reached again with a larger budget
      }
      for (vtkIdType l = this->N.linkStart[static_cast<size_t>(p)]; l < this->N.linkStart[static_cast<size_t>(p) + 1];
           ++l)
      {
        const vtkIdType c = this->N.links[static_cast<size_t>(l)];
        if (this->CellTaken[static_cast<size_t>(c)])
        {
          continue; // taken with a budget at least b
        }
        this->CellTaken[static_cast<size_t>(c)] = 1;
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
}

vtkSmartPointer<vtkPolyData> RingGrower::Packet(
  const std::vector<vtkIdType>& chosen, const std::vector<vtkIdType>& touched)
{
  const Cells& own = this->N.own;
  vtkPolyData* piece = this->Piece;
  // The chosen cells as polygons of any size (their kinds in cell data) over their points.
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
  // Point data, with the points' global ids and budgets.
  const vtkIdType rows = pointRows->GetNumberOfIds();
  packet->GetPointData()->CopyGlobalIdsOn(); // CopyAllocate leaves them out otherwise
  packet->GetPointData()->CopyAllocate(piece->GetPointData(), rows);
  packet->GetPointData()->CopyData(piece->GetPointData(), pointRows, Sequence(rows));
  vtkNew<vtkIdTypeArray> pointIds;
  pointIds->SetName(PacketPointIds);
  pointIds->SetNumberOfTuples(rows);
  vtkNew<vtkIntArray> budgets;
  budgets->SetName(PacketBudgets);
  budgets->SetNumberOfTuples(rows);
  for (vtkIdType k = 0; k < rows; ++k)
  {
    pointIds->SetValue(k, this->N.gid[static_cast<size_t>(pointRows->GetId(k))]);
    budgets->SetValue(k, std::max(0, this->Best[static_cast<size_t>(pointRows->GetId(k))]));
  }
  packet->GetPointData()->AddArray(pointIds);
  packet->GetPointData()->AddArray(budgets);
  // Cell data, with the cells' global numbers and kinds.
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
    cellIds->InsertNextValue(this->FirstCell[static_cast<size_t>(this->N.me)] + c);
    kinds->InsertNextValue(own.kind[static_cast<size_t>(c)]);
    this->CellTaken[static_cast<size_t>(c)] = 0; // the search's marks, reset for the next asker
  }
  for (vtkIdType p : touched)
  {
    this->Best[static_cast<size_t>(p)] = -1;
  }
  packet->GetCellData()->AddArray(cellIds);
  packet->GetCellData()->AddArray(kinds);
  return packet;
}

std::vector<vtkSmartPointer<vtkCharArray>> RingGrower::ExchangeAnswers(
  const std::vector<vtkSmartPointer<vtkPolyData>>& answers, const std::vector<vtkIdType>& transposed,
  std::vector<int>& arrived)
{
  // Every process marshals its answers before the exchange and reads what it
  // received after it, so that no process waits for another's marshalling.
  const int processes = this->N.processes;
  std::vector<vtkSmartPointer<vtkCharArray>> sendBuffers(static_cast<size_t>(processes));
  for (int r = 0; r < processes; ++r)
  {
    if (answers[static_cast<size_t>(r)])
    {
      sendBuffers[static_cast<size_t>(r)] = vtkSmartPointer<vtkCharArray>::New();
      PackPacket(answers[static_cast<size_t>(r)], sendBuffers[static_cast<size_t>(r)]);
    }
  }
  std::vector<vtkSmartPointer<vtkCharArray>> received;
  InPairOrder(this->N.me, processes, transposed,
    [&](int r) {
      vtkCharArray* buffer = sendBuffers[static_cast<size_t>(r)];
      vtkIdType size = buffer->GetNumberOfValues();
      this->Controller->Send(&size, 1, r, AnswerTag);
      this->Controller->Send(buffer->GetPointer(0), size, r, AnswerTag + 1);
    },
    [&](int s) {
      vtkIdType size = 0;
      this->Controller->Receive(&size, 1, s, AnswerTag);
      auto buffer = vtkSmartPointer<vtkCharArray>::New();
      buffer->SetNumberOfValues(size);
      this->Controller->Receive(buffer->GetPointer(0), size, s, AnswerTag + 1);
      received.push_back(buffer);
      arrived.push_back(s);
    });
  return received;
}

void RingGrower::TakePacket(vtkCharArray* buffer, int source)
{
  auto packet = vtkSmartPointer<vtkPolyData>::New();
  if (!UnpackPacket(buffer, packet))
  {
    packet->Initialize(); // damaged: no arrays, so that the assembly reports a missing array
  }
  const int packetIndex = static_cast<int>(this->R.packets.size());
  this->R.packets.push_back(packet);
  auto* pointIds = vtkIdTypeArray::SafeDownCast(packet->GetPointData()->GetArray(PacketPointIds));
  auto* budgets = vtkIntArray::SafeDownCast(packet->GetPointData()->GetArray(PacketBudgets));
  auto* cellIds = vtkIdTypeArray::SafeDownCast(packet->GetCellData()->GetArray(PacketCellIds));
  auto* kinds = vtkUnsignedCharArray::SafeDownCast(packet->GetCellData()->GetArray(PacketCellKinds));
  if (!pointIds || !budgets || !cellIds || !kinds)
  {
    return;
  }
  // Points: new ones join, and every budget is the largest known.
  const vtkIdType np = this->N.np;
  std::vector<vtkIdType> localOf(static_cast<size_t>(pointIds->GetNumberOfTuples()));
  for (vtkIdType k = 0; k < pointIds->GetNumberOfTuples(); ++k)
  {
    const vtkIdType id = pointIds->GetValue(k);
    bool added = false;
    const vtkIdType p = this->N.local.Find(id, np + static_cast<vtkIdType>(this->R.ghostPoints.size()), added);
    if (added)
    {
      this->R.ghostPoints.push_back({ packetIndex, k });
      this->GhostPointSource.push_back(source);
      this->R.ghostPointIds.push_back(id);
      this->Budget.push_back(-1);
    }
    localOf[static_cast<size_t>(k)] = p;
    if (budgets->GetValue(k) > this->Budget[static_cast<size_t>(p)])
    {
      this->Budget[static_cast<size_t>(p)] = budgets->GetValue(k);
      this->Grown.emplace_back(p, source);
    }
  }
  // Cells: those not held yet, over local point ids.
  auto iterator = vtk::TakeSmartPointer(packet->GetPolys()->NewIterator());
  vtkIdType c = 0;
  std::vector<vtkIdType> ids;
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++c)
  {
    if (!this->HeldCells.insert(cellIds->GetValue(c)).second)
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
    this->R.ghost.Append(kinds->GetValue(c), n, ids.data());
    this->R.ghostCellRows.push_back({ packetIndex, c });
  }
}
}

void RingGrower::RingsOfGhostCells()
{
  // A point's final budget is Layers minus its distance (in cells) from the
  // own cells; a ghost cell is in the ring one beyond its nearest point.
  const Cells& ghost = this->R.ghost;
  this->R.ghostCellRing.assign(static_cast<size_t>(ghost.Size()), 0);
  for (vtkIdType c = 0; c < ghost.Size(); ++c)
  {
    int budget = 0;
    for (vtkIdType i = ghost.offsets[static_cast<size_t>(c)]; i < ghost.offsets[static_cast<size_t>(c) + 1]; ++i)
    {
      budget = std::max(budget, this->Budget[static_cast<size_t>(ghost.points[static_cast<size_t>(i)])]);
    }
    this->R.ghostCellRing[static_cast<size_t>(c)] =
      static_cast<unsigned char>(std::min(255, std::max(1, this->Layers + 1 - budget)));
  }
}

void GrowRings(
  vtkMultiProcessController* controller, vtkPolyData* piece, int layers, Numbering& numbering, Rings& rings)
{
  RingGrower grower(controller, piece, layers, numbering, rings);
  grower.Run();
  grower.RingsOfGhostCells();
}
}
}
