/**
 * @file ShockGhostPackets.cxx
 * @brief How the ghost rings' answers travel (ShockGhostCells.h, step 3): a
 * packet (a vtkPolyData of cells, their points and arrays) as raw blocks of
 * memory, or through VTK's marshalling when an array does not allow that.
 */
#include "ShockGhostCells.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace ShockParallel
{
namespace ghost
{
namespace
{
/**
 * A packet's bytes: its points, cells and the point and cell arrays, each
 * block as it lies in memory (the pieces run on one kind of machine: MPI
 * moves bytes between processes of one build), behind a tag. VTK's
 * marshalling (a legacy file, every value byte-swapped) is the fallback for
 * an array that does not hold its values contiguously (strings, bits, ...).
 */
constexpr std::int64_t RawTag = 0x5348434B52415731; // "SHCKRAW1"

struct Writer
{
  std::vector<char>& bytes;
  void Word(std::int64_t w) { this->Block(&w, sizeof(w)); }
  void Block(const void* data, size_t size)
  {
    const size_t at = this->bytes.size();
    this->bytes.resize(at + ((size + 7) / 8) * 8, 0);
    if (size > 0)
    {
      std::memcpy(this->bytes.data() + at, data, size);
    }
  }
};

struct Reader
{
  const char* at;
  const char* end;
  bool ok = true;
  std::int64_t Word()
  {
    std::int64_t w = 0;
    this->Block(&w, sizeof(w));
    return w;
  }
  void Block(void* data, size_t size)
  {
    const size_t padded = ((size + 7) / 8) * 8;
    if (!this->ok || static_cast<size_t>(this->end - this->at) < padded)
    {
      this->ok = false;
      return;
    }
    if (size > 0)
    {
      std::memcpy(data, this->at, size);
    }
    this->at += padded;
  }
};

bool RawArray(vtkAbstractArray* array)
{
  auto* data = vtkDataArray::SafeDownCast(array);
  return data && data->HasStandardMemoryLayout() && data->GetDataType() != VTK_BIT && data->GetDataTypeSize() > 0;
}

void WriteArray(Writer& out, vtkDataArray* array)
{
  const std::string name = array->GetName() ? array->GetName() : ""; // the coordinates have none
  out.Word(static_cast<std::int64_t>(name.size()));
  out.Block(name.data(), name.size());
  out.Word(array->GetDataType());
  out.Word(array->GetNumberOfComponents());
  out.Word(array->GetNumberOfTuples());
  out.Block(array->GetVoidPointer(0),
    static_cast<size_t>(array->GetNumberOfValues()) * static_cast<size_t>(array->GetDataTypeSize()));
}

vtkSmartPointer<vtkDataArray> ReadArray(Reader& in)
{
  const std::int64_t length = in.Word();
  if (!in.ok || length < 0 || length > in.end - in.at)
  {
    in.ok = false; // a damaged buffer: sizes are checked before anything is allocated
    return nullptr;
  }
  std::string name(static_cast<size_t>(length), '\0');
  in.Block(&name[0], name.size());
  const int type = static_cast<int>(in.Word());
  const int components = static_cast<int>(in.Word());
  const vtkIdType tuples = in.Word();
  if (!in.ok || components < 1 || tuples < 0 || tuples > (in.end - in.at) / components)
  {
    in.ok = false;
    return nullptr;
  }
  auto array = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(type));
  if (!array)
  {
    in.ok = false;
    return nullptr;
  }
  if (!name.empty())
  {
    array->SetName(name.c_str());
  }
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  in.Block(array->GetVoidPointer(0),
    static_cast<size_t>(array->GetNumberOfValues()) * static_cast<size_t>(array->GetDataTypeSize()));
  return array;
}

}

/// `packet` into `buffer`: raw blocks when every array allows, else VTK's marshalling.
void PackPacket(vtkPolyData* packet, vtkCharArray* buffer)
{
  vtkDataSetAttributes* attributes[2] = { packet->GetPointData(), packet->GetCellData() };
  bool raw = RawArray(packet->GetPoints()->GetData());
  for (vtkDataSetAttributes* data : attributes)
  {
    for (int k = 0; k < data->GetNumberOfArrays() && raw; ++k)
    {
      raw = RawArray(data->GetAbstractArray(k));
    }
  }
  if (!raw)
  {
    vtkCommunicator::MarshalDataObject(packet, buffer);
    return;
  }
  std::vector<char> bytes;
  Writer out{ bytes };
  out.Word(RawTag);
  WriteArray(out, packet->GetPoints()->GetData());
  vtkCellArray* polys = packet->GetPolys();
  vtkNew<vtkIdTypeArray> connectivity;
  polys->ExportLegacyFormat(connectivity); // (size, ids...) per cell: one block
  out.Word(polys->GetNumberOfCells());
  WriteArray(out, connectivity);
  for (vtkDataSetAttributes* data : attributes)
  {
    out.Word(data->GetNumberOfArrays());
    for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    {
      WriteArray(out, data->GetArray(k));
    }
  }
  buffer->SetNumberOfValues(static_cast<vtkIdType>(bytes.size()));
  std::memcpy(buffer->GetPointer(0), bytes.data(), bytes.size());
}

/// The packet of `buffer` (PackPacket's either way); false when it is damaged.
bool UnpackPacket(vtkCharArray* buffer, vtkPolyData* packet)
{
  std::int64_t tag = 0;
  if (buffer->GetNumberOfValues() >= 8)
  {
    std::memcpy(&tag, buffer->GetPointer(0), sizeof(tag));
  }
  if (tag != RawTag)
  {
    return vtkCommunicator::UnMarshalDataObject(buffer, packet) != 0;
  }
  Reader in{ buffer->GetPointer(0) + 8, buffer->GetPointer(0) + buffer->GetNumberOfValues() };
  vtkSmartPointer<vtkDataArray> coordinates = ReadArray(in);
  const vtkIdType cells = in.Word();
  vtkSmartPointer<vtkDataArray> legacy = ReadArray(in);
  auto* ids = vtkIdTypeArray::SafeDownCast(legacy);
  if (!in.ok || !coordinates || coordinates->GetNumberOfComponents() != 3 || !ids)
  {
    return false;
  }
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  packet->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  polys->ImportLegacyFormat(ids);
  if (polys->GetNumberOfCells() != cells)
  {
    return false;
  }
  packet->SetPolys(polys);
  vtkDataSetAttributes* attributes[2] = { packet->GetPointData(), packet->GetCellData() };
  for (vtkDataSetAttributes* data : attributes)
  {
    const std::int64_t count = in.Word();
    for (std::int64_t k = 0; k < count && in.ok; ++k)
    {
      vtkSmartPointer<vtkDataArray> array = ReadArray(in);
      if (array)
      {
        data->AddArray(array);
      }
    }
  }
  return in.ok;
}
}
}
