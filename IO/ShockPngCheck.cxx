#include "ShockImageChecks.h"

#include "ShockIOMessages.h"

#include "vtk_zlib.h"

#include <algorithm>
#include <array>
#include <memory>
#include <cstring>
#include <string_view>
#include <vector>

namespace shockio
{
namespace
{

std::uint32_t BigEndian32(const unsigned char* bytes)
{
  return (std::uint32_t{ bytes[0] } << 24) | (std::uint32_t{ bytes[1] } << 16) |
    (std::uint32_t{ bytes[2] } << 8) | std::uint32_t{ bytes[3] };
}

/// The fields of IHDR.
struct PngImage
{
  std::uint32_t width = 0, height = 0;
  int bitDepth = 0, colorType = 0, interlace = 0;
  int Channels() const
  {
    switch (this->colorType)
    {
      case 2:
        return 3;
      case 4:
        return 2;
      case 6:
        return 4;
      default:
        return 1;
    }
  }
};

/// libpng refuses (with a longjmp) rows or columns of more pixels than this by default.
constexpr std::uint32_t LibpngMaxDimension = 1000000;

/// Whether IHDR's 13 bytes are valid for libpng; else `problem` is set.
bool ReadIhdr(const unsigned char* data, std::uint32_t length, PngImage& image, std::string& problem)
{
  if (length != 13)
  {
    problem = "the IHDR chunk has " + std::to_string(length) + " bytes, not 13";
    return false;
  }
  image.width = BigEndian32(data);
  image.height = BigEndian32(data + 4);
  image.bitDepth = data[8];
  image.colorType = data[9];
  image.interlace = data[12];
  static const std::array<std::vector<int>, 7> depths = { std::vector<int>{ 1, 2, 4, 8, 16 }, {},
    { 8, 16 }, { 1, 2, 4, 8 }, { 8, 16 }, {}, { 8, 16 } };
  const bool depthValid = image.colorType < 7 &&
    std::find(depths[image.colorType].begin(), depths[image.colorType].end(), image.bitDepth) !=
      depths[image.colorType].end();
  if (image.width == 0 || image.height == 0 || image.width > LibpngMaxDimension ||
    image.height > LibpngMaxDimension)
  {
    problem = "the PNG header declares " + std::to_string(image.width) + "x" +
      std::to_string(image.height) + " pixels (each side must be 1 to 1000000)";
    return false;
  }
  if (!depthValid || data[10] != 0 || data[11] != 0 || image.interlace > 1)
  {
    problem = "invalid PNG header (colour type " + std::to_string(image.colorType) + ", bit depth " +
      std::to_string(image.bitDepth) + ", compression " + std::to_string(data[10]) + ", filter " +
      std::to_string(data[11]) + ", interlace " + std::to_string(image.interlace) + ")";
    return false;
  }
  return true;
}

/**
 * Walks the rows of the inflated image data (Adam7 passes when interlaced):
 * each row is a filter byte (0 to 4) and the row's pixel bytes.
 */
class PngRows
{
public:
  explicit PngRows(const PngImage& image)
    : Image(image)
  {
    this->StartPass(image.interlace ? 0 : -1);
  }

  /// Takes `count` inflated bytes; false with `problem` set if they do not fit the rows.
  bool Take(const unsigned char* bytes, std::size_t count, std::string& problem)
  {
    for (std::size_t i = 0; i < count;)
    {
      if (this->LeftInRow == 0)
      {
        if (!this->NextRow())
        {
          problem = "the PNG image data is longer than the image";
          return false;
        }
        if (bytes[i] > 4)
        {
          problem = "the PNG image data has an invalid filter byte " + std::to_string(bytes[i]);
          return false;
        }
        ++i;
        continue;
      }
      const std::size_t take = std::min<std::uint64_t>(this->LeftInRow, count - i);
      this->LeftInRow -= take;
      i += take;
    }
    return true;
  }

  /// Whether every row was complete.
  bool Complete() const { return this->LeftInRow == 0 && !this->NextRowExists(); }

private:
  /// Pass -1: the whole image; 0 to 6: the Adam7 passes.
  void StartPass(int pass)
  {
    static const int x0[] = { 0, 4, 0, 2, 0, 1, 0 }, y0[] = { 0, 0, 4, 0, 2, 0, 1 },
                     dx[] = { 8, 8, 4, 4, 2, 2, 1 }, dy[] = { 8, 8, 8, 4, 4, 2, 2 };
    this->Pass = pass;
    const std::uint64_t w = this->Image.width, h = this->Image.height;
    const auto count = [](std::uint64_t size, int start, int step) {
      return size > static_cast<std::uint64_t>(start) ? (size - start + step - 1) / step : 0;
    };
    const std::uint64_t columns = pass < 0 ? w : count(w, x0[pass], dx[pass]);
    this->RowsLeft = columns == 0 ? 0 : (pass < 0 ? h : count(h, y0[pass], dy[pass]));
    const std::uint64_t bits = columns * this->Image.Channels() * this->Image.bitDepth;
    this->RowBytes = (bits + 7) / 8;
  }

  bool NextRowExists() const
  {
    if (this->RowsLeft > 0)
    {
      return true;
    }
    for (int pass = this->Pass + 1; this->Pass >= 0 && pass < 7; ++pass)
    {
      PngRows probe(*this);
      probe.StartPass(pass);
      if (probe.RowsLeft > 0)
      {
        return true;
      }
    }
    return false;
  }

  bool NextRow()
  {
    while (this->RowsLeft == 0)
    {
      if (this->Pass < 0 || this->Pass >= 6)
      {
        return false;
      }
      this->StartPass(this->Pass + 1);
    }
    --this->RowsLeft;
    this->LeftInRow = this->RowBytes;
    return true;
  }

  PngImage Image;
  int Pass = -1;
  std::uint64_t RowsLeft = 0, RowBytes = 0, LeftInRow = 0;
};

/// Inflates the concatenated IDAT data, feeding the rows; false with `problem` set.
class PngInflater
{
public:
  explicit PngInflater(const PngImage& image)
    : Rows(image)
  {
    std::memset(&this->Stream, 0, sizeof(this->Stream));
    this->Ready = inflateInit(&this->Stream) == Z_OK;
  }
  ~PngInflater() { inflateEnd(&this->Stream); }
  PngInflater(const PngInflater&) = delete;
  PngInflater& operator=(const PngInflater&) = delete;

  /// Whether data was fed.
  bool Started() const { return this->Fed; }

  bool Feed(const unsigned char* data, std::uint32_t length, std::string& problem)
  {
    this->Fed = true;
    if (!this->Ready)
    {
      problem = "zlib could not start";
      return false;
    }
    if (this->Ended)
    {
      return length == 0 || (problem = "data after the end of the compressed PNG image", false);
    }
    this->Stream.next_in = const_cast<Bytef*>(data);
    this->Stream.avail_in = length;
    std::array<unsigned char, 65536> out;
    while (this->Stream.avail_in > 0 && !this->Ended)
    {
      this->Stream.next_out = out.data();
      this->Stream.avail_out = static_cast<uInt>(out.size());
      const int status = inflate(&this->Stream, Z_NO_FLUSH);
      if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR)
      {
        problem = std::string("the compressed PNG image data is damaged (zlib: ") +
          (this->Stream.msg ? this->Stream.msg : "error") + ")";
        return false;
      }
      if (!this->Rows.Take(out.data(), out.size() - this->Stream.avail_out, problem))
      {
        return false;
      }
      this->Ended = status == Z_STREAM_END;
      if (status == Z_BUF_ERROR && this->Stream.avail_out != 0)
      {
        break; // needs more input
      }
    }
    return true;
  }

  bool Finish(std::string& problem)
  {
    if (!this->Ended || !this->Rows.Complete())
    {
      problem = "the PNG image data is shorter than the image (truncated or damaged IDAT)";
      return false;
    }
    return true;
  }

private:
  z_stream Stream;
  PngRows Rows;
  bool Ready = false;
  bool Ended = false;
  bool Fed = false;
};

} // namespace

bool CheckPng(const std::string& text, ImageHeader& header, std::uint64_t maxSamples, std::string& problem)
{
  static const unsigned char signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
  const auto* bytes = reinterpret_cast<const unsigned char*>(text.data());
  if (text.size() < 8 || std::memcmp(bytes, signature, 8) != 0)
  {
    problem = "not a PNG file (no PNG signature)";
    return false;
  }
  PngImage image;
  std::unique_ptr<PngInflater> inflater;
  bool palette = false, idatEnded = false;
  for (std::size_t at = 8, index = 0;; ++index)
  {
    if (text.size() - at < 12)
    {
      problem = "the PNG file is truncated (it ends before its IEND chunk)";
      return false;
    }
    const std::uint32_t length = BigEndian32(bytes + at);
    const std::string_view type(text.data() + at + 4, 4);
    if (length > 0x7fffffffu || text.size() - at - 12 < length)
    {
      problem = "the PNG chunk " + Quoted(type) + " is truncated or declares a wrong length";
      return false;
    }
    const unsigned char* data = bytes + at + 8;
    const std::uint32_t crc = static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), bytes + at + 4, length + 4));
    if (crc != BigEndian32(data + length))
    {
      problem = "the PNG chunk " + Quoted(type) + " is damaged (CRC mismatch)";
      return false;
    }
    at += 12 + std::size_t{ length };
    if ((index == 0) != (type == "IHDR"))
    {
      problem = index == 0 ? "the PNG file does not start with an IHDR chunk" : "a second IHDR chunk";
      return false;
    }
    if (type == "IHDR")
    {
      if (!ReadIhdr(data, length, image, problem))
      {
        return false;
      }
      header = { image.width, image.height, 1, static_cast<std::uint64_t>(image.Channels()),
        image.bitDepth == 16 ? 2u : 1u, true };
      if (!WithinLimit(header, maxSamples, problem))
      {
        return false;
      }
      inflater = std::make_unique<PngInflater>(image);
      continue;
    }
    palette = palette || type == "PLTE";
    if (type == "IDAT")
    {
      if (idatEnded)
      {
        problem = "the PNG IDAT chunks are not consecutive";
        return false;
      }
      if ((image.colorType == 3 && !palette) || !inflater->Feed(data, length, problem))
      {
        problem = problem.empty() ? "a palette PNG without a PLTE chunk before its data" : problem;
        return false;
      }
      continue;
    }
    idatEnded = idatEnded || inflater->Started();
    if (type == "IEND")
    {
      return inflater->Finish(problem);
    }
  }
}

} // namespace shockio
