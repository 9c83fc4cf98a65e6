/**
 * @file ShockImageInternals.h
 * @brief The image filter's glue (private to the module): what
 * vtkImageShockAdvectionFilter checks of an image and its array, its blanked
 * samples, the grid the kernels see, the flow arrays, and cropping to pieces.
 */
#ifndef ShockImageInternals_h
#define ShockImageInternals_h

#include "GridShape.h"
#include "GridShockAdvection.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <cstdint>
#include <string>

class vtkDataArray;
class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;
namespace ShockParallel
{
struct ImageLayers;
}

namespace ShockImageInternals
{
/// The length of column `a` of the image's direction matrix: the scale it gives axis a.
double AxisScale(vtkImageData* image, int a);

/// "" when the direction matrix has orthogonal, non-zero, finite columns, else the message.
std::string CheckDirection(vtkImageData* image);

/**
 * The grid a piece of `image` belongs to, as "whole extent ...;origin
 * ...;spacing ...;direction ...": the whole extent from `inInfo` (its
 * WHOLE_EXTENT, "unknown" without one), the rest from the image (12
 * significant digits). The pieces of one image have the same text.
 */
std::string GridText(vtkInformation* inInfo, vtkImageData* image);

/**
 * "" when the processes of `controller` ask `outInfo` for pieces of their own
 * (their UPDATE_PIECE_NUMBER differ), else the one-line message naming the
 * first process that asks for a piece an earlier one asks for, the same on every process
 * (collective: one gather).
 */
std::string RepeatedPieceError(vtkMultiProcessController* controller, vtkInformation* outInfo);

/// The blanking mark of samples: HIDDENCELL for cell data, HIDDENPOINT for point data.
unsigned char HiddenMark(bool cellData);

/// Whether sample `t` of `image` (points, or cells for cell data) is blanked.
bool IsHidden(vtkImageData* image, bool cellData, vtkIdType t);

/// Whether any sample of `array` on `image` is blanked (a scan of the marks only).
bool AnyHidden(vtkImageData* image, vtkDataArray* array, bool cellData);

/// A double copy of `array` with its blanked samples NaN, or nullptr when none is blanked.
vtkSmartPointer<vtkDataArray> MaskHiddenSamples(vtkImageData* image, vtkDataArray* array, bool cellData);

/**
 * A writer that keeps the blanked samples' own values (read here once from
 * `array` on `image`) in place of the kernel's results, then hands on to `writer`.
 */
shock::SampleWriter KeepHiddenValues(const shock::SampleWriter& writer, vtkImageData* image, vtkDataArray* array,
  bool cellData);

/**
 * Where the filtered samples go: `output`, in which they replace `replaced`
 * (the filtered array, or a piece's own array), and the extent they cover:
 * null for every sample of the filtered image, else a sub-extent of it (a
 * piece's extent within the piece with its halo).
 */
struct SampleTarget
{
  vtkImageData* output;
  vtkDataArray* replaced;
  const int* extent = nullptr;
  /// The whole image's extent when the input is a piece of it, so that lengths
  /// and the trace step cap are the whole image's (GridShape::wholeDimensions);
  /// null: the input's.
  const int* wholeExtent = nullptr;
  /// With `extent`: where the kernel reports how far the traces of the written
  /// samples went beyond them (AdvectionReport::haloReach); null when not wanted.
  std::array<std::int64_t, 6>* haloReach = nullptr;
  /// The piece's halo in layers beside the piece's own array (ShockParallel::ImageLayers);
  /// null: the filtered array holds every sample.
  const ShockParallel::ImageLayers* layers = nullptr;
};

/**
 * The samples (points, or cells for cell data) of `image` within the
 * sub-extent `extent`, per axis the first and the last index of the sample
 * grid (AdvectionParameters::writtenSamples).
 */
std::array<std::int64_t, 6> SamplesOfExtent(vtkImageData* image, const int extent[6], bool cellData);

/**
 * A writer of the samples of `grid` that hands those in the box `samples`
 * (per axis first and last) to `writer`, numbered within the box: any run of
 * samples, split into the box's rows.
 */
shock::SampleWriter BoxWriter(const shock::SampleWriter& writer, const shock::GridShape& grid,
  const std::array<std::int64_t, 6>& samples, int components);

/// "" when `array` (of `association`) can be filtered on `image`, else the message.
std::string CheckImageArray(vtkImageData* image, vtkDataArray* array, int association);

/// The grid of the processed samples (points, or cell centres for cell data), physical spacing per axis.
shock::GridShape SampleGrid(vtkImageData* image, bool cellData);

/// Flow of the kernel (grid axes, physical lengths) in world axes.
void ToWorldAxes(vtkImageData* image, const double* gridVector, double* world);

/// A piece's cropped result into `output`: its scalars in place of `array`, the flow arrays added.
void TakeResultArrays(vtkImageData* filtered, vtkImageData* output, vtkDataArray* array);

/// Attach ShockPotential and ShockFlow to the output (see the class documentation).
void AttachFlowArrays(vtkImageData* output, bool cellData, const shock::GridShape& grid,
  const shock::GridFlowFields& fields);

/// The request's number of pieces (1 when not set).
int UpdatePieces(vtkInformation* info);

/// The request's ghost levels (0 when not set).
int UpdateGhostLevels(vtkInformation* info);

/// Crop `image` to `target` a row at a time; false, changing nothing, when vtkImageData::Crop must do it.
bool CropByRows(vtkImageData* image, const int target[6]);

/// The extent of one piece of `extent` with `ghost` layers, split as the source splits it.
void PieceExtent(vtkInformation* info, const int extent[6], int ghost, int piece[6]);

/**
 * `output` becomes the piece `piece` (a point extent within `input`'s): the
 * input's structure there and every point and cell array with one tuple per
 * sample cropped to it (the others shared, as vtkImageData::Crop leaves them),
 * names, attribute roles and order kept, the field data shared; but
 * `filtered` is not copied: in its place an empty array of its type, name,
 * components and role, returned, which the filter's results then replace
 * (SampleTarget::replaced).
 */
vtkDataArray* PieceOfImage(vtkImageData* input, const int piece[6], vtkDataArray* filtered, vtkImageData* output);

/**
 * When `placeholder` (PieceOfImage's) is still in `output` (an abort or a
 * failure before the results): put the piece's own values of `array` (of
 * `input`, cropped to `piece`) in its place, so that the output never holds
 * an empty array.
 */
void KeepPieceValues(vtkImageData* input, const int piece[6], vtkDataArray* array, bool cellData,
  vtkImageData* output, vtkDataArray* placeholder);
}

#endif
