/**
 * @file ShockParallel.cxx
 * @brief The parallel steps every filter shares: which controller runs the
 * collectives, the agreement of the pieces, sums and ranges over them.
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
  // The sizes first: pieces of different sizes (the usual case) are not
  // replicated, and need no pass over their cells and points.
  const double points = input ? static_cast<double>(input->GetNumberOfPoints()) : 0.0;
  const double cells = input ? static_cast<double>(input->GetNumberOfCells()) : 0.0;
  const double sizes[4] = { points, cells, -points, -cells }; // largest, and minus the smallest
  double extremes[4];
  controller->AllReduce(sizes, extremes, 4, vtkCommunicator::MAX_OP);
  if (extremes[0] != -extremes[2] || extremes[1] != -extremes[3] || !(extremes[0] > 0.0))
  {
    return false;
  }
  // A fingerprint: sizes, and sums of the coordinates weighted two ways (so
  // that a permutation or a different piece shows).
  double print[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
  if (input)
  {
    print[0] = points;
    print[1] = cells;
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

int MoreLayers(vtkMultiProcessController* controller, bool aborted, int needed, int layers, int most, bool& tooFew,
  bool* anyAborted)
{
  int wanted = layers;
  int beyond = 0;
  if (!aborted && needed > layers)
  {
    // Two layers more than this piece's traces needed: with the exact flow they may run a little further.
    wanted = std::min(most, std::max(layers + 1, needed + 2));
    beyond = layers >= most ? 1 : 0;
  }
  const int local[3] = { aborted ? 1 : 0, wanted, beyond };
  int global[3] = { 0, 0, 0 };
  controller->AllReduce(local, global, 3, vtkCommunicator::MAX_OP);
  tooFew = global[0] == 0 && global[2] != 0;
  if (anyAborted)
  {
    *anyAborted = global[0] != 0;
  }
  return global[0] != 0 ? layers : std::max(layers, global[1]);
}

bool Agree(vtkMultiProcessController* controller, const std::string& localError,
  const std::string& parameters, const std::string& arrays, std::string& error, const std::string& grid)
{
  // One reduction: the first failing process, and whether the fingerprints of
  // the parameters, of the arrays (processes with data only) and of the grid
  // (when given) are the same everywhere.
  const int me = controller->GetLocalProcessId();
  const int processes = controller->GetNumberOfProcesses();
  const vtkIdType none = std::numeric_limits<vtkIdType>::min() / 2;
  const vtkIdType p = Fingerprint(parameters);
  const vtkIdType a = arrays.empty() ? none : Fingerprint(arrays);
  const vtkIdType g = grid.empty() ? none : Fingerprint(grid);
  const vtkIdType local[7] = { localError.empty() ? 0 : processes - me, p, -p, a, a == none ? none : -a, g,
    g == none ? none : -g };
  vtkIdType global[7];
  controller->AllReduce(local, global, 7, vtkCommunicator::MAX_OP);
  if (global[0] > 0)
  {
    const int first = static_cast<int>(processes - global[0]);
    error = "Process " + std::to_string(first) + " of " + std::to_string(processes) +
      " cannot filter its piece: " + BroadcastText(controller, localError, first);
    return false;
  }
  const bool sameParameters = global[1] == -global[2];
  const bool sameArrays = global[3] == none || global[3] == -global[4];
  const bool sameGrid = global[5] == none || global[5] == -global[6];
  if (sameParameters && sameArrays && sameGrid)
  {
    return true;
  }
  // Name the first process that differs from the reference (process 0's
  // parameters; the arrays or grid of the first process that has them) and what differs.
  const char* what = !sameParameters ? "filter's parameters" : !sameArrays ? "filter's arrays" : "image's grid";
  const std::string& mineText = !sameParameters ? parameters : !sameArrays ? arrays : grid;
  const vtkIdType hasData = mineText.empty() ? processes : me;
  vtkIdType reference = 0;
  if (sameParameters)
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
  const std::string why = !sameParameters
    ? "; every process must run the filter with the same parameters."
    : !sameArrays ? "; every piece must hold the same point and cell arrays (names, types, components) and filter the same one."
                  : "; the pieces must be pieces of one image (the same whole extent, origin, spacing and direction).";
  error = std::string("The processes disagree on the ") + what + ": " + detail + why;
  return false;
}

bool PrepareSurfacePiece(vtkMultiProcessController* controller, vtkPolyData* input,
  const std::string& localError, const std::string& parameters, const std::string& selection, int layers,
  const CarriedArrays& carried, SurfacePiece& piece, std::string& error)
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
  piece.work = WithGhostCells(controller, Carrying(piece.owned, carried), layers, error, &piece.cellRing);
  piece.rings = layers;
  vtkLogEndScope("shock: ghost rings");
  return piece.work != nullptr; // its failures are agreed by every process already
}

}
