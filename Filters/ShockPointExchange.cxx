/**
 * @file ShockPointExchange.cxx
 * @brief PointExchange: the values of a distributed surface's shared points,
 * from their owners to the pieces that hold copies, point to point.
 */
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

std::vector<char> PointExchange::SentMask(std::int64_t count) const
{
  std::vector<char> mask(static_cast<size_t>(count), 0);
  for (const auto& points : this->SendPoints)
  {
    for (vtkIdType p : points)
    {
      mask[static_cast<size_t>(p)] = 1;
    }
  }
  return mask;
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
