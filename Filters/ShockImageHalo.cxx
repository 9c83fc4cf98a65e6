/**
 * @file ShockImageHalo.cxx
 * @brief The halo of an image piece: the samples around it that other
 * processes hold, exchanged point to point (ShockParallel::GrowImageSamples).
 */
#include "ShockParallel.h"

#include "GridShockAdvection.h" // shock::LayeredSignalOverlap

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace ShockParallel
{
namespace
{
constexpr int HaloTag = 84671;

using Box = std::array<int, 6>;

bool Empty(const Box& box)
{
  return box[0] > box[1] || box[2] > box[3] || box[4] > box[5];
}

Box Intersect(const Box& a, const Box& b)
{
  return { std::max(a[0], b[0]), std::min(a[1], b[1]), std::max(a[2], b[2]), std::min(a[3], b[3]),
    std::max(a[4], b[4]), std::min(a[5], b[5]) };
}

vtkIdType Samples(const Box& box)
{
  return Empty(box) ? 0
                    : static_cast<vtkIdType>(box[1] - box[0] + 1) * (box[3] - box[2] + 1) * (box[5] - box[4] + 1);
}

bool Inside(const Box& box, const int ijk[3])
{
  return box[0] <= ijk[0] && ijk[0] <= box[1] && box[2] <= ijk[1] && ijk[1] <= box[3] && box[4] <= ijk[2] &&
    ijk[2] <= box[5];
}

/**
 * Whether the boxes cover `target`: every cell of the grid their faces make
 * inside `target` lies in one of them (exact, and cheap for the few boxes
 * that touch a piece's halo).
 */
bool Covered(const Box& target, const std::vector<Box>& boxes)
{
  std::vector<Box> touching;
  for (const Box& box : boxes)
  {
    if (!Empty(Intersect(box, target)))
    {
      touching.push_back(Intersect(box, target));
    }
  }
  std::array<std::vector<int>, 3> cuts;
  for (int a = 0; a < 3; ++a)
  {
    cuts[a] = { target[2 * a], target[2 * a + 1] + 1 };
    for (const Box& box : touching)
    {
      cuts[a].push_back(box[2 * a]);
      cuts[a].push_back(box[2 * a + 1] + 1);
    }
    std::sort(cuts[a].begin(), cuts[a].end());
    cuts[a].erase(std::unique(cuts[a].begin(), cuts[a].end()), cuts[a].end());
  }
  for (size_t i = 0; i + 1 < cuts[0].size(); ++i)
  {
    for (size_t j = 0; j + 1 < cuts[1].size(); ++j)
    {
      for (size_t k = 0; k + 1 < cuts[2].size(); ++k)
      {
        const int corner[3] = { cuts[0][i], cuts[1][j], cuts[2][k] };
        if (!std::any_of(touching.begin(), touching.end(), [&](const Box& box) { return Inside(box, corner); }))
        {
          return false;
        }
      }
    }
  }
  return true;
}

/// Copy the samples of `part` between two boxes' row-major buffers (x fastest).
void CopyBox(const char* from, const Box& fromBox, char* to, const Box& toBox, const Box& part, size_t tupleBytes)
{
  const vtkIdType fromX = fromBox[1] - fromBox[0] + 1, fromY = fromBox[3] - fromBox[2] + 1;
  const vtkIdType toX = toBox[1] - toBox[0] + 1, toY = toBox[3] - toBox[2] + 1;
  const size_t rowBytes = static_cast<size_t>(part[1] - part[0] + 1) * tupleBytes;
  for (int z = part[4]; z <= part[5]; ++z)
  {
    for (int y = part[2]; y <= part[3]; ++y)
    {
      const vtkIdType source = ((z - fromBox[4]) * fromY + (y - fromBox[2])) * fromX + (part[0] - fromBox[0]);
      const vtkIdType target = ((z - toBox[4]) * toY + (y - toBox[2])) * toX + (part[0] - toBox[0]);
      std::memcpy(to + static_cast<size_t>(target) * tupleBytes, from + static_cast<size_t>(source) * tupleBytes,
        rowBytes);
    }
  }
}

/// Every process's held extent and piece as sample extents (an empty piece: empty boxes). Collective.
void GatherPieces(vtkMultiProcessController* controller, bool has, const int held[6], const int own[6],
  std::vector<Box>& helds, std::vector<Box>& owns)
{
  const int processes = controller->GetNumberOfProcesses();
  vtkIdType mine[12];
  for (int k = 0; k < 6; ++k)
  {
    mine[k] = has ? held[k] : (k % 2 == 0 ? 1 : 0);
    mine[6 + k] = has ? own[k] : (k % 2 == 0 ? 1 : 0);
  }
  std::vector<vtkIdType> all(static_cast<size_t>(12 * processes));
  controller->AllGather(mine, all.data(), 12);
  helds.assign(static_cast<size_t>(processes), Box{});
  owns.assign(static_cast<size_t>(processes), Box{});
  for (size_t r = 0; r < static_cast<size_t>(processes); ++r)
  {
    for (size_t k = 0; k < 6; ++k)
    {
      helds[r][k] = static_cast<int>(all[12 * r + k]);
      owns[r][k] = static_cast<int>(all[12 * r + 6 + k]);
    }
  }
}

/**
 * The whole image's samples: the box around every piece (the same on every
 * process, whatever each one's pipeline says of the whole extent).
 */
Box WholeBox(const std::vector<Box>& pieces)
{
  Box whole{ 1, 0, 1, 0, 1, 0 };
  bool first = true;
  for (const Box& piece : pieces)
  {
    if (Empty(piece))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      whole[2 * a] = first ? piece[2 * a] : std::min(whole[2 * a], piece[2 * a]);
      whole[2 * a + 1] = first ? piece[2 * a + 1] : std::max(whole[2 * a + 1], piece[2 * a + 1]);
    }
    first = false;
  }
  return whole;
}

/**
 * Every piece's grown extent: `layers` more on the axes the whole image spans,
 * unless the held extents do not cover it (then no halo for that piece: the
 * same decision on every process, from the same extents).
 */
std::vector<Box> HaloBoxes(const std::vector<Box>& owns, const std::vector<Box>& helds, int layers)
{
  const Box whole = WholeBox(helds);
  std::vector<Box> halos(owns.size());
  for (size_t r = 0; r < owns.size(); ++r)
  {
    Box& halo = halos[r];
    halo = owns[r];
    if (Empty(halo))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      if (whole[2 * a + 1] > whole[2 * a])
      {
        halo[2 * a] = std::max(whole[2 * a], halo[2 * a] - layers);
        halo[2 * a + 1] = std::min(whole[2 * a + 1], halo[2 * a + 1] + layers);
      }
    }
    if (!Covered(halo, helds))
    {
      halo = owns[r];
    }
  }
  return halos;
}

/// Where held and received samples go: the samples of `box`, row-major, at `bytes`.
struct Destination
{
  Box box;
  char* bytes;
};

/**
 * Point to point, in one global order of (sender, receiver) pairs (no
 * deadlock): each process sends the part of its held samples in a receiver's
 * halo that the receiver does not hold itself (all of it when not contained),
 * and copies what it holds and what it receives into each of the
 * `destinations` (its halo box's samples as one array, or the layers below and
 * above its piece). Where held extents overlap, a sample may arrive from two
 * processes: the same value.
 */
void ExchangeHalos(vtkMultiProcessController* controller, const std::vector<Box>& helds,
  const std::vector<Box>& halos, const char* heldBytes, const std::vector<Destination>& destinations,
  size_t tupleBytes)
{
  const int me = controller->GetLocalProcessId();
  const int processes = controller->GetNumberOfProcesses();
  auto part = [&](int sender, int receiver) {
    const Box shared = Intersect(helds[static_cast<size_t>(sender)], halos[static_cast<size_t>(receiver)]);
    const Box inside = Intersect(shared, helds[static_cast<size_t>(receiver)]);
    return sender == receiver || Empty(shared) || inside == shared ? Box{ 1, 0, 1, 0, 1, 0 } : shared;
  };
  const Box& mine = helds[static_cast<size_t>(me)];
  // Each destination gets its samples of `box` from `bytes` (a buffer of `from`).
  const auto deliver = [&](const char* bytes, const Box& from, const Box& box) {
    for (const Destination& to : destinations)
    {
      const Box part = Intersect(box, to.box);
      if (!Empty(part))
      {
        CopyBox(bytes, from, to.bytes, to.box, part, tupleBytes);
      }
    }
  };
  deliver(heldBytes, mine, Intersect(mine, halos[static_cast<size_t>(me)]));
  std::vector<char> buffer;
  for (int a = 0; a < processes; ++a)
  {
    for (int b = 0; b < processes; ++b)
    {
      if (a == b || (a != me && b != me))
      {
        continue;
      }
      const Box box = part(a, b);
      const vtkIdType count = Samples(box);
      if (count == 0 || Empty(helds[static_cast<size_t>(a)]) || Empty(helds[static_cast<size_t>(b)]))
      {
        continue;
      }
      buffer.resize(static_cast<size_t>(count) * tupleBytes);
      if (a == me)
      {
        CopyBox(heldBytes, mine, buffer.data(), box, box, tupleBytes);
        controller->Send(buffer.data(), static_cast<vtkIdType>(buffer.size()), b, HaloTag);
      }
      else
      {
        controller->Receive(buffer.data(), static_cast<vtkIdType>(buffer.size()), a, HaloTag);
        deliver(buffer.data(), box, box);
      }
    }
  }
}

/**
 * The axis along which the grown box `target` adds layers to the piece `own`
 * (ImageLayers): its last axis of more than one sample, or -1 when the halo
 * is not only along it, or the array cannot be read in place.
 */
int LayersAxis(vtkDataArray* array, const Box& held, const Box& own, const Box& target)
{
  if (!ReadableInLayers(array) || held != own || target == own)
  {
    return -1;
  }
  return HaloLayersAxis(own.data(), target.data());
}
}

bool ReadableInLayers(vtkDataArray* array)
{
  const int type = array ? array->GetDataType() : VTK_VOID;
  return array && array->HasStandardMemoryLayout() &&
    (type == VTK_FLOAT || type == VTK_DOUBLE || type == VTK_UNSIGNED_CHAR);
}

int HaloLayersAxis(const int piece[6], const int halo[6])
{
  int axis = -1;
  for (int a = 0; a < 3; ++a)
  {
    axis = halo[2 * a + 1] > halo[2 * a] ? a : axis;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (a != axis && (halo[2 * a] != piece[2 * a] || halo[2 * a + 1] != piece[2 * a + 1]))
    {
      return -1;
    }
  }
  return axis;
}

vtkSmartPointer<vtkDataArray> GrowImageSamples(vtkMultiProcessController* controller, vtkDataArray* array,
  const int held[6], const int own[6], int layers, int grown[6])
{
  return GrowImageSamples(controller, array, held, own, layers, grown, nullptr);
}

vtkSmartPointer<vtkDataArray> GrowImageSamples(vtkMultiProcessController* controller, vtkDataArray* array,
  const int held[6], const int own[6], int layers, int grown[6], ImageLayers* layered)
{
  const int me = controller->GetLocalProcessId();
  const bool has = array && array->GetNumberOfTuples() > 0;
  std::vector<Box> helds;
  std::vector<Box> owns;
  GatherPieces(controller, has, held, own, helds, owns);
  const std::vector<Box> halos = HaloBoxes(owns, helds, layers);
  const Box& target = halos[static_cast<size_t>(me)];
  std::copy(target.begin(), target.end(), grown);
  if (!has)
  {
    // Nothing to grow; still take part in the exchange as a sender of nothing.
    return nullptr;
  }
  const int components = array->GetNumberOfComponents();
  const size_t tupleBytes = static_cast<size_t>(array->GetDataTypeSize()) * static_cast<size_t>(components);
  vtkSmartPointer<vtkDataArray> source = array;
  if (!array->HasStandardMemoryLayout())
  {
    source = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(array->GetDataType()));
    source->DeepCopy(array); // an array of structures, as the rows are copied
  }
  const auto newArray = [&](const Box& box) {
    auto made = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(array->GetDataType()));
    made->SetName(array->GetName());
    made->SetNumberOfComponents(components);
    made->CopyComponentNames(array);
    made->SetNumberOfTuples(Samples(box));
    return made;
  };
  const Box mine{ { held[0], held[1], held[2], held[3], held[4], held[5] } };
  const Box piece{ { own[0], own[1], own[2], own[3], own[4], own[5] } };
  const int axis = layered ? LayersAxis(array, mine, piece, target) : -1;
  if (axis >= 0)
  {
    // The halo in layers: below and above the piece, each with the piece's
    // layers beside it (shock::LayeredSignalOverlap); the piece where it lies.
    const int overlap = static_cast<int>(shock::LayeredSignalOverlap);
    layered->used = true;
    layered->piece = array;
    layered->pieceFirst = own[2 * axis] - target[2 * axis];
    layered->pieceEnd = own[2 * axis + 1] + 1 - target[2 * axis];
    std::vector<Destination> destinations;
    if (target[2 * axis] < own[2 * axis])
    {
      Box below = target;
      below[2 * axis + 1] = std::min(target[2 * axis + 1], own[2 * axis] + overlap - 1);
      layered->below = newArray(below);
      destinations.push_back({ below, static_cast<char*>(layered->below->GetVoidPointer(0)) });
    }
    if (target[2 * axis + 1] > own[2 * axis + 1])
    {
      Box above = target;
      above[2 * axis] = std::max(target[2 * axis], own[2 * axis + 1] + 1 - overlap);
      layered->above = newArray(above);
      destinations.push_back({ above, static_cast<char*>(layered->above->GetVoidPointer(0)) });
    }
    ExchangeHalos(
      controller, helds, halos, static_cast<const char*>(source->GetVoidPointer(0)), destinations, tupleBytes);
    return nullptr;
  }
  auto result = newArray(target);
  ExchangeHalos(controller, helds, halos, static_cast<const char*>(source->GetVoidPointer(0)),
    { Destination{ target, static_cast<char*>(result->GetVoidPointer(0)) } }, tupleBytes);
  return result;
}

vtkSmartPointer<vtkImageData> ImageWithHalo(vtkMultiProcessController* controller, vtkImageData* input,
  const int* own, vtkDataArray* array, bool cellData, bool hidden, int layers, ImageLayers* layered)
{
  // The samples held and the piece's as sample extents (cells: one fewer on
  // the axes the input spans).
  int held[6];
  int piece[6];
  input->GetExtent(held);
  std::copy(own ? own : held, (own ? own : held) + 6, piece);
  for (int a = 0; a < 3 && cellData; ++a)
  {
    const int less = held[2 * a + 1] > held[2 * a] ? 1 : 0;
    held[2 * a + 1] -= less;
    piece[2 * a + 1] -= less;
  }
  // Blanked samples: their marks travel with the halo when any piece has some
  // (decided together: the exchange is collective); the kernel then reads one
  // grown array (masked), not layers.
  int anyHidden = 0;
  const int mine = hidden ? 1 : 0;
  controller->AllReduce(&mine, &anyHidden, 1, vtkCommunicator::MAX_OP);
  int grown[6];
  vtkSmartPointer<vtkDataArray> grownArray =
    GrowImageSamples(controller, array, held, piece, layers, grown, anyHidden ? nullptr : layered);
  const bool inLayers = layered && layered->used;
  vtkSmartPointer<vtkDataArray> grownGhosts;
  if (anyHidden)
  {
    vtkUnsignedCharArray* ghosts = !array ? nullptr : (cellData ? input->GetCellGhostArray() : input->GetPointGhostArray());
    vtkNew<vtkUnsignedCharArray> none; // a piece without marks: nothing blanked
    if (array && !(ghosts && ghosts->GetNumberOfTuples() == array->GetNumberOfTuples()))
    {
      none->SetNumberOfTuples(array->GetNumberOfTuples());
      none->Fill(0);
      ghosts = none;
    }
    int grownAgain[6];
    grownGhosts = GrowImageSamples(controller, array ? ghosts : nullptr, held, piece, layers, grownAgain);
  }
  if (input->GetNumberOfPoints() == 0 || !(grownArray || inLayers))
  {
    return nullptr;
  }
  // The piece with its halo as an image of its own (the filtered array only).
  auto withHalo = vtkSmartPointer<vtkImageData>::New();
  int pointExtent[6];
  for (int a = 0; a < 3; ++a)
  {
    const bool spans = input->GetExtent()[2 * a + 1] > input->GetExtent()[2 * a];
    pointExtent[2 * a] = grown[2 * a];
    pointExtent[2 * a + 1] = grown[2 * a + 1] + (cellData && spans ? 1 : 0);
  }
  withHalo->SetExtent(pointExtent);
  withHalo->SetOrigin(input->GetOrigin());
  withHalo->SetSpacing(input->GetSpacing());
  withHalo->SetDirectionMatrix(input->GetDirectionMatrix());
  vtkDataSetAttributes* samples = cellData ? static_cast<vtkDataSetAttributes*>(withHalo->GetCellData())
                                           : static_cast<vtkDataSetAttributes*>(withHalo->GetPointData());
  if (grownArray)
  {
    samples->SetScalars(grownArray);
  }
  if (grownGhosts)
  {
    grownGhosts->SetName(vtkDataSetAttributes::GhostArrayName());
    samples->AddArray(grownGhosts);
  }
  return withHalo;
}
}
