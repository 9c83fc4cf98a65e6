/**
 * @file ShockImageInternals.cxx
 * @brief The image filter's glue (ShockImageInternals.h): the checks of an
 * image and its array, blanked samples, the flow arrays, cropping and pieces.
 */
#include "ShockImageInternals.h"
#include "vtkShockAdvectionFilter.h"

#include "GridShockAdvection.h"
#include "GridGradientDomain.h"
#include "GridShockPDE.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkMultiProcessController.h"
#include "vtkCommunicator.h"
#include "vtkMatrix3x3.h"
#include "vtkDataSetAttributes.h"
#include "vtkUnsignedCharArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "ShockFilterInternals.h"
#include "ShockParallel.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>
#include <sstream>
#include <cmath>
#include <cstring>
#include <string>

namespace ShockImageInternals
{
/// The length of column `a` of the image's direction matrix: the scale it gives axis a.
double AxisScale(vtkImageData* image, int a)
{
  const vtkMatrix3x3* d = image->GetDirectionMatrix();
  return std::sqrt(d->GetElement(0, a) * d->GetElement(0, a) + d->GetElement(1, a) * d->GetElement(1, a) +
    d->GetElement(2, a) * d->GetElement(2, a));
}

std::string GridText(vtkInformation* inInfo, vtkImageData* image)
{
  std::ostringstream text;
  text.precision(12);
  text << "whole extent";
  if (inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    const int* whole = inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    for (int k = 0; k < 6; ++k)
    {
      text << ' ' << whole[k];
    }
  }
  else
  {
    text << " unknown";
  }
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  text << ";origin " << origin[0] << ' ' << origin[1] << ' ' << origin[2] << ";spacing " << spacing[0] << ' '
       << spacing[1] << ' ' << spacing[2] << ";direction";
  const double* direction = image->GetDirectionMatrix()->GetData();
  for (int k = 0; k < 9; ++k)
  {
    text << ' ' << direction[k];
  }
  return text.str();
}

std::string RepeatedPieceError(vtkMultiProcessController* controller, vtkInformation* outInfo)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  const int processes = controller->GetNumberOfProcesses();
  int mine = outInfo && outInfo->Has(SDDP::UPDATE_PIECE_NUMBER()) ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
  std::vector<int> pieces(static_cast<size_t>(processes), 0);
  controller->AllGather(&mine, pieces.data(), 1);
  std::vector<int> firstAsking(static_cast<size_t>(processes), -1);
  for (int p = 0; p < processes; ++p)
  {
    const int piece = pieces[static_cast<size_t>(p)];
    if (piece < 0 || piece >= processes)
    {
      continue; // no such piece (PieceController: as many pieces as processes)
    }
    int& first = firstAsking[static_cast<size_t>(piece)];
    if (first >= 0)
    {
      return "Process " + std::to_string(p) + " of " + std::to_string(processes) + " asks for piece " +
        std::to_string(piece) + " of " + std::to_string(processes) + ", as process " + std::to_string(first) +
        " does: each process must ask for a piece of its own (e.g. UpdatePiece(rank, number of processes, 0)), "
        "or the pieces no process asks for are missing and the halos beside them wrong.";
    }
    first = p;
  }
  return "";
}

/**
 * "" when the direction matrix is finite with orthogonal, non-zero columns
 * (a rotation or reflection of the axes, each scaled: the scales count as
 * spacing), else the message. A shear has no grid of the paper.
 */
std::string CheckDirection(vtkImageData* image)
{
  const vtkMatrix3x3* d = image->GetDirectionMatrix();
  double scale[3];
  for (int a = 0; a < 3; ++a)
  {
    for (int r = 0; r < 3; ++r)
    {
      if (!std::isfinite(d->GetElement(r, a)))
      {
        return "The image direction matrix has a non-finite entry: set a rotation (e.g. the identity).";
      }
    }
    scale[a] = AxisScale(image, a);
    if (!(scale[a] > 0.0))
    {
      return "The image direction matrix is singular (column " + std::to_string(a) +
        " is zero): set a rotation (e.g. the identity).";
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    for (int b = a + 1; b < 3; ++b)
    {
      double dot = 0.0;
      for (int r = 0; r < 3; ++r)
      {
        dot += d->GetElement(r, a) * d->GetElement(r, b);
      }
      if (std::abs(dot) > 1e-4 * scale[a] * scale[b]) // orientations written with 4-6 decimals pass
      {
        return "The image direction matrix shears the axes (columns " + std::to_string(a) + " and " +
          std::to_string(b) + " are not orthogonal): the filter needs a rotation, scaled per axis at most; "
          "resample the image onto such a grid first.";
      }
    }
  }
  return "";
}

/// The blanking mark of samples: HIDDENCELL for cell data, HIDDENPOINT for point data.
unsigned char HiddenMark(bool cellData)
{
  return static_cast<unsigned char>(
    cellData ? static_cast<int>(vtkDataSetAttributes::HIDDENCELL) : static_cast<int>(vtkDataSetAttributes::HIDDENPOINT));
}

/// Whether sample `t` of `image` (points, or cells for cell data) is blanked.
bool IsHidden(vtkImageData* image, bool cellData, vtkIdType t)
{
  vtkUnsignedCharArray* ghosts = cellData ? image->GetCellGhostArray() : image->GetPointGhostArray();
  return ghosts && t < ghosts->GetNumberOfTuples() && (ghosts->GetValue(t) & HiddenMark(cellData));
}

/// Whether any sample of `array` on `image` is blanked (a scan of the marks only).
bool AnyHidden(vtkImageData* image, vtkDataArray* array, bool cellData)
{
  vtkUnsignedCharArray* ghosts = cellData ? image->GetCellGhostArray() : image->GetPointGhostArray();
  if (!array || !ghosts || ghosts->GetNumberOfTuples() != array->GetNumberOfTuples())
  {
    return false;
  }
  const unsigned char mark = HiddenMark(cellData);
  for (vtkIdType t = 0; t < ghosts->GetNumberOfTuples(); ++t)
  {
    if (ghosts->GetValue(t) & mark)
    {
      return true;
    }
  }
  return false;
}

/**
 * A double copy of `array` whose blanked samples (the ghost array's
 * HIDDENPOINT, or HIDDENCELL for cell data) are NaN, or nullptr when none is
 * blanked.
 */
vtkSmartPointer<vtkDataArray> MaskHiddenSamples(vtkImageData* image, vtkDataArray* array, bool cellData)
{
  if (!AnyHidden(image, array, cellData))
  {
    return nullptr;
  }
  vtkSmartPointer<vtkDoubleArray> masked;
  for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
  {
    if (!IsHidden(image, cellData, t))
    {
      continue;
    }
    if (!masked)
    {
      masked = vtkSmartPointer<vtkDoubleArray>::New();
      masked->DeepCopy(array); // as doubles
      masked->SetName(array->GetName());
    }
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      masked->SetComponent(t, c, std::numeric_limits<double>::quiet_NaN());
    }
  }
  return masked;
}

/// "" when `array` (of `association`) can be filtered on `image`, else the message.
std::string CheckImageArray(vtkImageData* image, vtkDataArray* array, int association)
{
  const bool cellData = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const std::string direction = CheckDirection(image);
  if (!direction.empty())
  {
    return direction;
  }
  const shock::GridShape grid = SampleGrid(image, cellData);
  std::ostringstream error;
  if (array->GetNumberOfTuples() != grid.NumberOfSamples())
  {
    error << "Array '" << (array->GetName() ? array->GetName() : "(unnamed)") << "' has "
          << array->GetNumberOfTuples() << " tuples, the image has " << grid.NumberOfSamples()
          << (cellData ? " cells." : " points.");
    return error.str();
  }
  for (int a = 0; a < 3; ++a)
  {
    if (grid.dimensions[a] > 1 && !(grid.spacing[a] > 0.0 && std::isfinite(grid.spacing[a])))
    {
      error << "The image spacing must be finite and non-zero along every axis with more "
               "than one sample; axis "
            << a << " has spacing " << image->GetSpacing()[a] << ".";
      return error.str();
    }
  }
  return "";
}

/**
 * The grid of the processed samples: points, or cell centres for cell data;
 * the physical distance between samples along each axis (|spacing| times the
 * direction matrix's scale of that axis: diag(4,1,1) is spacing 4 along x).
 */
shock::GridShape SampleGrid(vtkImageData* image, bool cellData)
{
  shock::GridShape shape;
  int dims[3];
  image->GetDimensions(dims);
  const double* spacing = image->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    shape.dimensions[a] = cellData ? std::max(dims[a] - 1, 1) : dims[a];
    shape.spacing[a] = std::abs(spacing[a]) * AxisScale(image, a);
  }
  return shape;
}

/// Flow of the kernel (grid axes, physical lengths) in world axes: axis flips,
/// then the direction matrix's unit columns.
void ToWorldAxes(vtkImageData* image, const double* gridVector, double* world)
{
  const double* spacing = image->GetSpacing();
  double flipped[3];
  for (int a = 0; a < 3; ++a)
  {
    const double scale = AxisScale(image, a);
    flipped[a] = (spacing[a] < 0.0 ? -gridVector[a] : gridVector[a]) / (scale > 0.0 ? scale : 1.0);
  }
  image->GetDirectionMatrix()->MultiplyPoint(flipped, world);
}

/**
 * The arrays of `filtered` (a piece's result, cropped to it) into `output`:
 * its scalars (the filtered array) in place of `array`, the flow arrays added.
 */
void TakeResultArrays(vtkImageData* filtered, vtkImageData* output, vtkDataArray* array)
{
  for (int which = 0; which < 2; ++which)
  {
    vtkDataSetAttributes* from = which == 0 ? static_cast<vtkDataSetAttributes*>(filtered->GetPointData())
                                            : static_cast<vtkDataSetAttributes*>(filtered->GetCellData());
    vtkDataSetAttributes* to = which == 0 ? static_cast<vtkDataSetAttributes*>(output->GetPointData())
                                          : static_cast<vtkDataSetAttributes*>(output->GetCellData());
    for (int k = 0; k < from->GetNumberOfArrays(); ++k)
    {
      vtkAbstractArray* result = from->GetAbstractArray(k);
      if (result == from->GetScalars() && result != nullptr)
      {
        ShockFilterInternals::ReplaceArray(to, array, vtkDataArray::SafeDownCast(result));
      }
      else if (result)
      {
        to->AddArray(result);
      }
    }
  }
}

/// Attach ShockPotential and ShockFlow to the output (see the class documentation).
void AttachFlowArrays(vtkImageData* output, bool cellData, const shock::GridShape& grid,
  const shock::GridFlowFields& fields)
{
  vtkNew<vtkDoubleArray> potential;
  potential->SetName(vtkShockAdvectionFilter::PotentialArrayName());
  potential->SetNumberOfTuples(static_cast<vtkIdType>(fields.potential.size()));
  std::copy(fields.potential.begin(), fields.potential.end(), potential->GetPointer(0));

  vtkNew<vtkDoubleArray> flow;
  flow->SetName(vtkShockAdvectionFilter::FlowArrayName());
  flow->SetNumberOfComponents(3);
  // Faces of the sample grid: the image cells (point data) or the points between
  // cell centres (cell data).
  int dims[3];
  output->GetDimensions(dims);
  const vtkIdType tuples = cellData ? output->GetNumberOfPoints() : output->GetNumberOfCells();
  flow->SetNumberOfTuples(tuples);
  flow->Fill(0.0);
  std::array<std::int64_t, 3> faces;
  for (int a = 0; a < 3; ++a)
  {
    faces[a] = std::max(grid.dimensions[a] - 1, 1);
  }
  double world[3];
  if (!cellData)
  {
    for (vtkIdType f = 0; f < tuples; ++f)
    {
      ToWorldAxes(output, &fields.flow[3 * f], world);
      flow->SetTypedTuple(f, world);
    }
  }
  else
  {
    for (int k = 0; k < dims[2]; ++k)
    {
      for (int j = 0; j < dims[1]; ++j)
      {
        for (int i = 0; i < dims[0]; ++i)
        {
          int ijk[3] = { i, j, k };
          std::int64_t face = 0;
          std::int64_t stride = 1;
          bool interior = true;
          for (int a = 0; a < 3 && interior; ++a)
          {
            // A point is interior along an axis the cell grid spans; flat axes map to 0.
            const std::int64_t c = grid.dimensions[a] > 1 ? ijk[a] - 1 : 0;
            interior = c >= 0 && c < faces[a];
            face += c * stride;
            stride *= faces[a];
          }
          if (interior)
          {
            ToWorldAxes(output, &fields.flow[3 * face], world);
            // The point's index from its zero-based coordinates (ComputePointId takes extent coordinates).
            flow->SetTypedTuple(i + static_cast<vtkIdType>(dims[0]) * (j + static_cast<vtkIdType>(dims[1]) * k), world);
          }
        }
      }
    }
  }
  vtkDataSetAttributes* sampleData =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetCellData()) : output->GetPointData();
  vtkDataSetAttributes* faceData =
    cellData ? static_cast<vtkDataSetAttributes*>(output->GetPointData()) : output->GetCellData();
  sampleData->AddArray(potential);
  faceData->AddArray(flow);
}

int UpdatePieces(vtkInformation* info)
{
  return info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
}

int UpdateGhostLevels(vtkInformation* info)
{
  return info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS())
    ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS())
    : 0;
}

namespace
{
/// The samples of a sub-extent within an image's: first index, count, and the image's count per axis.
struct SampleBox
{
  vtkIdType first[3], count[3], dims[3];
};

/// The point and cell sample boxes of the point extent `piece` within `extent`.
void SampleBoxes(const int extent[6], const int piece[6], SampleBox& points, SampleBox& cells)
{
  for (int a = 0; a < 3; ++a)
  {
    const bool spans = extent[2 * a + 1] > extent[2 * a];
    points.first[a] = piece[2 * a] - extent[2 * a];
    points.count[a] = piece[2 * a + 1] - piece[2 * a] + 1;
    points.dims[a] = extent[2 * a + 1] - extent[2 * a] + 1;
    cells.first[a] = spans ? points.first[a] : 0;
    cells.count[a] = spans ? std::max<vtkIdType>(points.count[a] - 1, 0) : 1;
    cells.dims[a] = spans ? points.dims[a] - 1 : 1;
  }
}
}

/**
 * Crop `image` to `target` (within its extent) as vtkImageData::Crop does, but
 * a row at a time: each point and cell array is copied with memcpy instead of
 * one vtkDataSetAttributes::CopyData call per tuple. Returns false, changing nothing, when an
 * array is not a plain named vtkDataArray or an axis the image spans would be
 * left with a single point (vtkImageData::Crop then does it).
 */
bool CropByRows(vtkImageData* image, const int target[6])
{
  const int* extent = image->GetExtent();
  int crop[6];
  for (int a = 0; a < 3; ++a)
  {
    crop[2 * a] = std::max(target[2 * a], extent[2 * a]);
    crop[2 * a + 1] = std::min(target[2 * a + 1], extent[2 * a + 1]);
    const bool spans = extent[2 * a + 1] > extent[2 * a];
    if (crop[2 * a] > crop[2 * a + 1] || (spans && crop[2 * a] == crop[2 * a + 1]))
    {
      return false;
    }
  }
  SampleBox points;
  SampleBox cells;
  SampleBoxes(extent, crop, points, cells);
  vtkDataSetAttributes* attributes[2] = { image->GetPointData(), image->GetCellData() };
  for (vtkDataSetAttributes* data : attributes)
  {
    for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    {
      vtkDataArray* array = data->GetArray(k);
      if (!array || !array->GetName() || !array->HasStandardMemoryLayout())
      {
        return false;
      }
    }
  }
  for (int which = 0; which < 2; ++which)
  {
    const SampleBox& box = which == 0 ? points : cells;
    vtkDataSetAttributes* data = attributes[which];
    for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    {
      vtkDataArray* array = data->GetArray(k);
      const size_t tupleBytes = static_cast<size_t>(array->GetDataTypeSize()) * array->GetNumberOfComponents();
      if (array->GetNumberOfTuples() != box.dims[0] * box.dims[1] * box.dims[2])
      {
        continue; // not one tuple per sample: vtkImageData::Crop would not know it either
      }
      vtkSmartPointer<vtkDataArray> cropped = vtk::TakeSmartPointer(array->NewInstance());
      cropped->SetName(array->GetName());
      cropped->SetNumberOfComponents(array->GetNumberOfComponents());
      cropped->CopyComponentNames(array);
      cropped->SetNumberOfTuples(box.count[0] * box.count[1] * box.count[2]);
      const char* from = static_cast<const char*>(array->GetVoidPointer(0));
      char* to = static_cast<char*>(cropped->GetVoidPointer(0));
      for (vtkIdType z = 0; z < box.count[2]; ++z)
      {
        for (vtkIdType y = 0; y < box.count[1]; ++y)
        {
          const vtkIdType row = ((box.first[2] + z) * box.dims[1] + box.first[1] + y) * box.dims[0] + box.first[0];
          std::memcpy(to, from + static_cast<size_t>(row) * tupleBytes, static_cast<size_t>(box.count[0]) * tupleBytes);
          to += static_cast<size_t>(box.count[0]) * tupleBytes;
        }
      }
      data->AddArray(cropped); // same name: replaces the array at its index (attributes kept)
    }
  }
  image->SetExtent(crop);
  return true;
}

/// The extent of one piece of `extent` with `ghost` layers, split as the source splits it.
void PieceExtent(vtkInformation* info, const int extent[6], int ghost, int piece[6])
{
  const int mode = info->Has(vtkExtentTranslator::UPDATE_SPLIT_MODE())
    ? info->Get(vtkExtentTranslator::UPDATE_SPLIT_MODE())
    : vtkExtentTranslator::BLOCK_MODE;
  vtkNew<vtkExtentTranslator> translator;
  int whole[6];
  std::copy(extent, extent + 6, whole);
  translator->PieceToExtentThreadSafe(info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()),
    UpdatePieces(info), ghost, whole, piece, mode, 0);
}

namespace
{
/**
 * A new array like `array` (type, name, components, lookup table) with
 * `tuples` tuples. Not its information: that caches the value ranges of
 * the whole array.
 */
vtkSmartPointer<vtkAbstractArray> NewLike(vtkAbstractArray* array, vtkIdType tuples)
{
  vtkSmartPointer<vtkAbstractArray> copy = vtk::TakeSmartPointer(array->NewInstance());
  copy->SetName(array->GetName());
  copy->SetNumberOfComponents(array->GetNumberOfComponents());
  copy->CopyComponentNames(array);
  vtkDataArray* numbers = vtkDataArray::SafeDownCast(array);
  if (numbers && numbers->GetLookupTable())
  {
    vtkDataArray::SafeDownCast(copy)->SetLookupTable(numbers->GetLookupTable());
  }
  copy->SetNumberOfTuples(tuples);
  return copy;
}

/// The tuples of `array` (one per sample of the image) in the box `box`, row by row.
vtkSmartPointer<vtkAbstractArray> CroppedTuples(vtkAbstractArray* array, const SampleBox& box)
{
  vtkSmartPointer<vtkAbstractArray> kept = NewLike(array, box.count[0] * box.count[1] * box.count[2]);
  vtkDataArray* from = vtkDataArray::SafeDownCast(array);
  const bool raw = from && from->HasStandardMemoryLayout();
  const size_t tupleBytes = static_cast<size_t>(array->GetDataTypeSize()) * array->GetNumberOfComponents();
  vtkIdType to0 = 0;
  for (vtkIdType z = 0; z < box.count[2]; ++z)
  {
    for (vtkIdType y = 0; y < box.count[1]; ++y)
    {
      const vtkIdType first = box.first[0] + box.dims[0] * (box.first[1] + y + box.dims[1] * (box.first[2] + z));
      if (raw)
      {
        std::memcpy(static_cast<char*>(kept->GetVoidPointer(0)) + static_cast<size_t>(to0) * tupleBytes,
          static_cast<const char*>(array->GetVoidPointer(0)) + static_cast<size_t>(first) * tupleBytes,
          static_cast<size_t>(box.count[0]) * tupleBytes);
      }
      else
      {
        kept->InsertTuples(to0, box.count[0], first, array);
      }
      to0 += box.count[0];
    }
  }
  kept->Modified();
  return kept;
}
}

vtkDataArray* PieceOfImage(vtkImageData* input, const int piece[6], vtkDataArray* filtered, vtkImageData* output)
{
  SampleBox points;
  SampleBox cells;
  SampleBoxes(input->GetExtent(), piece, points, cells);
  output->Initialize();
  output->CopyStructure(input);
  output->SetExtent(const_cast<int*>(piece));
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
  vtkDataArray* placeholder = nullptr;
  for (int which = 0; which < 2; ++which)
  {
    const SampleBox& box = which == 0 ? points : cells;
    vtkDataSetAttributes* from = which == 0 ? static_cast<vtkDataSetAttributes*>(input->GetPointData())
                                            : static_cast<vtkDataSetAttributes*>(input->GetCellData());
    vtkDataSetAttributes* to = which == 0 ? static_cast<vtkDataSetAttributes*>(output->GetPointData())
                                          : static_cast<vtkDataSetAttributes*>(output->GetCellData());
    for (int k = 0; k < from->GetNumberOfArrays(); ++k)
    {
      vtkAbstractArray* array = from->GetAbstractArray(k);
      if (!array)
      {
        continue;
      }
      vtkSmartPointer<vtkAbstractArray> kept = array; // not one tuple per sample: shared, as vtkImageData::Crop leaves it
      if (array == filtered)
      {
        kept = NewLike(array, 0);
        placeholder = vtkDataArray::SafeDownCast(kept);
      }
      else if (array->GetNumberOfTuples() == box.dims[0] * box.dims[1] * box.dims[2])
      {
        kept = CroppedTuples(array, box);
      }
      const int index = to->AddArray(kept);
      const int role = from->IsArrayAnAttribute(k);
      if (role >= 0)
      {
        to->SetActiveAttribute(index, role);
      }
    }
  }
  return placeholder;
}

void KeepPieceValues(vtkImageData* input, const int piece[6], vtkDataArray* array, bool cellData,
  vtkImageData* output, vtkDataArray* placeholder)
{
  vtkDataSetAttributes* to = cellData ? static_cast<vtkDataSetAttributes*>(output->GetCellData())
                                      : static_cast<vtkDataSetAttributes*>(output->GetPointData());
  bool present = false;
  for (int k = 0; k < to->GetNumberOfArrays(); ++k)
  {
    present = present || to->GetAbstractArray(k) == placeholder;
  }
  if (!present)
  {
    return; // the results took its place
  }
  SampleBox points;
  SampleBox cells;
  SampleBoxes(input->GetExtent(), piece, points, cells);
  vtkSmartPointer<vtkAbstractArray> own = CroppedTuples(array, cellData ? cells : points);
  ShockFilterInternals::ReplaceArray(to, placeholder, vtkDataArray::SafeDownCast(own));
}

shock::SampleWriter KeepHiddenValues(const shock::SampleWriter& writer, vtkImageData* image, vtkDataArray* array,
  bool cellData)
{
  // The blanked samples' own values, read here once (the writer runs on
  // several threads at once: it reads only these plain vectors).
  const int C = array->GetNumberOfComponents();
  auto hiddenAt = std::make_shared<std::vector<std::int64_t>>(); // sorted sample indices
  auto hiddenValues = std::make_shared<std::vector<double>>();
  for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
  {
    if (IsHidden(image, cellData, t))
    {
      hiddenAt->push_back(t);
      for (int c = 0; c < C; ++c)
      {
        hiddenValues->push_back(array->GetComponent(t, c));
      }
    }
  }
  return [writer, C, hiddenAt, hiddenValues](std::int64_t first, std::int64_t count, const double* in) {
    auto k = std::lower_bound(hiddenAt->begin(), hiddenAt->end(), first);
    if (k == hiddenAt->end() || *k >= first + count)
    {
      writer(first, count, in); // no blanked sample in this run
      return;
    }
    std::vector<double> values(in, in + count * C);
    for (; k != hiddenAt->end() && *k < first + count; ++k)
    {
      const size_t which = static_cast<size_t>(k - hiddenAt->begin());
      std::copy(hiddenValues->begin() + static_cast<long>(which * C),
        hiddenValues->begin() + static_cast<long>((which + 1) * C), values.begin() + (*k - first) * C);
    }
    writer(first, count, values.data());
  };
}

std::array<std::int64_t, 6> SamplesOfExtent(vtkImageData* image, const int extent[6], bool cellData)
{
  const int* whole = image->GetExtent();
  std::array<std::int64_t, 6> samples{};
  for (int a = 0; a < 3; ++a)
  {
    // Cells along an axis the image spans: one fewer than the points; a flat axis has one.
    const bool spans = whole[2 * a + 1] > whole[2 * a];
    const bool cells = cellData && spans;
    samples[2 * a] = spans ? extent[2 * a] - whole[2 * a] : 0;
    samples[2 * a + 1] = spans ? extent[2 * a + 1] - whole[2 * a] - (cells ? 1 : 0) : 0;
  }
  return samples;
}

shock::SampleWriter BoxWriter(const shock::SampleWriter& writer, const shock::GridShape& grid,
  const std::array<std::int64_t, 6>& samples, int components)
{
  const std::int64_t nx = grid.dimensions[0];
  const std::int64_t ny = grid.dimensions[1];
  return [writer, nx, ny, samples, components](std::int64_t first, std::int64_t count, const double* values) {
    const std::int64_t bx = samples[1] - samples[0] + 1;
    const std::int64_t by = samples[3] - samples[2] + 1;
    while (count > 0)
    {
      // The rest of the run in the grid row of sample `first`.
      const std::int64_t x = first % nx;
      const std::int64_t y = (first / nx) % ny;
      const std::int64_t z = first / nx / ny;
      const std::int64_t inRow = std::min(count, nx - x);
      const std::int64_t from = std::max(x, samples[0]);
      const std::int64_t to = std::min(x + inRow - 1, samples[1]);
      if (y >= samples[2] && y <= samples[3] && z >= samples[4] && z <= samples[5] && from <= to)
      {
        writer(((z - samples[4]) * by + (y - samples[2])) * bx + (from - samples[0]), to - from + 1,
          values + (from - x) * components);
      }
      first += inRow;
      count -= inRow;
      values += inRow * components;
    }
  };
}
}
