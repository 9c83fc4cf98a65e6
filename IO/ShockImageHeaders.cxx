#include "ShockImageChecks.h"

#include "ShockIOFiles.h"
#include "ShockMeshChecks.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace shockio
{

std::uint64_t ImageHeader::Bytes() const
{
  std::uint64_t bytes = 1;
  for (const std::uint64_t factor :
    { this->width, this->height, this->depth, this->components, this->bytesPerComponent })
  {
    bytes = factor != 0 && bytes > std::numeric_limits<std::uint64_t>::max() / factor
      ? std::numeric_limits<std::uint64_t>::max()
      : bytes * factor;
  }
  return bytes;
}

std::string SizeText(const ImageHeader& header)
{
  std::string text = std::to_string(header.width) + "x" + std::to_string(header.height);
  if (header.depth != 1)
  {
    text += "x" + std::to_string(header.depth);
  }
  return text + " samples";
}

std::string BytesText(std::uint64_t bytes)
{
  const char* units[] = { "bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB" };
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 6)
  {
    value /= 1024.0;
    ++unit;
  }
  std::ostringstream text;
  text.precision(unit == 0 ? 0 : 3);
  text << value << " " << units[unit];
  return text.str();
}

bool WithinLimit(const ImageHeader& header, std::uint64_t maxSamples, std::string& problem)
{
  const std::uint64_t samples = ImageHeader{ header.width, header.height, header.depth, 1, 1, true }.Bytes();
  if (samples <= maxSamples)
  {
    return true;
  }
  problem = "declares " + SizeText(header) + " (" + BytesText(header.Bytes()) +
    " as read), more than the limit of " + std::to_string(maxSamples) + " samples";
  return false;
}

namespace
{

/// Up to `count` bytes of `path` from `offset` (fewer at the end of the file).
std::string ReadBytes(const std::string& path, std::uint64_t offset, std::size_t count)
{
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  std::string bytes(count, '\0');
  file.read(bytes.data(), static_cast<std::streamsize>(count));
  bytes.resize(file ? count : static_cast<std::size_t>(std::max<std::streamsize>(0, file.gcount())));
  return bytes;
}

std::uint64_t Unsigned(const std::string& bytes, std::size_t at, int size, bool little)
{
  std::uint64_t value = 0;
  for (int i = 0; i < size; ++i)
  {
    const auto byte = static_cast<unsigned char>(bytes[at + (little ? size - 1 - i : i)]);
    value = (value << 8) | byte;
  }
  return value;
}

/// JPEG: the frame header (SOFn) of the first frame.
bool JpegHeader(const std::string& path, ImageHeader& header, std::string& problem)
{
  std::string bytes;
  if (!ReadFile(path, bytes, problem))
  {
    return false;
  }
  std::size_t at = 2;
  if (bytes.size() < 4 || Unsigned(bytes, 0, 2, false) != 0xFFD8)
  {
    problem = "not a JPEG file (no start-of-image marker)";
    return false;
  }
  while (at + 4 <= bytes.size())
  {
    const auto marker = static_cast<unsigned char>(bytes[at + 1]);
    if (static_cast<unsigned char>(bytes[at]) != 0xFF || marker == 0xDA || marker == 0xD9)
    {
      break; // not a marker, or the scan starts without a frame header
    }
    const std::uint64_t length = Unsigned(bytes, at + 2, 2, false);
    const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
      marker != 0xCC;
    if (frame && at + 10 <= bytes.size())
    {
      header = { Unsigned(bytes, at + 7, 2, false), Unsigned(bytes, at + 5, 2, false), 1,
        static_cast<unsigned char>(bytes[at + 9]), 1, true };
      return true;
    }
    at += 2 + length;
  }
  problem = "the JPEG file has no frame header (truncated or damaged)";
  return false;
}

/// A signed little-endian field of `size` bytes (2 or 4), as VTK's BMP reader reads it.
std::int64_t SignedLE(const std::string& bytes, std::size_t at, int size)
{
  const std::uint64_t value = Unsigned(bytes, at, size, true);
  return size == 2 ? static_cast<std::int16_t>(value) : static_cast<std::int32_t>(value);
}

/**
 * BMP: what VTK 9.2's vtkBMPReader can read. Its ExecuteInformation reports a
 * problem but does not stop the read: it then reads the pixels with what it
 * had set so far (no colour table for an 8-bit file whose header ends early:
 * a null pointer; no depth at all for an unknown header: a read past a buffer).
 * So the whole header must be there and be one of its two kinds (the 40-byte
 * BITMAPINFOHEADER, the 12-byte OS/2 BITMAPCOREHEADER, whose sizes it reads as
 * signed 16-bit numbers), 8 or 24 bits, uncompressed (it reads compressed data
 * as pixels), with every pixel row inside the file.
 */
bool BmpHeader(const std::string& path, ImageHeader& header, std::string& problem)
{
  const std::string bytes = ReadBytes(path, 0, 54);
  if (bytes.size() < 18 || bytes.compare(0, 2, "BM") != 0)
  {
    problem = "not a BMP file (too short, or no 'BM' signature)";
    return false;
  }
  const std::uint64_t infoSize = Unsigned(bytes, 14, 4, true);
  if (infoSize != 40 && infoSize != 12)
  {
    problem = "a BMP with a " + std::to_string(infoSize) +
      "-byte info header (VTK reads the 40-byte BITMAPINFOHEADER and the 12-byte OS/2 header)";
    return false;
  }
  const bool core = infoSize == 12;
  if (bytes.size() < 14 + infoSize)
  {
    problem = "the BMP header is truncated (" + std::to_string(bytes.size()) + " of " +
      std::to_string(14 + infoSize) + " bytes)";
    return false;
  }
  const std::int64_t width = SignedLE(bytes, 18, core ? 2 : 4);
  const std::int64_t height = SignedLE(bytes, core ? 20 : 22, core ? 2 : 4);
  const std::uint64_t bits = Unsigned(bytes, core ? 24 : 28, 2, true);
  const std::uint64_t compression = core ? 0 : Unsigned(bytes, 30, 4, true);
  if (bits != 8 && bits != 24)
  {
    problem = "a BMP of " + std::to_string(bits) + " bits per pixel (VTK reads 8 and 24)";
    return false;
  }
  if (compression != 0)
  {
    problem = "a compressed BMP (compression " + std::to_string(compression) +
      "; VTK reads uncompressed BMP files only)";
    return false;
  }
  if (width <= 0 || height == 0 || height == std::numeric_limits<std::int32_t>::min())
  {
    problem = "the BMP header declares " + std::to_string(width) + "x" + std::to_string(height) +
      " pixels";
    return false;
  }
  header = { static_cast<std::uint64_t>(width), static_cast<std::uint64_t>(std::abs(height)), 1,
    bits == 24 ? 3u : 1u, 1, true };
  return true;
}

/// Whether the pixel rows of the BMP `path` (its header checked) lie inside the file.
bool BmpPixelsInFile(const std::string& path, const ImageHeader& header, std::string& problem)
{
  const std::string bytes = ReadBytes(path, 0, 18);
  const std::uint64_t offset = Unsigned(bytes, 10, 4, true);
  const std::uint64_t headerEnd = 14 + Unsigned(bytes, 14, 4, true);
  // Rows are padded to 4 bytes; VTK reads the last one without its padding.
  const std::uint64_t row = header.width * header.components;
  const std::uint64_t needed = ((row + 3) / 4 * 4) * (header.height - 1) + row;
  std::error_code code;
  const std::uint64_t size = std::filesystem::file_size(path, code);
  if (offset < headerEnd)
  {
    problem = "the BMP pixel data offset " + std::to_string(offset) + " lies inside its header";
    return false;
  }
  if (!code && (offset > size || size - offset < needed))
  {
    problem = "the BMP file holds fewer pixels than its header declares (truncated?)";
    return false;
  }
  return true;
}

/**
 * PNM: the header as the format defines it ("P5" or "P6", width, height,
 * maximum value as decimal numbers, separated by white space and comments,
 * one white space character before the data) and data for every pixel.
 * vtkPNMReader loops forever on some headers that do not follow it.
 */
bool PnmHeader(
  const std::string& path, std::uint64_t maxSamples, ImageHeader& header, std::string& problem)
{
  const std::string bytes = ReadBytes(path, 0, 4096);
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '6'))
  {
    problem = "not a binary PGM (P5) or PPM (P6) file";
    return false;
  }
  std::size_t at = 2;
  std::uint64_t values[3] = { 0, 0, 0 };
  for (std::uint64_t& value : values)
  {
    while (at < bytes.size() && (std::isspace(static_cast<unsigned char>(bytes[at])) || bytes[at] == '#'))
    {
      at = bytes[at] == '#' ? std::min(bytes.find('\n', at), bytes.size()) : at + 1;
    }
    const std::size_t start = at;
    while (at < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[at])) && at - start < 10)
    {
      value = value * 10 + static_cast<std::uint64_t>(bytes[at++] - '0');
    }
    if (at == start || at >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[at])))
    {
      problem = "malformed PNM header (expected width, height and maximum value as numbers)";
      return false;
    }
  }
  if (values[0] == 0 || values[1] == 0 || values[2] == 0 || values[2] > 255)
  {
    problem = "the PNM header declares " + std::to_string(values[0]) + "x" +
      std::to_string(values[1]) + " pixels of maximum value " + std::to_string(values[2]) +
      " (sizes must be positive, values 1 to 255)";
    return false;
  }
  header = { values[0], values[1], 1, bytes[1] == '6' ? 3u : 1u, 1, true, values[2] };
  if (!WithinLimit(header, maxSamples, problem))
  {
    return false;
  }
  std::error_code code;
  const std::uint64_t size = std::filesystem::file_size(path, code);
  const std::uint64_t needed = header.Samples() * header.components;
  if (!code && (size < at + 1 || size - at - 1 < needed))
  {
    problem = "the PNM file holds fewer pixels than its header declares (truncated?)";
    return false;
  }
  return true;
}

/// What a TIFF directory declares of its pixels (0 where a tag is absent or unreadable).
struct TiffLayout
{
  std::uint64_t width = 0, height = 0, samples = 1, bits = 1, photometric = 0;
  bool operator!=(const TiffLayout& o) const
  {
    return this->width != o.width || this->height != o.height || this->samples != o.samples ||
      this->bits != o.bits;
  }
};

/// The first value of the TIFF directory entry at `entry` of `bytes` (SHORT or LONG; inline or at its offset).
std::uint64_t TiffFirstValue(const std::string& path, const std::string& bytes, std::size_t entry, bool little)
{
  const std::uint64_t type = Unsigned(bytes, entry + 2, 2, little);
  const std::uint64_t count = Unsigned(bytes, entry + 4, 4, little);
  const int size = type == 3 ? 2 : type == 4 ? 4 : 0;
  if (size == 0 || count == 0)
  {
    return 0; // libtiff ignores a tag of another type
  }
  if (count * size <= 4)
  {
    return Unsigned(bytes, entry + 8, size, little);
  }
  const std::string value = ReadBytes(path, Unsigned(bytes, entry + 8, 4, little), size);
  return value.size() == static_cast<std::size_t>(size) ? Unsigned(value, 0, size, little) : 0;
}

/**
 * The layout of the TIFF directory `bytes` (its entries and next offset);
 * false with `problem` set for a tag listed twice (libtiff takes the first, a
 * reader of the last would check another size) or a size that is not one SHORT or LONG.
 */
bool TiffDirectory(const std::string& path, const std::string& bytes, std::uint64_t entries, bool little,
  TiffLayout& layout, std::string& problem)
{
  std::set<std::uint64_t> tags;
  for (std::size_t e = 0; e < entries; ++e)
  {
    const std::size_t entry = e * 12;
    const std::uint64_t tag = Unsigned(bytes, entry, 2, little);
    if (!tags.insert(tag).second)
    {
      problem = "a TIFF directory lists tag " + std::to_string(tag) + " twice";
      return false;
    }
    const std::uint64_t type = Unsigned(bytes, entry + 2, 2, little);
    if ((tag == 256 || tag == 257 || tag == 277) &&
      ((type != 3 && type != 4) || Unsigned(bytes, entry + 4, 4, little) != 1))
    {
      problem = "the TIFF tag " + std::to_string(tag) + " is not one SHORT or LONG value";
      return false;
    }
    const std::uint64_t value = TiffFirstValue(path, bytes, entry, little);
    layout.width = tag == 256 ? value : layout.width;
    layout.height = tag == 257 ? value : layout.height;
    layout.samples = tag == 277 ? value : layout.samples;
    layout.bits = tag == 258 ? value : layout.bits;
    layout.photometric = tag == 262 ? value : layout.photometric;
  }
  return true;
}

/**
 * Whether VTK 9.2's vtkTIFFReader reads pixels of `layout` (the first
 * directory's) into a buffer of the right size: it makes 3 components of 2
 * samples per pixel but writes 4 per pixel into them when it reads through
 * libtiff's RGBA interface, and it copies 3 samples per pixel of an RGB or
 * YCbCr image into as many components as the samples.
 */
bool TiffLayoutVtkReads(const TiffLayout& layout, std::string& problem)
{
  if (layout.samples == 2)
  {
    problem = "a TIFF of 2 samples per pixel (VTK 9.2's reader writes past its buffer for them)";
    return false;
  }
  if ((layout.photometric == 2 || layout.photometric == 6) && layout.samples < 3)
  {
    problem = "a TIFF of " + std::string(layout.photometric == 2 ? "RGB" : "YCbCr") + " colours with " +
      std::to_string(layout.samples) + " sample per pixel (3 or more needed)";
    return false;
  }
  return true;
}

/**
 * TIFF (classic, either byte order): the first directory's size, and the
 * number of directories (slices). VTK reads every directory with the first's
 * layout, so all must declare the same size, samples and bits per sample.
 */
bool TiffHeader(const std::string& path, ImageHeader& header, std::string& problem)
{
  std::string bytes = ReadBytes(path, 0, 8);
  const bool little = bytes.compare(0, 4, std::string("II*\0", 4)) == 0;
  if (bytes.size() < 8 || (!little && bytes.compare(0, 4, std::string("MM\0*", 4)) != 0))
  {
    problem = "not a classic TIFF file (BigTIFF is not read)";
    return false;
  }
  std::uint64_t offset = Unsigned(bytes, 4, 4, little);
  std::set<std::uint64_t> seen;
  TiffLayout first;
  header = { 0, 0, 0, 1, 1, true };
  std::uint64_t budget = 64 << 20; // bytes of directories read: a chain of them cannot make this slow
  while (offset != 0 && seen.insert(offset).second)
  {
    bytes = ReadBytes(path, offset, 2);
    const std::uint64_t entries = bytes.size() == 2 ? Unsigned(bytes, 0, 2, little) : 0;
    if (entries * 12 + 4 > budget)
    {
      problem = "the TIFF directories are too many or too large";
      return false;
    }
    budget -= entries * 12 + 4;
    bytes = ReadBytes(path, offset + 2, static_cast<std::size_t>(entries * 12 + 4));
    if (entries == 0 || bytes.size() < entries * 12 + 4)
    {
      problem = "a TIFF directory is empty or truncated";
      return false;
    }
    TiffLayout layout;
    if (!TiffDirectory(path, bytes, entries, little, layout, problem))
    {
      return false;
    }
    if (header.depth == 0)
    {
      first = layout;
      header.width = layout.width;
      header.height = layout.height;
      header.components = layout.samples;
      header.bytesPerComponent = std::max<std::uint64_t>(1, layout.bits / 8);
    }
    else if (layout != first)
    {
      problem = "the TIFF directories (pages) differ in size, samples or bits per sample (VTK reads all as the first)";
      return false;
    }
    ++header.depth;
    offset = Unsigned(bytes, entries * 12, 4, little);
  }
  if (header.width == 0 || header.height == 0)
  {
    problem = "the TIFF file declares no image size";
    return false;
  }
  return TiffLayoutVtkReads(first, problem);
}

/// The first `count` numbers after `key` in `text` (e.g. "DIMENSIONS" or "WholeExtent=\""); false if absent.
bool NumbersAfter(const std::string& text, const std::string& key, std::int64_t* numbers, int count)
{
  const std::size_t at = text.find(key);
  if (at == std::string::npos)
  {
    return false;
  }
  std::istringstream stream(text.substr(at + key.size(), 200));
  for (int i = 0; i < count; ++i)
  {
    if (!(stream >> numbers[i]))
    {
      return false;
    }
  }
  return true;
}

/// VTI (WholeExtent) and legacy structured points (DIMENSIONS): the size in the text header.
bool VtkHeader(const std::string& path, bool xml, ImageHeader& header, std::string& problem)
{
  const std::string text = ReadBytes(path, 0, 1 << 16);
  std::int64_t numbers[6] = { 0, 0, 0, 0, 0, 0 };
  std::int64_t dims[3] = { 0, 0, 0 };
  if (xml ? !NumbersAfter(text, "WholeExtent=\"", numbers, 6) : !NumbersAfter(text, "DIMENSIONS", dims, 3))
  {
    header.known = false; // the reader reports what is missing
    return true;
  }
  for (int a = 0; xml && a < 3; ++a)
  {
    dims[a] = numbers[2 * a + 1] - numbers[2 * a] + 1;
  }
  if (std::any_of(dims, dims + 3, [](std::int64_t d) { return d <= 0 || d > (std::int64_t{ 1 } << 31); }))
  {
    problem = "the file declares invalid dimensions " + std::to_string(dims[0]) + "x" +
      std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
    return false;
  }
  header = { static_cast<std::uint64_t>(dims[0]), static_cast<std::uint64_t>(dims[1]),
    static_cast<std::uint64_t>(dims[2]), 1, 4, true };
  return true;
}

/// The header of `path` in `format`; false with `problem` set.
bool ReadHeader(const std::string& path, const ImageFormat& format, std::uint64_t maxSamples,
  ImageHeader& header, std::string& problem)
{
  switch (format.id)
  {
    case ImageFormat::PNG:
    {
      std::string text;
      return ReadFile(path, text, problem) && CheckPng(text, header, maxSamples, problem);
    }
    case ImageFormat::JPEG:
      return JpegHeader(path, header, problem);
    case ImageFormat::TIFF:
      return TiffHeader(path, header, problem) && WithinLimit(header, maxSamples, problem) &&
        CheckTiffDirectories(path, header.depth, problem);
    case ImageFormat::BMP:
      return BmpHeader(path, header, problem) && WithinLimit(header, maxSamples, problem) &&
        BmpPixelsInFile(path, header, problem);
    case ImageFormat::PNM:
      return PnmHeader(path, maxSamples, header, problem);
    case ImageFormat::VTI:
      return VtkHeader(path, true, header, problem) && CheckXmlCompleteness(path, problem);
    case ImageFormat::LegacyVTK:
      return CheckLegacyCounts(path, maxSamples, problem) && VtkHeader(path, false, header, problem);
  }
  return true;
}

} // namespace

bool CheckImageFile(const std::string& path, const ImageFormat& format, std::uint64_t maxSamples,
  ImageHeader& header, std::string& error)
{
  std::string problem;
  if (!ReadHeader(path, format, maxSamples, header, problem) ||
    (header.known && !WithinLimit(header, maxSamples, problem)))
  {
    error = problem.rfind(path + ":", 0) == 0 ? problem : path + ": " + problem;
    return false;
  }
  if (header.known && (header.width == 0 || header.height == 0))
  {
    error = path + ": the file declares an empty image (" + SizeText(header) + ")";
    return false;
  }
  return true;
}

} // namespace shockio
