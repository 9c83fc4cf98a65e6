/**
 * @file   ShockImageChecks.h
 * @brief  Checks of image files before VTK 9.2's readers see them.
 *
 * VTK's image readers trust their files: libpng's errors on a damaged PNG
 * (bad CRC, bad deflate data, bad filter byte, invalid IHDR, short IDAT) end in
 * a longjmp vtkPNGReader does not catch (a crash); every reader allocates the
 * size a header declares (an abort, or gigabytes, for a 715-byte file); and
 * vtkPNMReader loops forever on some malformed headers ("P6\nx", "P5\n4 4 \n").
 * So each file is checked first: a PNG completely (every chunk's CRC, the IHDR
 * fields, the inflated image data and its filter bytes, with zlib), the
 * headers of the other formats for the size they declare, which must be at
 * most `maxSamples` samples (points), and PNM headers token by token.
 */
#ifndef ShockImageChecks_h
#define ShockImageChecks_h

#include "ShockImageIO.h"

#include <cstdint>
#include <string>

namespace shockio
{

/// The size an image file declares.
struct ImageHeader
{
  std::uint64_t width = 0, height = 0, depth = 1;
  std::uint64_t components = 1;        ///< per sample
  std::uint64_t bytesPerComponent = 1; ///< as read
  bool known = false;                  ///< whether the header gave the size
  std::uint64_t maxValue = 0;          ///< PNM: the declared maximum value (0: not given)

  std::uint64_t Samples() const { return this->width * this->height * this->depth; }
  /// Bytes of the image as read (saturating; 0 if unknown).
  std::uint64_t Bytes() const;
};

/**
 * Whether VTK's reader of `format` can read `path` safely, the size it
 * declares (in `header`) at most `maxSamples` samples; else `error` is set to
 * "<path>: <what is wrong>" (for the limit, with "the limit of <n> samples").
 */
bool CheckImageFile(const std::string& path, const ImageFormat& format, std::uint64_t maxSamples,
  ImageHeader& header, std::string& error);

/**
 * Whether libtiff reads each of the `directories` directories (pages) of the
 * TIFF file `path` without an error; else `problem` says which error.
 */
bool CheckTiffDirectories(const std::string& path, std::uint64_t directories, std::string& problem);

/// Whether `text` (a whole PNG file) is a complete, undamaged PNG; else `problem` says why.
bool CheckPng(const std::string& text, ImageHeader& header, std::uint64_t maxSamples, std::string& problem);

/**
 * Whether the size `header` declares is at most `maxSamples` samples; else
 * `problem` says "declares <size> (<bytes> as read), more than the limit of <n> samples".
 */
bool WithinLimit(const ImageHeader& header, std::uint64_t maxSamples, std::string& problem);

/// "4000x3000 samples" or "64x64x64 samples", for messages.
std::string SizeText(const ImageHeader& header);

/// "1.5 GiB", "12 MiB", "700 bytes".
std::string BytesText(std::uint64_t bytes);

} // namespace shockio

#endif
