/**
 * @file   ShockImageIO.h
 * @brief  Reading and writing images and volumes, in the format the file
 *         name's extension names (any letter case).
 *
 *  - `.png` (vtkPNGReader/Writer): unsigned char or unsigned short, 1 to 4 components, 2D;
 *  - `.jpg .jpeg` (vtkJPEGReader/Writer, quality 95): unsigned char, 1 or 3 components, 2D;
 *  - `.tif .tiff` (vtkTIFFReader/Writer): unsigned char, unsigned short or float,
 *    1, 3 or 4 components, 2D or 3D; read the same way up as the other formats;
 *  - `.bmp` (vtkBMPReader/Writer), `.pnm .ppm .pgm` (vtkPNMReader/Writer):
 *    unsigned char, 1 or 3 components, 2D;
 *  - `.vti` (VTK XML image data), `.vtk` (legacy structured points, written
 *    binary): any type, every array.
 *
 * Reading checks the file first (ShockImageChecks.h): a damaged PNG, a header
 * that declares more samples than the limit, or a PNM header VTK's reader
 * would loop on give one line instead of a crash, an abort or a hang. Writing
 * goes through a temporary file renamed over the target when complete.
 *
 * Memory: an image read takes its samples times their components times the
 * bytes of their type (1 for 8-bit formats, 2 for 16-bit, 4 for float), plus
 * as much again for the copy TIFF orientation needs. Errors come back as one
 * line "<path>: <what is wrong>".
 */
#ifndef ShockImageIO_h
#define ShockImageIO_h

#include "vtkImageData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkDataArray;

namespace shockio
{

/// An image file format.
struct ImageFormat
{
  enum Id
  {
    PNG,
    JPEG,
    TIFF,
    BMP,
    PNM,
    VTI,
    LegacyVTK
  } id;
  const char* name;
  std::vector<std::string> extensions; ///< lower case, without the dot
  std::vector<int> storableTypes;      ///< scalar types the writer takes; empty = any
  std::vector<int> components;         ///< component counts the writer takes; empty = any
  bool volumes;                        ///< whether it stores images with several z-slices
};

/// The image formats.
const std::vector<ImageFormat>& ImageFormats();

/// The format of `path` by its extension; null with `error` set if there is none.
const ImageFormat* ImageFormatOf(const std::string& path, std::string& error);

/**
 * Reads an image or volume; null with `error` set when the file is missing,
 * invalid, declares more than `maxSamples` samples (points), or holds no data.
 */
vtkSmartPointer<vtkImageData> ReadImage(
  const std::string& path, std::uint64_t maxSamples, std::string& error);

/**
 * Whether `format` can store the point array `arrayName` of `image` (its type
 * aside, which WriteImage() converts): number of components, and a single
 * z-slice for the 2D formats. Else `error` is set.
 */
bool CheckStorable(vtkImageData* image, const std::string& arrayName, const ImageFormat& format,
  const std::string& path, std::string& error);

/**
 * Writes `image` in the format of the extension of `path`: the VTK formats
 * every array, the raster formats the point array `arrayName`, converted when
 * the format cannot store its type (TIFF: to float; 8-bit formats: rounded and
 * clamped to unsigned char 0..255, which `note` then tells). An existing file
 * is replaced only when the new one is complete. False with `error` set on failure.
 */
bool WriteImage(vtkImageData* image, const std::string& path, const std::string& arrayName,
  std::string& error, std::string& note);

/**
 * Every value times `scale` rounded to the nearest integer in [0, 255] (NaN
 * gives 0); `clamped` counts the values that were out of range.
 */
vtkSmartPointer<vtkUnsignedCharArray> QuantizeToBytes(
  vtkDataArray* values, double scale, vtkIdType* clamped = nullptr);

/// "512x384x1"
std::string DimensionsText(vtkImageData* image);

} // namespace shockio

#endif
