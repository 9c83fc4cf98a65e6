// The IO library's image files: the whole-file PNG check (written from the PNG
// specification, not from the code: chunk CRCs, IHDR rules, Adam7 passes,
// filter bytes), declared sizes against the limit, PNM headers VTK's reader
// loops on, and outputs that replace their target only when complete.
#include "IOTestSupport.h"
#include "ShockIOFiles.h"
#include "ShockImageChecks.h"
#include "ShockImageIO.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include "vtk_zlib.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
using shocktest::FileBytes;
using shocktest::TempPath;

std::string BigEndian(std::uint32_t value)
{
  return { static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8),
    static_cast<char>(value) };
}

/// A PNG chunk: length, type, data, CRC of type and data (PNG specification, 5.3).
std::string Chunk(const std::string& type, const std::string& data)
{
  const std::string body = type + data;
  const auto crc = static_cast<std::uint32_t>(
    crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size())));
  return BigEndian(static_cast<std::uint32_t>(data.size())) + body + BigEndian(crc);
}

std::string Ihdr(std::uint32_t width, std::uint32_t height, int depth, int colour, int interlace)
{
  return BigEndian(width) + BigEndian(height) + std::string{ static_cast<char>(depth), static_cast<char>(colour), 0, 0,
    static_cast<char>(interlace) };
}

std::string Deflate(const std::string& raw)
{
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string out(size, '\0');
  compress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
    static_cast<uLong>(raw.size()));
  out.resize(size);
  return out;
}

/// The image rows of a greyscale 8-bit image, each a filter byte 0 then `width` pixel bytes.
std::string Rows(std::uint32_t width, std::uint32_t height, char filter = 0)
{
  std::string rows;
  for (std::uint32_t y = 0; y < height; ++y)
  {
    rows += filter;
    for (std::uint32_t x = 0; x < width; ++x)
    {
      rows += static_cast<char>(x * 16 + y);
    }
  }
  return rows;
}

const std::string Signature = "\x89PNG\r\n\x1a\n";

std::string Png(const std::string& ihdr, const std::string& idat)
{
  return Signature + Chunk("IHDR", ihdr) + Chunk("IDAT", idat) + Chunk("IEND", "");
}

bool Check(const std::string& png, std::string& problem, std::uint64_t limit = shockio::DefaultMaxSamples)
{
  shockio::ImageHeader header;
  problem.clear();
  return shockio::CheckPng(png, header, limit, problem);
}

TEST(ShockImageIO, CompletePngsPass)
{
  std::string problem;
  EXPECT_TRUE(Check(Png(Ihdr(5, 3, 8, 0, 0), Deflate(Rows(5, 3))), problem)) << problem;
  // Adam7 (PNG specification, 8.2): pass p covers the pixels from (x0, y0) in steps (dx, dy).
  const int x0[] = { 0, 4, 0, 2, 0, 1, 0 }, y0[] = { 0, 0, 4, 0, 2, 0, 1 }, dx[] = { 8, 8, 4, 4, 2, 2, 1 },
            dy[] = { 8, 8, 8, 4, 4, 2, 2 };
  const int width = 11, height = 6;
  std::string interlaced;
  for (int pass = 0; pass < 7; ++pass)
  {
    int columns = 0, rows = 0;
    for (int x = x0[pass]; x < width; x += dx[pass])
    {
      ++columns;
    }
    for (int y = y0[pass]; y < height; y += dy[pass])
    {
      ++rows;
    }
    if (columns > 0)
    {
      interlaced += Rows(static_cast<std::uint32_t>(columns), static_cast<std::uint32_t>(rows));
    }
  }
  EXPECT_TRUE(Check(Png(Ihdr(width, height, 8, 0, 1), Deflate(interlaced)), problem)) << problem;
  // The same data read as not interlaced is too long.
  EXPECT_FALSE(Check(Png(Ihdr(width, height, 8, 0, 0), Deflate(interlaced)), problem));
}

TEST(ShockImageIO, DamagedPngsAreRefusedWithTheReason)
{
  const std::string good = Png(Ihdr(5, 3, 8, 0, 0), Deflate(Rows(5, 3)));
  std::string problem;
  std::string crc = good;
  crc[Signature.size() + 8 + 2] ^= 1; // a byte of IHDR's data
  EXPECT_FALSE(Check(crc, problem));
  EXPECT_EQ(problem, "the PNG chunk 'IHDR' is damaged (CRC mismatch)");
  EXPECT_FALSE(Check(Png(Ihdr(5, 3, 8, 0, 0), Deflate(Rows(5, 3, 5))), problem));
  EXPECT_EQ(problem, "the PNG image data has an invalid filter byte 5");
  std::string deflate = Deflate(Rows(5, 3));
  deflate[0] = 0x7f; // not a zlib header
  EXPECT_FALSE(Check(Png(Ihdr(5, 3, 8, 0, 0), deflate), problem));
  EXPECT_NE(problem.find("the compressed PNG image data is damaged"), std::string::npos) << problem;
  EXPECT_FALSE(Check(Png(Ihdr(5, 3, 8, 0, 0), Deflate(Rows(5, 2))), problem));
  EXPECT_NE(problem.find("shorter than the image"), std::string::npos) << problem;
  EXPECT_FALSE(Check(Png(Ihdr(0, 3, 8, 0, 0), Deflate("")), problem));
  EXPECT_NE(problem.find("declares 0x3 pixels"), std::string::npos) << problem;
  EXPECT_FALSE(Check(Png(Ihdr(5, 3, 16, 3, 0), Deflate(Rows(5, 3))), problem)); // palette of 16 bits
  EXPECT_NE(problem.find("invalid PNG header"), std::string::npos) << problem;
  EXPECT_FALSE(Check(good.substr(0, good.size() - 12), problem));
  EXPECT_NE(problem.find("truncated"), std::string::npos) << problem;
}

TEST(ShockImageIO, DeclaredSizesBeyondTheLimitAreRefusedBeforeTheData)
{
  // 20000 x 20000 grey pixels in a file of a few hundred bytes (the data is short).
  const std::string png = Png(Ihdr(20000, 20000, 8, 0, 0), Deflate(std::string(20001, '\0')));
  std::string problem;
  EXPECT_FALSE(Check(png, problem));
  EXPECT_EQ(problem,
    "declares 20000x20000 samples (381 MiB as read), more than the limit of 100000000 samples");
  EXPECT_FALSE(Check(png, problem, 400000000)); // within the limit, the short data is found
  EXPECT_NE(problem.find("shorter than the image"), std::string::npos) << problem;

  const std::string path = TempPath("huge.pgm");
  std::ofstream(path, std::ios::binary) << "P5\n65000 65000\n255\n" << std::string(64, '\0');
  std::string error;
  EXPECT_EQ(shockio::ReadImage(path, shockio::DefaultMaxSamples, error), nullptr);
  EXPECT_EQ(error, path + ": declares 65000x65000 samples (3.93 GiB as read), more than the limit of 100000000 samples");
}

TEST(ShockImageIO, PnmHeadersVtkLoopsOnAreRefusedAtOnce)
{
  for (const std::string header : { std::string("P6\nx"), std::string("P5\n4 4 \n"), std::string("P6\n-5 x") })
  {
    const std::string path = TempPath("loop.ppm");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << header;
    std::string error;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(shockio::ReadImage(path, shockio::DefaultMaxSamples, error), nullptr);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
    EXPECT_EQ(error, path + ": malformed PNM header (expected width, height and maximum value as numbers)");
  }
}

std::string LittleEndian(std::uint32_t value, int bytes)
{
  std::string text;
  for (int i = 0; i < bytes; ++i)
  {
    text += static_cast<char>(value >> (8 * i));
  }
  return text;
}

/**
 * A BMP file (Microsoft's BITMAPFILEHEADER, then a BITMAPINFOHEADER of 40 bytes
 * or a BITMAPCOREHEADER of 12) of `width` x `height` pixels of `bits` bits,
 * with a grey colour table of 256 entries for 8 bits, and `pixelBytes` bytes of
 * pixels (rows padded to 4 bytes), the pixel offset pointing after the table.
 */
std::string Bmp(std::int32_t width, std::int32_t height, int bits, std::size_t pixelBytes, int info = 40,
  std::uint32_t compression = 0)
{
  std::string header = info == 12
    ? LittleEndian(12, 4) + LittleEndian(static_cast<std::uint32_t>(width), 2) +
      LittleEndian(static_cast<std::uint32_t>(height), 2) + LittleEndian(1, 2) + LittleEndian(bits, 2)
    : LittleEndian(static_cast<std::uint32_t>(info), 4) + LittleEndian(static_cast<std::uint32_t>(width), 4) +
      LittleEndian(static_cast<std::uint32_t>(height), 4) + LittleEndian(1, 2) + LittleEndian(bits, 2) +
      LittleEndian(compression, 4) + std::string(20, '\0');
  header.resize(std::max<std::size_t>(header.size(), static_cast<std::size_t>(info)), '\0');
  std::string table;
  for (int i = 0; bits == 8 && i < 256; ++i)
  {
    // Blue, green, red (and a reserved byte in the 40-byte kind): entry i is (255 - i, i, i / 2).
    table += std::string{ static_cast<char>(i / 2), static_cast<char>(i), static_cast<char>(255 - i) } +
      (info == 12 ? "" : std::string(1, '\0'));
  }
  std::string pixels;
  for (std::size_t i = 0; i < pixelBytes; ++i)
  {
    pixels += static_cast<char>(i * 37 % 256);
  }
  const auto offset = static_cast<std::uint32_t>(14 + header.size() + table.size());
  return "BM" + LittleEndian(offset + static_cast<std::uint32_t>(pixels.size()), 4) + LittleEndian(0, 4) +
    LittleEndian(offset, 4) + header + table + pixels;
}

/// ReadImage's error on a file `name` holding `bytes` without its "<path>: " (empty if it was read).
std::string Refusal(const std::string& name, const std::string& bytes)
{
  const std::string path = TempPath(name);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  std::string error;
  const auto image = shockio::ReadImage(path, shockio::DefaultMaxSamples, error);
  EXPECT_EQ(image == nullptr, !error.empty()) << error;
  EXPECT_TRUE(error.empty() || error.rfind(path + ": ", 0) == 0) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  return error.empty() ? error : error.substr(path.size() + 2);
}

TEST(ShockImageIO, BmpFilesVtkReadsWellPassAndTheOthersAreRefused)
{
  // 3 x 2 pixels, rows of 3 bytes padded to 4 (8 bits) or 9 padded to 12 (24 bits).
  EXPECT_EQ(Refusal("grey.bmp", Bmp(3, 2, 8, 8)), "");
  EXPECT_EQ(Refusal("core.bmp", Bmp(3, 2, 8, 8, 12)), "");
  EXPECT_EQ(Refusal("rgb.bmp", Bmp(3, -2, 24, 24)), "");
  // The colour table is applied: pixel (0, 0) is byte 0 (entry 0), pixel (1, 0) byte 37.
  std::string error;
  const std::string path = TempPath("grey.bmp");
  const auto image = shockio::ReadImage(path, shockio::DefaultMaxSamples, error);
  ASSERT_NE(image, nullptr) << error;
  auto* colour = image->GetPointData()->GetScalars();
  ASSERT_EQ(colour->GetNumberOfComponents(), 3);
  EXPECT_EQ(colour->GetComponent(1, 0), 255 - 37);
  EXPECT_EQ(colour->GetComponent(1, 1), 37);
  EXPECT_EQ(colour->GetComponent(1, 2), 37 / 2);

  // Of the kind of the 30-byte file the fuzz search found (seeds/bmp/crash-bmp-reader-segv.bmp):
  // an 8-bit 40-byte header that ends after the bit count; VTK 9.2 read it through a null pointer.
  const std::string found = Bmp(50, 40, 8, 0).substr(0, 30);
  EXPECT_EQ(Refusal("found.bmp", found), "the BMP header is truncated (30 of 54 bytes)");
  EXPECT_EQ(Refusal("short.bmp", Bmp(3, 2, 24, 24, 12).substr(0, 25)),
    "the BMP header is truncated (25 of 26 bytes)");
  // Header kinds VTK does not read (its reader then reads pixels of depth 0).
  for (const int info : { 0, 41, 108, 124 })
  {
    EXPECT_EQ(Refusal("kind.bmp", Bmp(3, 2, 24, 24, info)),
      "a BMP with a " + std::to_string(info) +
        "-byte info header (VTK reads the 40-byte BITMAPINFOHEADER and the 12-byte OS/2 header)");
  }
  EXPECT_EQ(Refusal("rle.bmp", Bmp(3, 2, 8, 8, 40, 1)),
    "a compressed BMP (compression 1; VTK reads uncompressed BMP files only)");
  // The OS/2 header's sizes are signed 16-bit numbers: 0x8000 is -32768.
  EXPECT_EQ(Refusal("wide.bmp", Bmp(0x8000, 2, 24, 24, 12)),
    "the BMP header declares -32768x2 pixels");
  EXPECT_EQ(Refusal("rows.bmp", Bmp(3, 2, 24, 20)),
    "the BMP file holds fewer pixels than its header declares (truncated?)");
  std::string inside = Bmp(3, 2, 24, 24);
  inside[10] = 20;
  EXPECT_EQ(Refusal("inside.bmp", inside), "the BMP pixel data offset 20 lies inside its header");
}

/// A 16 x 8 RGB test image, its point scalars named "Colour".
vtkSmartPointer<vtkImageData> TestImage()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(16, 8, 1);
  vtkNew<vtkUnsignedCharArray> colour;
  colour->SetName("Colour");
  colour->SetNumberOfComponents(3);
  colour->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < colour->GetNumberOfValues(); ++i)
  {
    colour->SetValue(i, static_cast<unsigned char>(i * 7));
  }
  image->GetPointData()->SetScalars(colour);
  return image;
}

TEST(ShockImageIO, RasterFilesRoundTripAndAFailedWriteLeavesTheTarget)
{
  for (const char* extension : { "png", "jpg", "tif", "bmp", "ppm", "vti", "vtk" })
  {
    const std::string path = TempPath(std::string("image.") + extension);
    const std::string before = "the existing file, which must survive\n";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << before;
    std::string error, note;
    bool written = true;
    {
      shocktest::FileSizeLimit fullDisk(64);
      written = shockio::WriteImage(TestImage(), path, "Colour", error, note);
    }
    EXPECT_FALSE(written) << extension;
    EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
    EXPECT_EQ(FileBytes(path), before) << extension;
    EXPECT_TRUE(shocktest::PartialFiles(path).empty());

    ASSERT_TRUE(shockio::WriteImage(TestImage(), path, "Colour", error, note)) << error;
    const vtkSmartPointer<vtkImageData> read = shockio::ReadImage(path, shockio::DefaultMaxSamples, error);
    ASSERT_NE(read, nullptr) << error;
    int dims[3];
    read->GetDimensions(dims);
    EXPECT_EQ(dims[0], 16) << extension;
    EXPECT_EQ(dims[1], 8) << extension;
    if (std::string(extension) != "jpg") // lossy
    {
      vtkDataArray* values = read->GetPointData()->GetScalars();
      for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
      {
        ASSERT_EQ(values->GetComponent(i / 3, static_cast<int>(i % 3)), static_cast<unsigned char>(i * 7))
          << extension << " value " << i;
      }
    }
  }
}

// A PGM/PPM whose maximum value is below 255 (white = 15 here) is read on the
// 0..255 scale: v -> round(255 v / maxval). And a 3D RGB volume is refused for
// TIFF (its writer would store one sample per voxel), kept by .vti.
TEST(ShockImageIO, PnmMaximumValuesAndTiffVolumesAreHonoured)
{
  const std::string path = TempPath("grey15.pgm");
  std::ofstream(path, std::ios::binary | std::ios::trunc)
    << std::string("P5\n4 2\n15\n") + std::string{ 0, 5, 10, 15, 15, 15, 0, 7 };
  std::string error;
  const vtkSmartPointer<vtkImageData> read = shockio::ReadImage(path, shockio::DefaultMaxSamples, error);
  ASSERT_NE(read, nullptr) << error;
  vtkDataArray* values = read->GetPointData()->GetScalars();
  // VTK puts the last row of the file first.
  const double expected[8] = { 255, 255, 0, 119, 0, 85, 170, 255 };
  for (vtkIdType i = 0; i < 8; ++i)
  {
    EXPECT_EQ(values->GetTuple1(i), expected[i]) << i;
  }

  vtkNew<vtkImageData> volume;
  volume->SetDimensions(6, 5, 4);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("Colour");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(volume->GetNumberOfPoints());
  rgb->Fill(7);
  volume->GetPointData()->SetScalars(rgb);
  const std::string tif = TempPath("volume.tif");
  const shockio::ImageFormat* format = shockio::ImageFormatOf(tif, error);
  ASSERT_NE(format, nullptr) << error;
  EXPECT_FALSE(shockio::CheckStorable(volume, "Colour", *format, tif, error));
  EXPECT_NE(error.find("TIFF volumes hold one component per voxel"), std::string::npos) << error;
  const std::string vti = TempPath("volume.vti");
  format = shockio::ImageFormatOf(vti, error);
  ASSERT_NE(format, nullptr);
  EXPECT_TRUE(shockio::CheckStorable(volume, "Colour", *format, vti, error)) << error;
}

// A target name of 254 bytes (legal: the limit is 255) is written; its
// temporary file beside it takes a shortened name, never the target's whole.
TEST(ShockImageIO, ALongLegalNameIsWritten)
{
  const std::string path =
    (std::filesystem::path(TempPath("x")).parent_path() / (std::string(250, 'n') + ".png")).string();
  std::string error, note;
  ASSERT_TRUE(shockio::WriteImage(TestImage(), path, "Colour", error, note)) << error;
  EXPECT_NE(shockio::ReadImage(path, shockio::DefaultMaxSamples, error), nullptr) << error;
  std::remove(path.c_str());
}

} // namespace
