#include "ShockImageIO.h"

#include "ShockIOFiles.h"
#include "ShockIOMessages.h"
#include "ShockImageChecks.h"

#include "vtkBMPReader.h"
#include "vtkBMPWriter.h"
#include "vtkFloatArray.h"
#include "vtkImageFlip.h"
#include "vtkJPEGReader.h"
#include "vtkJPEGWriter.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPNMReader.h"
#include "vtkUnsignedCharArray.h"
#include "vtkPNMWriter.h"
#include "vtkPointData.h"
#include "vtkStructuredPointsReader.h"
#include "vtkStructuredPointsWriter.h"
#include "vtkTIFFReader.h"
#include "vtkTIFFWriter.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkOutputWindow.h"
#include "vtk_tiff.h"

#include <algorithm>
#include <cmath>
#include <sys/mman.h>
#include <unistd.h>
#include <cstdarg>
#include <cstdio>
#include <new>

namespace shockio
{

const std::vector<ImageFormat>& ImageFormats()
{
  static const std::vector<ImageFormat> formats = {
    { ImageFormat::PNG, "PNG", { "png" }, { VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT }, { 1, 2, 3, 4 },
      false },
    { ImageFormat::JPEG, "JPEG", { "jpg", "jpeg" }, { VTK_UNSIGNED_CHAR }, { 1, 3 }, false },
    { ImageFormat::TIFF, "TIFF", { "tif", "tiff" },
      { VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT, VTK_FLOAT }, { 1, 3, 4 }, true },
    { ImageFormat::BMP, "BMP", { "bmp" }, { VTK_UNSIGNED_CHAR }, { 1, 3 }, false },
    { ImageFormat::PNM, "PNM", { "pnm", "ppm", "pgm" }, { VTK_UNSIGNED_CHAR }, { 1, 3 }, false },
    { ImageFormat::VTI, "VTK XML image", { "vti" }, {}, {}, true },
    { ImageFormat::LegacyVTK, "legacy VTK structured points", { "vtk" }, {}, {}, true },
  };
  return formats;
}

const ImageFormat* ImageFormatOf(const std::string& path, std::string& error)
{
  return FormatOfPath(ImageFormats(), path, "image", error);
}

std::string DimensionsText(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  return std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
}

vtkSmartPointer<vtkUnsignedCharArray> QuantizeToBytes(
  vtkDataArray* values, double scale, vtkIdType* clamped)
{
  auto bytes = vtkSmartPointer<vtkUnsignedCharArray>::New();
  bytes->SetName(values->GetName());
  bytes->SetNumberOfComponents(values->GetNumberOfComponents());
  bytes->SetNumberOfTuples(values->GetNumberOfTuples());
  vtkIdType outside = 0;
  const vtkIdType count = values->GetNumberOfValues();
  const int components = values->GetNumberOfComponents();
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double v =
      std::round(values->GetComponent(i / components, static_cast<int>(i % components)) * scale);
    const double inRange = std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 255.0);
    outside += inRange != v ? 1 : 0;
    bytes->SetValue(i, static_cast<unsigned char>(inRange));
  }
  if (clamped)
  {
    *clamped = outside;
  }
  return bytes;
}

namespace
{

/// A reader of one of the vtkImageReader2 formats, checked with CanReadFile; null with `error` set.
template <typename Reader>
vtkSmartPointer<vtkAlgorithm> MakeRasterReader(
  const std::string& path, const ImageFormat& format, std::string& error)
{
  auto reader = vtkSmartPointer<Reader>::New();
  if (!reader->CanReadFile(path.c_str()))
  {
    error = path + ": not a valid " + std::string(format.name) + " file";
    return nullptr;
  }
  reader->SetFileName(path.c_str());
  return reader;
}

/// The legacy structured points reader, reading every array; null with `error` set.
vtkSmartPointer<vtkAlgorithm> MakeLegacyReader(const std::string& path, std::string& error)
{
  auto reader = vtkSmartPointer<vtkStructuredPointsReader>::New();
  reader->SetFileName(path.c_str());
  // Every array, not only the first of each attribute kind.
  reader->ReadAllScalarsOn();
  reader->ReadAllVectorsOn();
  reader->ReadAllNormalsOn();
  reader->ReadAllTensorsOn();
  reader->ReadAllColorScalarsOn();
  reader->ReadAllTCoordsOn();
  reader->ReadAllFieldsOn();
  if (!reader->IsFileStructuredPoints())
  {
    error = path + ": not a legacy VTK file of structured points (image data)";
    return nullptr;
  }
  return reader;
}

/// The reader for `path`, after checking that the file has the right format; null with `error` set.
vtkSmartPointer<vtkAlgorithm> MakeReader(
  const std::string& path, const ImageFormat& format, MessageTrap* trap, std::string& error)
{
  vtkSmartPointer<vtkAlgorithm> reader;
  switch (format.id)
  {
    case ImageFormat::PNG:
      reader = MakeRasterReader<vtkPNGReader>(path, format, error);
      break;
    case ImageFormat::JPEG:
      reader = MakeRasterReader<vtkJPEGReader>(path, format, error);
      break;
    case ImageFormat::TIFF:
      reader = MakeRasterReader<vtkTIFFReader>(path, format, error);
      break;
    case ImageFormat::BMP:
      reader = MakeRasterReader<vtkBMPReader>(path, format, error);
      break;
    case ImageFormat::PNM:
      reader = MakeRasterReader<vtkPNMReader>(path, format, error);
      break;
    case ImageFormat::VTI:
    {
      auto xml = vtkSmartPointer<vtkXMLImageDataReader>::New();
      xml->SetReaderErrorObserver(trap);
      xml->SetParserErrorObserver(trap);
      if (xml->CanReadFile(path.c_str()))
      {
        xml->SetFileName(path.c_str());
        reader = xml;
      }
      else
      {
        error = path + ": not a valid VTK XML image data (.vti) file";
      }
      break;
    }
    case ImageFormat::LegacyVTK:
      reader = MakeLegacyReader(path, error);
      break;
  }
  if (reader)
  {
    trap->Watch(reader);
  }
  return reader;
}

/**
 * vtkTIFFReader puts the first row of a TIFF with the usual top-left orientation
 * at y = 0, upside down with respect to the other readers and to vtkTIFFWriter;
 * this flips such images along y so that every format reads the same way up.
 */
vtkSmartPointer<vtkImageData> UprightTiff(vtkAlgorithm* reader, vtkImageData* image, MessageTrap* trap)
{
  auto* tiffReader = vtkTIFFReader::SafeDownCast(reader);
  const unsigned int topLeft = 1; // ORIENTATION_TOPLEFT
  if (!tiffReader || tiffReader->GetOrientationType() != topLeft)
  {
    return image;
  }
  vtkNew<vtkImageFlip> flip;
  flip->SetInputData(image);
  flip->SetFilteredAxis(1);
  trap->Watch(flip);
  flip->Update();
  return flip->GetOutput();
}

/// Runs the reader of a checked file; null with `error` set.
vtkSmartPointer<vtkImageData> RunReader(
  const std::string& path, const ImageFormat& format, std::string& error)
{
  vtkNew<MessageTrap> trap;
  vtkSmartPointer<vtkAlgorithm> reader = MakeReader(path, format, trap, error);
  vtkSmartPointer<vtkImageData> image;
  if (reader)
  {
    reader->Update();
    image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
    image = image && image->GetNumberOfPoints() > 0 ? UprightTiff(reader, image, trap) : nullptr;
  }
  if (!trap->Finish(path, error, Strictness::WarningsFail) || !reader)
  {
    return nullptr;
  }
  if (!image || image->GetNumberOfPoints() == 0)
  {
    error = path + ": no image data in the file";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->ShallowCopy(image);
  return copy;
}

} // namespace

vtkSmartPointer<vtkImageData> ReadImage(
  const std::string& path, std::uint64_t maxSamples, std::string& error)
{
  error.clear();
  const ImageFormat* format = ImageFormatOf(path, error);
  ImageHeader header;
  if (!format || !CheckReadable(path, error) ||
    !CheckImageFile(path, *format, maxSamples, header, error))
  {
    return nullptr;
  }
  try
  {
    vtkSmartPointer<vtkImageData> image = RunReader(path, *format, error);
    if (image && header.maxValue > 0 && header.maxValue < 255)
    {
      // PGM/PPM with a maximum value below 255 (e.g. 15): white is that value;
      // VTK's reader hands the raw numbers, scaled here to 0..255.
      vtkDataArray* values = image->GetPointData()->GetScalars();
      auto* bytes = vtkUnsignedCharArray::SafeDownCast(values);
      if (bytes)
      {
        const double scale = 255.0 / static_cast<double>(header.maxValue);
        for (vtkIdType i = 0; i < bytes->GetNumberOfValues(); ++i)
        {
          bytes->SetValue(i, static_cast<unsigned char>(std::min(255.0, std::round(bytes->GetValue(i) * scale))));
        }
        bytes->Modified();
      }
    }
    return image;
  }
  catch (const std::bad_alloc&)
  {
    error = path + ": out of memory reading " + SizeText(header) + " (about " +
      BytesText(header.Bytes()) + ")";
    return nullptr;
  }
}

bool CheckStorable(vtkImageData* image, const std::string& arrayName, const ImageFormat& format,
  const std::string& path, std::string& error)
{
  vtkDataArray* array = image->GetPointData()->GetArray(arrayName.c_str());
  if (!array)
  {
    return true; // not a numeric point array: the filter reports it
  }
  const std::string where = path + ": cannot write: ";
  int dims[3];
  image->GetDimensions(dims);
  if (!format.volumes && dims[2] > 1)
  {
    error = where + format.name + " holds one 2D image, the data is " + DimensionsText(image) +
      " (write .vti, .vtk or .tif)";
    return false;
  }
  const auto& counts = format.components;
  const int components = array->GetNumberOfComponents();
  if (format.id == ImageFormat::TIFF && dims[2] > 1 && components > 1)
  {
    // vtkTIFFWriter stores a volume as pages of one sample per pixel.
    error = where + "TIFF volumes hold one component per voxel, array '" + arrayName + "' has " +
      std::to_string(components) + " (write .vti or .vtk)";
    return false;
  }
  if (!counts.empty() && std::find(counts.begin(), counts.end(), components) == counts.end())
  {
    std::string allowed;
    for (std::size_t i = 0; i < counts.size(); ++i)
    {
      allowed += (i == 0 ? "" : (i + 1 == counts.size() ? " or " : ", ")) + std::to_string(counts[i]);
    }
    error = where + format.name + " stores " + allowed + " components per pixel, array '" +
      arrayName + "' has " + std::to_string(components) + " (write .vti or .vtk)";
    return false;
  }
  return true;
}

namespace
{

/**
 * The image a raster writer gets: the grid of `image` with the single point
 * array `arrayName` as scalars, converted when the format cannot store its type
 * (TIFF: to float; 8-bit formats: rounded and clamped to unsigned char 0..255,
 * which `note` tells).
 */
vtkSmartPointer<vtkImageData> PrepareRasterImage(vtkImageData* image, vtkDataArray* array,
  const std::string& arrayName, const ImageFormat& format, std::string& note)
{
  vtkSmartPointer<vtkDataArray> stored = array;
  const auto& types = format.storableTypes;
  if (std::find(types.begin(), types.end(), array->GetDataType()) == types.end())
  {
    if (std::find(types.begin(), types.end(), VTK_FLOAT) != types.end())
    {
      auto floats = vtkSmartPointer<vtkFloatArray>::New(); // exact but for integers beyond 2^24
      floats->DeepCopy(array);
      floats->SetName(array->GetName());
      stored = floats;
    }
    else
    {
      vtkIdType clamped = 0;
      stored = QuantizeToBytes(array, 1.0, &clamped);
      note = std::string(array->GetDataTypeAsString()) + " array '" + arrayName + "' written to " +
        format.name + " as unsigned char (rounded, clamped to 0..255" +
        (clamped > 0 ? "; " + std::to_string(clamped) + " values clamped" : std::string()) + ")";
    }
  }
  auto raster = vtkSmartPointer<vtkImageData>::New();
  raster->CopyStructure(image);
  raster->GetPointData()->SetScalars(stored);
  return raster;
}

/**
 * Whether a raster file just written is complete: its checks pass and it
 * declares the size of `image` (vtkTIFFWriter and others ignore failed writes).
 */
WrittenFileCheck DeclaresSize(vtkImageData* image, const ImageFormat& format)
{
  int dims[3];
  image->GetDimensions(dims);
  return [dims0 = dims[0], dims1 = dims[1], &format](const std::string& written)
  {
    ImageHeader header;
    std::string error;
    return CheckImageFile(written, format, ~std::uint64_t{ 0 }, header, error) &&
      header.width == static_cast<std::uint64_t>(dims0) && header.height == static_cast<std::uint64_t>(dims1);
  };
}

/// Runs a new writer of type Writer on `image` (after `setup`), through an OutputFile.
template <typename Writer, typename Setup>
bool Write(vtkImageData* image, const std::string& path, std::string& error, Setup setup,
  const WrittenFileCheck& check = {})
{
  vtkNew<Writer> writer;
  writer->SetInputData(image);
  setup(writer.GetPointer());
  vtkNew<MessageTrap> trap;
  const bool written = RunWriter(writer.GetPointer(), path, trap, error, check);
  return trap->Finish(path, error, Strictness::Lenient) && written;
}

template <typename Writer>
bool Write(vtkImageData* image, const std::string& path, std::string& error)
{
  return Write<Writer>(image, path, error, [](Writer*) {});
}

/// A raster writer of type Writer, its file checked (DeclaresSize()) before it replaces the target.
template <typename Writer, typename Setup>
bool WriteRaster(vtkImageData* image, const ImageFormat& format, const std::string& path,
  std::string& error, Setup setup)
{
  return Write<Writer>(image, path, error, setup, DeclaresSize(image, format));
}

/// libtiff prints its errors on stderr unless told otherwise: they go to VTK's output window.
void TiffMessage(const char* module, const char* format, va_list arguments)
{
  char text[1024];
  std::vsnprintf(text, sizeof(text), format, arguments);
  vtkOutputWindowDisplayErrorText((std::string(module ? module : "libtiff") + ": " + text).c_str());
}

/// Writes a TIFF file with libtiff's messages going to the trap of the call.
bool WriteTiff(vtkImageData* image, const ImageFormat& format, const std::string& path, std::string& error)
{
  const TIFFErrorHandler previousError = TIFFSetErrorHandler(TiffMessage);
  const TIFFErrorHandler previousWarning = TIFFSetWarningHandler(TiffMessage);
  const bool written = WriteRaster<vtkTIFFWriter>(image, format, path, error, [](vtkTIFFWriter*) {});
  TIFFSetErrorHandler(previousError);
  TIFFSetWarningHandler(previousWarning);
  return written;
}

/**
 * libpng prints its warnings and errors on stderr itself (vtkPNGWriter installs
 * no handler): what it prints during a write is caught here, and folded into
 * the one error line when the write fails (given back to stderr otherwise).
 */
class StderrCapture
{
public:
  StderrCapture()
  {
    std::fflush(stderr);
    // In memory (a full /tmp must not lose the messages of a full disk).
    const int memory = ::memfd_create("shockfilter-stderr", 0);
    this->File = memory >= 0 ? ::fdopen(memory, "w+") : std::tmpfile();
    if (!this->File && memory >= 0)
    {
      ::close(memory);
    }
    this->Saved = this->File ? ::dup(STDERR_FILENO) : -1;
    if (this->Saved < 0 || ::dup2(::fileno(this->File), STDERR_FILENO) < 0)
    {
      this->Restore();
    }
  }
  /// An unfinished capture (an exception) gives back what it caught.
  ~StderrCapture()
  {
    if (this->Saved >= 0)
    {
      const std::string text = this->Finish();
      std::fputs(text.c_str(), stderr);
    }
    this->Restore();
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  /// Ends the capture; what was printed meanwhile.
  std::string Finish()
  {
    std::string text;
    if (this->Saved >= 0)
    {
      std::fflush(stderr);
      ::dup2(this->Saved, STDERR_FILENO);
      std::rewind(this->File);
      char buffer[4096];
      size_t read = 0;
      while ((read = std::fread(buffer, 1, sizeof(buffer), this->File)) > 0 && text.size() < 65536)
      {
        text.append(buffer, read);
      }
    }
    this->Restore();
    return text;
  }

private:
  void Restore()
  {
    if (this->Saved >= 0)
    {
      std::fflush(stderr);
      ::dup2(this->Saved, STDERR_FILENO);
      ::close(this->Saved);
      this->Saved = -1;
    }
    if (this->File)
    {
      std::fclose(this->File);
      this->File = nullptr;
    }
  }
  std::FILE* File = nullptr;
  int Saved = -1;
};

bool WritePng(vtkImageData* image, const ImageFormat& format, const std::string& path, std::string& error)
{
  StderrCapture capture;
  const bool written = WriteRaster<vtkPNGWriter>(image, format, path, error, [](vtkPNGWriter*) {});
  std::string printed = capture.Finish();
  if (!written && !printed.empty())
  {
    // "libpng warning: Write Error\nlibpng error: Write Error\n" -> "(libpng: Write Error)"
    std::string said;
    size_t at = 0;
    while (at < printed.size())
    {
      const size_t end = std::min(printed.find('\n', at), printed.size());
      std::string line = printed.substr(at, end - at);
      at = end + 1;
      if (line.rfind("libpng", 0) != 0)
      {
        std::fputs((line + "\n").c_str(), stderr); // not libpng's: given back as it was
        continue;
      }
      const size_t colon = line.find(": ");
      line = colon != std::string::npos ? line.substr(colon + 2) : line;
      if (!line.empty() && said.find(line) == std::string::npos)
      {
        said += (said.empty() ? "" : "; ") + line;
      }
    }
    error += said.empty() ? "" : " (libpng: " + said + ")";
  }
  else if (!printed.empty())
  {
    std::fputs(printed.c_str(), stderr);
  }
  return written;
}

} // namespace

bool WriteImage(vtkImageData* image, const std::string& path, const std::string& arrayName,
  std::string& error, std::string& note)
{
  error.clear();
  note.clear();
  const ImageFormat* format = ImageFormatOf(path, error);
  if (!format || !CheckWritable(path, error))
  {
    return false;
  }
  switch (format->id)
  {
    case ImageFormat::VTI:
      return Write<vtkXMLImageDataWriter>(image, path, error);
    case ImageFormat::LegacyVTK:
      return Write<vtkStructuredPointsWriter>(
        image, path, error, [](vtkStructuredPointsWriter* w) { w->SetFileTypeToBinary(); });
    default:
      break;
  }
  vtkDataArray* array = image->GetPointData()->GetArray(arrayName.c_str());
  if (!array)
  {
    error = path + ": cannot write: no point array '" + arrayName + "'";
    return false;
  }
  if (!CheckStorable(image, arrayName, *format, path, error))
  {
    return false;
  }
  vtkSmartPointer<vtkImageData> raster = PrepareRasterImage(image, array, arrayName, *format, note);
  switch (format->id)
  {
    case ImageFormat::PNG:
      return WritePng(raster, *format, path, error);
    case ImageFormat::JPEG:
      return WriteRaster<vtkJPEGWriter>(
        raster, *format, path, error, [](vtkJPEGWriter* w) { w->SetQuality(95); });
    case ImageFormat::TIFF:
      return WriteTiff(raster, *format, path, error);
    case ImageFormat::BMP:
      return WriteRaster<vtkBMPWriter>(raster, *format, path, error, [](vtkBMPWriter*) {});
    case ImageFormat::PNM:
      return WriteRaster<vtkPNMWriter>(raster, *format, path, error, [](vtkPNMWriter*) {});
    default:
      return false;
  }
}

} // namespace shockio
