/**
 * @file   ShockMeshIO.cxx
 * @brief  Mesh file input and output of the `shockfilter` program (see ShockMeshIO.h).
 */
#include "ShockMeshIO.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkGeometryFilter.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOBJReader.h"
#include "vtkOBJWriter.h"
#include "vtkOutputWindow.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyDataReader.h"
#include "vtkPolyDataWriter.h"
#include "vtkSTLReader.h"
#include "vtkSTLWriter.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGridReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <tuple>
#include <type_traits>
#include <vector>

namespace shockio
{
namespace
{

enum class Format
{
  PLY,
  OBJ,
  STL,
  VTP,
  VTK,
  OFF
};

/// The format named by the extension of `path`, in any letter case.
std::optional<Format> FormatOf(const std::string& path, std::string& error)
{
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::pair<const char*, Format> formats[] = { { ".ply", Format::PLY },
    { ".obj", Format::OBJ }, { ".stl", Format::STL }, { ".vtp", Format::VTP },
    { ".vtk", Format::VTK }, { ".off", Format::OFF } };
  for (const auto& [name, format] : formats)
  {
    if (extension == name)
    {
      return format;
    }
  }
  error = path + ": " +
    (extension.empty() ? std::string("no file extension")
                       : "unknown extension '" + extension + "'") +
    " (mesh files are .ply, .obj, .stl, .vtp, .vtk or .off)";
  return std::nullopt;
}

/// `text` quoted for a one-line message: at most 40 characters, non-printable ones as '?'.
std::string Quoted(std::string_view text)
{
  std::string quoted(text.substr(0, 40));
  std::replace_if(
    quoted.begin(), quoted.end(), [](unsigned char c) { return !std::isprint(c); }, '?');
  return "'" + quoted + (text.size() > 40 ? "...'" : "'");
}

/**
 * The message of a VTK error or warning on one line: without the first line
 * "ERROR: In <file>, line <n>" (or "Warning: ...", "Generic Warning: ...") and
 * the "<class> (<address>): " prefix VTK adds, its whitespace runs made single
 * spaces.
 */
std::string CleanMessage(const std::string& text)
{
  std::string_view message = text;
  const size_t firstLineEnd = message.find('\n');
  if (firstLineEnd != std::string_view::npos &&
    message.substr(0, firstLineEnd).find(", line ") != std::string_view::npos)
  {
    message.remove_prefix(firstLineEnd + 1);
  }
  if (const size_t prefix = message.find("): "); prefix != std::string_view::npos &&
      message.substr(0, prefix).find(" (0x") != std::string_view::npos)
  {
    message.remove_prefix(prefix + 3);
  }
  std::string clean;
  for (char c : message)
  {
    if (!std::isspace(static_cast<unsigned char>(c)))
    {
      clean += c;
    }
    else if (!clean.empty() && clean.back() != ' ')
    {
      clean += ' ';
    }
  }
  if (!clean.empty() && clean.back() == ' ')
  {
    clean.pop_back();
  }
  return clean;
}

/// An output window that keeps the messages instead of showing them.
class KeepingOutputWindow : public vtkOutputWindow
{
public:
  static KeepingOutputWindow* New();
  vtkTypeMacro(KeepingOutputWindow, vtkOutputWindow);

  void DisplayText(const char* text) override { this->Messages.emplace_back(text ? text : ""); }
  void DisplayErrorText(const char* text) override { this->DisplayText(text); }
  void DisplayWarningText(const char* text) override { this->DisplayText(text); }
  void DisplayGenericWarningText(const char* text) override { this->DisplayText(text); }
  void DisplayDebugText(const char*) override {}

  std::vector<std::string> Messages;

protected:
  KeepingOutputWindow() = default;
  ~KeepingOutputWindow() override = default;
};
vtkStandardNewMacro(KeepingOutputWindow);

/**
 * Catches what VTK reports while a mesh is read or written, so that nothing is
 * printed and a failure is told on one line:
 *  - the errors and warnings of the algorithms it watches, and of their
 *    executives (whose errors only say that a request failed);
 *  - while it lives, everything else VTK would print, through VTK's output
 *    window: generic messages, such as the data errors of the legacy readers,
 *    come only there (and to vtkLogger's standard error output, which is
 *    turned off meanwhile; it comes back at the logger's verbosity cutoff, its
 *    standard error verbosity unless log files or callbacks were added).
 * VTK's output window and logger are global: not for concurrent use.
 */
class MessageTrap : public vtkCommand
{
public:
  static MessageTrap* New() { return new MessageTrap; }

  void Execute(vtkObject* caller, unsigned long event, void* callData) override
  {
    const char* text = static_cast<const char*>(callData);
    if (event == vtkCommand::WarningEvent)
    {
      this->Warnings.emplace_back(text ? text : "");
    }
    else if (vtkExecutive::SafeDownCast(caller))
    {
      this->RequestFailed = true;
    }
    else if (this->Error.empty())
    {
      this->Error = CleanMessage(text ? text : "");
      this->Error = this->Error.empty() ? "unknown VTK error" : this->Error;
    }
  }

  /// Observes an algorithm and its executive.
  void Watch(vtkAlgorithm* algorithm)
  {
    for (vtkObject* object :
      { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
    {
      object->AddObserver(vtkCommand::ErrorEvent, this);
      object->AddObserver(vtkCommand::WarningEvent, this);
    }
  }

  /**
   * Gives VTK's output window back and tells whether nothing went wrong: no
   * error of the watched objects, no message through the output window. Else
   * sets `error` to "<path>: <reason>", the reason being the first error, else
   * the first message of the output window, else the first warning (vtkPLYReader
   * only warns before it fails). On success the warnings of the watched objects
   * go on to the output window, where they would have gone unobserved.
   */
  bool Finish(const std::string& path, std::string& error)
  {
    this->Restore();
    const std::vector<std::string>& printed = this->Window->Messages;
    if (this->Error.empty() && !this->RequestFailed && printed.empty())
    {
      for (const std::string& warning : this->Warnings)
      {
        vtkOutputWindowDisplayWarningText(warning.c_str());
      }
      return true;
    }
    std::string reason = this->Error;
    if (reason.empty() && !printed.empty())
    {
      reason = CleanMessage(printed.front());
    }
    if (reason.empty() && !this->Warnings.empty())
    {
      reason = CleanMessage(this->Warnings.front());
    }
    error = path + ": " + (reason.empty() ? "VTK reported a failure" : reason);
    return false;
  }

protected:
  MessageTrap()
    : Previous(vtkOutputWindow::GetInstance())
    , LoggerVerbosity(vtkLogger::GetCurrentVerbosityCutoff())
  {
    vtkOutputWindow::SetInstance(this->Window);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~MessageTrap() override { this->Restore(); }

private:
  void Restore()
  {
    if (this->Previous)
    {
      vtkOutputWindow::SetInstance(this->Previous);
      vtkLogger::SetStderrVerbosity(this->LoggerVerbosity);
      this->Previous = nullptr;
    }
  }

  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkLogger::Verbosity LoggerVerbosity;
  vtkNew<KeepingOutputWindow> Window;
  std::string Error;
  std::vector<std::string> Warnings;
  bool RequestFailed = false;
};

/// A new mesh sharing the data of an algorithm's output but not tied to the algorithm.
vtkSmartPointer<vtkPolyData> Detached(vtkPolyData* output)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(output);
  return mesh;
}

/// Whether `path` exists, is no directory, opens for reading and is not empty; else sets `error`.
bool CheckReadable(const std::string& path, std::string& error)
{
  std::error_code code;
  const auto status = std::filesystem::status(path, code);
  if (!std::filesystem::exists(status))
  {
    error = path + ": no such file";
  }
  else if (std::filesystem::is_directory(status))
  {
    error = path + ": is a directory, not a mesh file";
  }
  else if (!std::ifstream(path, std::ios::binary))
  {
    error = path + ": cannot be opened for reading";
  }
  else if (std::filesystem::is_regular_file(status) && std::filesystem::file_size(path, code) == 0)
  {
    error = path + ": the file is empty";
  }
  else
  {
    return true;
  }
  return false;
}

// --- Colours and faces ------------------------------------------------------------

/**
 * The colours among point or cell data: the active scalars, else the array
 * `name`, if it is an unsigned-char array of 3 or 4 components with `count`
 * tuples; else null.
 */
vtkUnsignedCharArray* FindColors(vtkDataSetAttributes* data, const char* name, vtkIdType count)
{
  for (vtkDataArray* array : { data->GetScalars(), data->GetArray(name) })
  {
    auto* colors = vtkUnsignedCharArray::SafeDownCast(array);
    if (colors && (colors->GetNumberOfComponents() == 3 || colors->GetNumberOfComponents() == 4) &&
      colors->GetNumberOfTuples() == count)
    {
      return colors;
    }
  }
  return nullptr;
}

/**
 * The polygons of `mesh` followed by the triangles of its strips, with the
 * matching cell data (a strip's data goes to each of its triangles), and its
 * points and point data; vertex and line cells are dropped. `mesh` itself when
 * it has polygons only.
 */
vtkSmartPointer<vtkPolyData> FacesOnly(vtkPolyData* mesh)
{
  if (mesh->GetNumberOfVerts() == 0 && mesh->GetNumberOfLines() == 0 &&
    mesh->GetNumberOfStrips() == 0)
  {
    return mesh;
  }
  auto faces = vtkSmartPointer<vtkPolyData>::New();
  faces->SetPoints(mesh->GetPoints());
  faces->GetPointData()->PassData(mesh->GetPointData());
  vtkCellData* inCells = mesh->GetCellData();
  vtkCellData* outCells = faces->GetCellData();
  outCells->CopyAllocate(inCells);
  vtkNew<vtkCellArray> polys;
  // Cell data is ordered vertices, lines, polygons, strips.
  vtkIdType cellId = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* inPolys = mesh->GetPolys();
  for (inPolys->InitTraversal(); inPolys->GetNextCell(size, ids); ++cellId)
  {
    outCells->CopyData(inCells, cellId, polys->InsertNextCell(size, ids));
  }
  vtkCellArray* strips = mesh->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(size, ids); ++cellId)
  {
    for (vtkIdType k = 0; k + 2 < size; ++k)
    {
      // The orientation alternates along a strip.
      const vtkIdType triangle[3] = { ids[k + k % 2], ids[k + 1 - k % 2], ids[k + 2] };
      outCells->CopyData(inCells, cellId, polys->InsertNextCell(3, triangle));
    }
  }
  faces->SetPolys(polys);
  return faces;
}

/// The largest number of points of a polygon of `mesh`.
vtkIdType LargestPolygon(vtkPolyData* mesh)
{
  vtkIdType largest = 0;
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    largest = std::max(largest, size);
  }
  return largest;
}

/// The words of a line, separated by any of `separators` (by default the C locale's white space).
std::vector<std::string_view> Words(
  std::string_view line, std::string_view separators = " \t\n\v\f\r")
{
  std::vector<std::string_view> words;
  const auto isSpace = [separators](
                         char c) { return separators.find(c) != std::string_view::npos; };
  auto at = line.begin();
  while ((at = std::find_if_not(at, line.end(), isSpace)) != line.end())
  {
    const auto stop = std::find_if(at, line.end(), isSpace);
    words.emplace_back(&*at, static_cast<size_t>(stop - at));
    at = stop;
  }
  return words;
}

/// Reads the whole file into `text`; false with `error` set on failure.
bool ReadFile(const std::string& path, std::string& text, std::string& error)
{
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = file ? static_cast<std::streamoff>(file.tellg()) : -1;
  if (size >= 0)
  {
    text.resize(static_cast<size_t>(size));
    file.seekg(0);
    file.read(text.data(), size);
  }
  if (size < 0 || !file)
  {
    error = path + ": reading failed";
    return false;
  }
  return true;
}

/// Writes `text` as the file `path`; false with `error` set on failure.
bool WriteFile(const std::string& path, const std::string& text, std::string& error)
{
  std::ofstream file(path, std::ios::binary);
  if (!file)
  {
    error = path + ": cannot be opened for writing";
    return false;
  }
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  file.close();
  if (!file)
  {
    error = path + ": writing failed (is the disk full?)";
    return false;
  }
  return true;
}

// --- OFF ------------------------------------------------------------------------------

/// The whitespace-separated words of an OFF line whose comment is removed, and the line's number.
struct OffLine
{
  size_t number = 0;
  std::vector<std::string_view> words;
};

/// Hands out the lines of an OFF text that hold words, skipping blank and comment-only ones.
class OffLines
{
public:
  explicit OffLines(std::string_view text)
    : Text(text)
  {
  }

  /// The next line with words; nullopt at the end of the text.
  std::optional<OffLine> Next()
  {
    while (this->Position < this->Text.size())
    {
      const size_t end = std::min(this->Text.find('\n', this->Position), this->Text.size());
      std::string_view line = this->Text.substr(this->Position, end - this->Position);
      this->Position = end + 1;
      ++this->Number;
      OffLine result{ this->Number, Words(line.substr(0, line.find('#'))) };
      if (!result.words.empty())
      {
        return result;
      }
    }
    return std::nullopt;
  }

private:
  std::string_view Text;
  size_t Position = 0;
  size_t Number = 0;
};

/// Parses a whole word as a finite number.
bool ParseNumber(std::string_view word, double& value)
{
  const char* end = word.data() + word.size();
  if (word.size() > 1 && word[0] == '+' && word[1] != '-')
  {
    word.remove_prefix(1); // from_chars takes no leading '+'
  }
  const auto [stop, code] = std::from_chars(word.data(), end, value);
  return code == std::errc() && stop == end && std::isfinite(value);
}

/// Parses a whole word as a non-negative integer.
bool ParseCount(std::string_view word, std::int64_t& value)
{
  const char* end = word.data() + word.size();
  const auto [stop, code] = std::from_chars(word.data(), end, value);
  return code == std::errc() && stop == end && value >= 0;
}

/// Whether a number is written as a real rather than an integer.
bool IsRealLiteral(std::string_view word)
{
  return word.find_first_of(".eE") != std::string_view::npos;
}

/// The colours of the vertices or faces of an OFF file as read: values, and each element's line.
struct OffColors
{
  int components = 0; ///< 0 (none), 3 or 4
  std::vector<double> values;
  std::vector<size_t> lines;
};

/**
 * Parses the colour words of an element (0, 3 or 4; every element of a kind
 * must have as many) into `colors`; returns an error text or "".
 */
std::string ReadOffColor(const std::vector<std::string_view>& words, size_t first, size_t line,
  OffColors& colors, bool& anyReal, bool firstElement)
{
  const auto count = static_cast<int>(words.size() - first);
  if (count != 0 && count != 3 && count != 4)
  {
    return count == 1 ? "colour-map indices are not supported (give an RGB or RGBA colour)"
                      : std::to_string(count) + " colour values; a colour has 3 (RGB) or 4 (RGBA)";
  }
  if (firstElement)
  {
    colors.components = count;
  }
  else if (count != colors.components)
  {
    return std::to_string(count) + " colour values, but the first one has " +
      std::to_string(colors.components);
  }
  for (size_t w = first; w < words.size(); ++w)
  {
    double value = 0.0;
    if (!ParseNumber(words[w], value))
    {
      return "colour value " + Quoted(words[w]) + " is not a number";
    }
    anyReal = anyReal || IsRealLiteral(words[w]);
    colors.values.push_back(value);
  }
  if (count > 0)
  {
    colors.lines.push_back(line);
  }
  return "";
}

/**
 * The colours as an unsigned-char array named `name`: 0..1 reals scaled to
 * 0..255 when `real`, else 0..255 integers. Sets `error` for a value out of range.
 */
vtkSmartPointer<vtkUnsignedCharArray> OffColorArray(
  const OffColors& colors, bool real, const char* name, const std::string& path, std::string& error)
{
  auto array = vtkSmartPointer<vtkUnsignedCharArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(colors.components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(colors.lines.size()));
  for (size_t i = 0; i < colors.values.size(); ++i)
  {
    const double value = colors.values[i];
    const bool valid = real ? value >= 0.0 && value <= 1.0
                            : value >= 0.0 && value <= 255.0 && value == std::floor(value);
    if (!valid)
    {
      std::ostringstream message;
      message << path << ": line " << colors.lines[i / colors.components] << ": colour value "
              << value
              << (real ? " is not in 0..1 (the file's colours are reals)"
                       : " is not an integer in 0..255 (the file's colours are integers)");
      error = message.str();
      return nullptr;
    }
    array->SetValue(static_cast<vtkIdType>(i),
      static_cast<unsigned char>(std::lround(real ? 255.0 * value : value)));
  }
  return array;
}

/// Reads an OFF or COFF file (the format ReadMesh() describes).
vtkSmartPointer<vtkPolyData> ReadOff(const std::string& path, std::string& error)
{
  std::string text;
  if (!ReadFile(path, text, error))
  {
    return nullptr;
  }
  OffLines lines(text);
  const auto fail = [&](const std::string& what, size_t line = 0) {
    error = path + ": " + (line > 0 ? "line " + std::to_string(line) + ": " : std::string()) + what;
    return nullptr;
  };

  // The header: OFF or COFF, the counts after it or on the next line.
  std::optional<OffLine> header = lines.Next();
  if (!header)
  {
    return fail("no OFF header (the file holds only blanks and comments)");
  }
  const std::string_view keyword = header->words[0];
  const bool colored = keyword == "COFF";
  if (!colored && keyword != "OFF")
  {
    const bool variant = keyword.size() > 3 && keyword.substr(keyword.size() - 3) == "OFF";
    return fail(variant
        ? "unsupported OFF variant " + Quoted(keyword) + " (only OFF and COFF are read)"
        : "not an OFF file: it starts with " + Quoted(keyword) + ", not OFF or COFF",
      header->number);
  }
  OffLine counts{ header->number, { header->words.begin() + 1, header->words.end() } };
  if (counts.words.empty())
  {
    std::optional<OffLine> next = lines.Next();
    if (!next)
    {
      return fail("the file ends before the counts of vertices and faces");
    }
    counts = *next;
  }
  if (counts.words.front() == "BINARY")
  {
    return fail("binary OFF files are not supported", counts.number);
  }
  std::int64_t numberOfVertices = 0, numberOfFaces = 0, numberOfEdges = 0;
  if (counts.words.size() < 2 || counts.words.size() > 3 ||
    !ParseCount(counts.words[0], numberOfVertices) || !ParseCount(counts.words[1], numberOfFaces) ||
    (counts.words.size() == 3 && !ParseCount(counts.words[2], numberOfEdges)))
  {
    return fail(
      "expected the counts 'vertices faces edges' as non-negative integers", counts.number);
  }

  // Vertices, one per line. The counts are not trusted for allocations: a
  // line takes at least two bytes.
  const auto capacity = [&text](std::int64_t count) {
    return static_cast<size_t>(
      std::min<std::int64_t>(count, static_cast<std::int64_t>(text.size() / 2)));
  };
  std::vector<double> coordinates;
  coordinates.reserve(3 * capacity(numberOfVertices));
  OffColors vertexColors, faceColors;
  bool realColors = false;
  const size_t vertexWords = 3;
  for (std::int64_t v = 0; v < numberOfVertices; ++v)
  {
    const std::optional<OffLine> line = lines.Next();
    if (!line)
    {
      return fail("the file ends after " + std::to_string(v) + " of its " +
        std::to_string(numberOfVertices) + " vertices");
    }
    const std::string vertex = "vertex " + std::to_string(v) + ": ";
    if (line->words.size() < vertexWords || (!colored && line->words.size() > vertexWords))
    {
      return fail(vertex + std::to_string(line->words.size()) + " values, expected " +
          (colored ? "x y z and an RGB or RGBA colour" : "the 3 coordinates x y z"),
        line->number);
    }
    for (size_t c = 0; c < vertexWords; ++c)
    {
      double value = 0.0;
      if (!ParseNumber(line->words[c], value))
      {
        return fail(vertex + "coordinate " + Quoted(line->words[c]) + " is not a finite number",
          line->number);
      }
      coordinates.push_back(value);
    }
    if (colored)
    {
      if (line->words.size() == vertexWords)
      {
        return fail(vertex + "no colour, but the file is COFF", line->number);
      }
      const std::string problem =
        ReadOffColor(line->words, vertexWords, line->number, vertexColors, realColors, v == 0);
      if (!problem.empty())
      {
        return fail(vertex + problem, line->number);
      }
    }
  }

  // Faces, one per line: their size, the vertex ids, optionally a colour.
  vtkNew<vtkCellArray> polys;
  polys->AllocateEstimate(static_cast<vtkIdType>(capacity(numberOfFaces)), 3);
  std::vector<vtkIdType> ids;
  for (std::int64_t f = 0; f < numberOfFaces; ++f)
  {
    const std::optional<OffLine> line = lines.Next();
    if (!line)
    {
      return fail("the file ends after " + std::to_string(f) + " of its " +
        std::to_string(numberOfFaces) + " faces");
    }
    const std::string face = "face " + std::to_string(f) + ": ";
    std::int64_t size = 0;
    if (!ParseCount(line->words[0], size))
    {
      return fail(
        face + "the vertex count " + Quoted(line->words[0]) + " is not a non-negative integer",
        line->number);
    }
    if (size < 3)
    {
      return fail(face + std::to_string(size) + " vertices; a face has at least 3", line->number);
    }
    if (static_cast<std::int64_t>(line->words.size()) - 1 < size)
    {
      return fail(face + "announces " + std::to_string(size) + " vertex ids but lists " +
          std::to_string(line->words.size() - 1),
        line->number);
    }
    ids.clear();
    for (std::int64_t k = 1; k <= size; ++k)
    {
      std::int64_t id = 0;
      if (!ParseCount(line->words[static_cast<size_t>(k)], id) || id >= numberOfVertices)
      {
        return fail(face + "vertex id " + Quoted(line->words[static_cast<size_t>(k)]) +
            " is not an integer in 0.." + std::to_string(numberOfVertices - 1),
          line->number);
      }
      ids.push_back(static_cast<vtkIdType>(id));
    }
    const std::string problem = ReadOffColor(
      line->words, static_cast<size_t>(size) + 1, line->number, faceColors, realColors, f == 0);
    if (!problem.empty())
    {
      return fail(face + problem, line->number);
    }
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  if (const std::optional<OffLine> extra = lines.Next())
  {
    return fail("more data after the last of the " + std::to_string(numberOfFaces) +
        " faces (do the counts match the file?)",
      extra->number);
  }

  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(numberOfVertices));
  std::copy(
    coordinates.begin(), coordinates.end(), static_cast<double*>(points->GetVoidPointer(0)));
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  if (vertexColors.components > 0)
  {
    auto colors = OffColorArray(vertexColors, realColors, PointColorsName, path, error);
    if (!colors)
    {
      return nullptr;
    }
    mesh->GetPointData()->SetScalars(colors);
  }
  if (faceColors.components > 0)
  {
    auto colors = OffColorArray(faceColors, realColors, FaceColorsName, path, error);
    if (!colors)
    {
      return nullptr;
    }
    mesh->GetCellData()->SetScalars(colors);
  }
  return mesh;
}

/// Appends the shortest text that reads back as exactly `value`.
void AppendNumber(std::string& out, double value)
{
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

/// Appends " r g b [a]" for tuple `i` of `colors`, if any.
void AppendColor(std::string& out, vtkUnsignedCharArray* colors, vtkIdType i)
{
  for (int c = 0; colors && c < colors->GetNumberOfComponents(); ++c)
  {
    out += ' ';
    out += std::to_string(colors->GetTypedComponent(i, c));
  }
}

/// Writes an OFF (COFF with point colours) file of the polygons of `mesh`.
bool WriteOff(vtkPolyData* mesh, const std::string& path, std::string& error)
{
  const vtkSmartPointer<vtkPolyData> faces = FacesOnly(mesh);
  const vtkIdType numberOfPoints = faces->GetNumberOfPoints(),
                  numberOfFaces = faces->GetNumberOfPolys();
  vtkUnsignedCharArray* pointColors =
    FindColors(faces->GetPointData(), PointColorsName, numberOfPoints);
  vtkUnsignedCharArray* faceColors =
    FindColors(faces->GetCellData(), FaceColorsName, numberOfFaces);

  // Most readers ignore the edge count and most writers put 0.
  std::string text = std::string(pointColors ? "COFF" : "OFF") + "\n" +
    std::to_string(numberOfPoints) + " " + std::to_string(numberOfFaces) + " 0\n";
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    double p[3];
    faces->GetPoint(i, p);
    for (int c = 0; c < 3; ++c)
    {
      if (c > 0)
      {
        text += ' ';
      }
      AppendNumber(text, p[c]);
    }
    AppendColor(text, pointColors, i);
    text += '\n';
  }
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = faces->GetPolys();
  vtkIdType face = 0;
  for (polys->InitTraversal(); polys->GetNextCell(size, ids); ++face)
  {
    text += std::to_string(size);
    for (vtkIdType k = 0; k < size; ++k)
    {
      text += ' ';
      text += std::to_string(ids[k]);
    }
    AppendColor(text, faceColors, face);
    text += '\n';
  }
  return WriteFile(path, text, error);
}

// --- Checks around VTK's readers -------------------------------------------------------
// The readers of this VTK (9.2) trust their input: vtkPLYReader aborts (an
// assertion) on a truncated body or a blank line in it, crashes on a header
// without vertex coordinates or with a list where it reads a value, misreads the
// data when other elements precede the vertices and faces, and reads
// non-numbers as 0; vtkSTLReader aborts allocating the triangles a bogus binary
// header announces; vtkOBJReader crashes on texture coordinate ids out of range
// and keeps faces of missing vertices. So PLY, STL and OBJ files are checked
// before they are read, and every mesh after.

/// A PLY value type.
struct PlyType
{
  int size = 0; ///< bytes in binary files
  bool integer = false;
  bool isSigned = false;
};

/// The PLY type named `name` (the classic and the sized names).
std::optional<PlyType> PlyTypeNamed(std::string_view name)
{
  static const std::pair<const char*, PlyType> types[] = { { "char", { 1, true, true } },
    { "int8", { 1, true, true } }, { "uchar", { 1, true, false } }, { "uint8", { 1, true, false } },
    { "short", { 2, true, true } }, { "int16", { 2, true, true } },
    { "ushort", { 2, true, false } }, { "uint16", { 2, true, false } },
    { "int", { 4, true, true } }, { "int32", { 4, true, true } }, { "uint", { 4, true, false } },
    { "uint32", { 4, true, false } }, { "float", { 4, false, true } },
    { "float32", { 4, false, true } }, { "double", { 8, false, true } },
    { "float64", { 8, false, true } } };
  for (const auto& [typeName, type] : types)
  {
    if (name == typeName)
    {
      return type;
    }
  }
  return std::nullopt;
}

/// A property of a PLY element: a value, or a list when it has a count type.
struct PlyProperty
{
  std::string_view name;
  PlyType type;
  std::optional<PlyType> countType;
};

/// An element of a PLY header: its name, count and properties.
struct PlyElement
{
  std::string_view name;
  std::int64_t count = 0;
  std::vector<PlyProperty> properties;
};

/// The format of the data of a PLY file.
enum class PlyEncoding
{
  Ascii,
  LittleEndian,
  BigEndian
};

/// vtkPLY reads lines into a buffer of this size; longer ones break it.
constexpr size_t PlyLineLength = 4096;

/**
 * The words of a line of a PLY file as vtkPLY splits them (at spaces, tabs and
 * carriage returns); false with a `problem` text for a line it would misread:
 * too long, or holding a NUL character (which ends its copy of the line).
 */
bool PlyWords(std::string_view line, std::vector<std::string_view>& words, std::string& problem)
{
  if (line.size() + 1 >= PlyLineLength || line.find('\0') != std::string_view::npos)
  {
    problem = line.size() + 1 >= PlyLineLength ? "the line is longer than VTK's PLY reader takes"
                                               : "a NUL character in the line";
    return false;
  }
  words = Words(line, " \t\r");
  return true;
}

/**
 * The values of the body of a PLY file in order, as vtkPLY reads them: in an
 * ASCII file one element per line, in a binary one packed. The functions return
 * false with a `problem` text when the data does not fit.
 */
class PlyBody
{
public:
  PlyBody(std::string_view data, PlyEncoding encoding, size_t headerBytes, size_t headerLines)
    : Data(data)
    , Encoding(encoding)
    , HeaderBytes(headerBytes)
    , LineNumber(headerLines)
  {
  }

  /// Starts the next element (in an ASCII file, its line).
  bool Begin(std::string& problem)
  {
    if (this->Encoding != PlyEncoding::Ascii)
    {
      return true;
    }
    if (this->Position >= this->Data.size())
    {
      return this->EndOfData(problem);
    }
    const size_t end = std::min(this->Data.find('\n', this->Position), this->Data.size());
    const std::string_view line = this->Data.substr(this->Position, end - this->Position);
    this->Position = end + 1;
    ++this->LineNumber;
    this->NextWord = 0;
    if (!PlyWords(line, this->LineWords, problem))
    {
      return false;
    }
    if (end == this->Data.size())
    {
      problem = "the last line has no line break, which VTK's PLY reader needs";
      return false;
    }
    if (this->LineWords.empty())
    {
      problem = "a blank line in the data";
      return false;
    }
    return true;
  }

  /// The next value, of type `type`.
  bool Next(const PlyType& type, double& value, std::string& problem)
  {
    if (this->Encoding == PlyEncoding::Ascii)
    {
      if (this->NextWord >= this->LineWords.size())
      {
        problem = "fewer values than the header announces";
        return false;
      }
      const std::string_view word = this->LineWords[this->NextWord++];
      std::int64_t integer = 0;
      const bool parsed = type.integer ? ParseInteger(word, integer) : ParseNumber(word, value);
      if (!parsed)
      {
        problem = Quoted(word) + (type.integer ? " is not an integer" : " is not a finite number");
        return false;
      }
      value = type.integer ? static_cast<double>(integer) : value;
      return true;
    }
    if (this->Data.size() - this->Position < static_cast<size_t>(type.size))
    {
      return this->EndOfData(problem);
    }
    value = this->Decode(type);
    this->Position += static_cast<size_t>(type.size);
    if (!std::isfinite(value))
    {
      problem = "a value is not a finite number";
      return false;
    }
    return true;
  }

  /// Ends an element.
  bool End(std::string& problem)
  {
    if (this->Encoding == PlyEncoding::Ascii && this->NextWord < this->LineWords.size())
    {
      problem = "more values than the header announces";
      return false;
    }
    return true;
  }

  /// Where the reading is, "line <n>: " or "byte <n>: ", or "" at the end of the data.
  std::string Where() const
  {
    if (this->Ended)
    {
      return "";
    }
    return this->Encoding == PlyEncoding::Ascii
      ? "line " + std::to_string(this->LineNumber) + ": "
      : "byte " + std::to_string(this->HeaderBytes + this->Position) + ": ";
  }

private:
  bool EndOfData(std::string& problem)
  {
    this->Ended = true;
    problem = "the file ends before the data the header announces (truncated?)";
    return false;
  }

  /// Parses a whole word as an integer.
  static bool ParseInteger(std::string_view word, std::int64_t& value)
  {
    const char* end = word.data() + word.size();
    const auto [stop, code] = std::from_chars(word.data(), end, value);
    return code == std::errc() && stop == end;
  }

  /// The binary value of `type` at the current position.
  double Decode(const PlyType& type) const
  {
    std::array<unsigned char, 8> bytes{};
    std::memcpy(bytes.data(), this->Data.data() + this->Position, static_cast<size_t>(type.size));
    const std::uint16_t one = 1;
    const bool hostLittleEndian = *reinterpret_cast<const unsigned char*>(&one) == 1;
    if (hostLittleEndian != (this->Encoding == PlyEncoding::LittleEndian))
    {
      std::reverse(bytes.begin(), bytes.begin() + type.size);
    }
    const auto as = [&bytes](auto typed) {
      std::memcpy(&typed, bytes.data(), sizeof(typed));
      return static_cast<double>(typed);
    };
    switch (type.size)
    {
      case 1:
        return type.isSigned ? as(std::int8_t()) : as(std::uint8_t());
      case 2:
        return type.isSigned ? as(std::int16_t()) : as(std::uint16_t());
      case 4:
        return !type.integer ? as(float())
          : type.isSigned    ? as(std::int32_t())
                             : as(std::uint32_t());
      default:
        return as(double());
    }
  }

  std::string_view Data;
  PlyEncoding Encoding;
  size_t HeaderBytes;
  size_t Position = 0;
  size_t LineNumber;
  std::vector<std::string_view> LineWords;
  size_t NextWord = 0;
  bool Ended = false;
};

/// The index of the element called `name`, or -1.
int FindPlyElement(const std::vector<PlyElement>& elements, std::string_view name)
{
  for (size_t e = 0; e < elements.size(); ++e)
  {
    if (elements[e].name == name)
    {
      return static_cast<int>(e);
    }
  }
  return -1;
}

/// The property called `name` of an element, or null.
const PlyProperty* FindPlyProperty(const PlyElement& element, std::string_view name)
{
  for (const PlyProperty& property : element.properties)
  {
    if (property.name == name)
    {
      return &property;
    }
  }
  return nullptr;
}

/// The vertex id list of a face element, or null (vtkPLY reads 'vertex_index' as well).
const PlyProperty* FindPlyFaceIndices(const PlyElement& face)
{
  const PlyProperty* indices = FindPlyProperty(face, "vertex_indices");
  return indices ? indices : FindPlyProperty(face, "vertex_index");
}

/**
 * The first property of `element` that vtkPLYReader reads as another kind than
 * the file declares, which breaks it: one of `values` declared a list, or one
 * of `lists` declared a single value. Null if none.
 */
const PlyProperty* MisdeclaredPlyProperty(const PlyElement& element,
  std::initializer_list<std::string_view> values, std::initializer_list<std::string_view> lists)
{
  for (const PlyProperty& property : element.properties)
  {
    const auto& expected = property.countType ? values : lists;
    if (std::find(expected.begin(), expected.end(), property.name) != expected.end())
    {
      return &property;
    }
  }
  return nullptr;
}

/// What the header of a PLY file says.
struct PlyHeader
{
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;
  size_t size = 0;  ///< bytes, up to the data
  size_t lines = 0; ///< lines, up to the data
};

/**
 * Reads the header of a PLY file (`text`, which it views) as vtkPLY does, and
 * checks what vtkPLYReader needs: the vertex element first, with x, y and z
 * values, then optionally the face element with a list of integer
 * vertex_indices. False with a `problem` text otherwise.
 */
bool ReadPlyHeader(std::string_view text, PlyHeader& header, std::string& problem)
{
  std::optional<PlyEncoding> encoding;
  bool ended = false;
  while (!ended && header.size < text.size())
  {
    const size_t end = std::min(text.find('\n', header.size), text.size());
    const std::string_view line = text.substr(header.size, end - header.size);
    header.size = end + 1;
    ++header.lines;
    const std::string at = "line " + std::to_string(header.lines) + ": ";
    std::vector<std::string_view> words;
    const bool readable = PlyWords(line, words, problem);
    if (header.lines == 1 && (!readable || words.size() != 1 || words[0] != "ply"))
    {
      problem = "not a PLY file (the first line is not 'ply')";
      return false;
    }
    if (!readable || words.empty())
    {
      problem = at + (readable ? "a blank line in the header" : problem);
      return false;
    }
    const std::string_view keyword = words[0];
    if (keyword == "format")
    {
      static const std::pair<const char*, PlyEncoding> encodings[] = {
        { "ascii", PlyEncoding::Ascii }, { "binary_little_endian", PlyEncoding::LittleEndian },
        { "binary_big_endian", PlyEncoding::BigEndian }
      };
      for (const auto& [name, value] : encodings)
      {
        encoding =
          words.size() == 3 && words[1] == name ? std::optional<PlyEncoding>(value) : encoding;
      }
      if (!encoding)
      {
        problem =
          at + "unknown PLY format (expected ascii, binary_little_endian or binary_big_endian)";
        return false;
      }
    }
    else if (keyword == "element")
    {
      std::int64_t count = 0;
      if (words.size() != 3 || !ParseCount(words[2], count) ||
        count > std::numeric_limits<int>::max())
      {
        problem = at + "expected 'element <name> <count>'";
        return false;
      }
      header.elements.push_back({ words[1], count, {} });
    }
    else if (keyword == "property")
    {
      const bool list = words.size() == 5 && words[1] == "list", scalar = words.size() == 3;
      const std::optional<PlyType> countType = list ? PlyTypeNamed(words[2]) : std::nullopt;
      const std::optional<PlyType> type =
        list || scalar ? PlyTypeNamed(words[list ? 3 : 1]) : std::nullopt;
      if (header.elements.empty() || !type || (list && (!countType || !countType->integer)))
      {
        problem = at +
          "expected 'property <type> <name>' or 'property list <integer type> <type> <name>' after "
          "an element";
        return false;
      }
      header.elements.back().properties.push_back({ words.back(), *type, countType });
    }
    ended = keyword == "end_header"; // comments, obj_info and others are skipped, as vtkPLY does
  }
  if (!ended || !encoding)
  {
    problem =
      !ended ? "the PLY header has no end_header line" : "the PLY header has no format line";
    return false;
  }
  header.encoding = *encoding;

  // vtkPLYReader reads the elements in file order but skips the data of
  // others than 'vertex' and 'face': those must come first.
  const std::vector<PlyElement>& elements = header.elements;
  const int vertexElement = FindPlyElement(elements, "vertex"),
            faceElement = FindPlyElement(elements, "face");
  if (vertexElement != 0 || (faceElement >= 0 && faceElement != 1))
  {
    problem = vertexElement < 0
      ? "the PLY file has no 'vertex' element"
      : "VTK's PLY reader needs the 'vertex' element first and the 'face' element next";
    return false;
  }
  for (const char* coordinate : { "x", "y", "z" })
  {
    if (!FindPlyProperty(elements[0], coordinate))
    {
      problem = "the PLY vertices have no x, y and z values";
      return false;
    }
  }
  const PlyProperty* misdeclared = MisdeclaredPlyProperty(elements[0],
    { "x", "y", "z", "nx", "ny", "nz", "u", "v", "texture_u", "texture_v", "red", "green", "blue",
      "alpha", "diffuse_red", "diffuse_green", "diffuse_blue" },
    {});
  if (faceElement == 1)
  {
    const PlyProperty* indices = FindPlyFaceIndices(elements[1]);
    if (!indices || !indices->countType || !indices->type.integer)
    {
      problem = "the PLY faces have no 'vertex_indices' list of integers";
      return false;
    }
    misdeclared = misdeclared
      ? misdeclared
      : MisdeclaredPlyProperty(elements[1], { "intensity", "red", "green", "blue", "alpha" },
          { "vertex_indices", "vertex_index", "texcoord" });
  }
  if (misdeclared)
  {
    problem = "the PLY property '" + std::string(misdeclared->name) + "' is declared a " +
      (misdeclared->countType ? "list" : "single value") + ", which VTK's PLY reader does not take";
    return false;
  }
  return true;
}

/**
 * Checks the data of the vertices and faces of a PLY file (`text`) as its
 * header describes it: complete, numeric, finite, with at most 255 vertices
 * per face and every vertex id in range. False with a `problem` text otherwise.
 */
bool CheckPlyData(std::string_view text, const PlyHeader& header, std::string& problem)
{
  PlyBody body(
    text.substr(std::min(header.size, text.size())), header.encoding, header.size, header.lines);
  const std::int64_t numberOfVertices = header.elements[0].count;
  // ReadPlyHeader() put the vertices first and the faces, if any, second.
  const bool faces = header.elements.size() > 1 && header.elements[1].name == "face";
  const PlyProperty* indices = faces ? FindPlyFaceIndices(header.elements[1]) : nullptr;
  for (size_t e = 0; e < (faces ? 2u : 1u); ++e)
  {
    const PlyElement& element = header.elements[e];
    for (std::int64_t i = 0; i < element.count; ++i)
    {
      std::string what;
      const auto fail = [&]() {
        problem = body.Where() + std::string(element.name) + " " + std::to_string(i) + ": " + what;
        return false;
      };
      if (!body.Begin(what))
      {
        return fail();
      }
      for (const PlyProperty& property : element.properties)
      {
        const bool faceIds = &property == indices;
        double length = 1.0;
        if (property.countType && !body.Next(*property.countType, length, what))
        {
          return fail();
        }
        if (length < 0.0 || (faceIds && length > 255.0))
        {
          what = "a list of " + std::to_string(static_cast<std::int64_t>(length)) +
            (faceIds ? " vertex ids (VTK reads 0 to 255)" : " values");
          return fail();
        }
        for (std::int64_t k = 0; k < static_cast<std::int64_t>(length); ++k)
        {
          double value = 0.0;
          if (!body.Next(property.type, value, what))
          {
            return fail();
          }
          if (faceIds && (value < 0.0 || value >= static_cast<double>(numberOfVertices)))
          {
            what = "vertex id " + std::to_string(static_cast<std::int64_t>(value)) +
              " is not in 0.." + std::to_string(numberOfVertices - 1);
            return fail();
          }
        }
      }
      if (!body.End(what))
      {
        return fail();
      }
    }
  }
  return true;
}

/// Whether vtkPLYReader can read `path` safely (ReadPlyHeader(), CheckPlyData()); else sets error.
bool CheckPly(const std::string& path, std::string& error)
{
  std::string text;
  if (!ReadFile(path, text, error))
  {
    return false;
  }
  PlyHeader header;
  std::string problem;
  if (!ReadPlyHeader(text, header, problem) || !CheckPlyData(text, header, problem))
  {
    error = path + ": " + problem;
    return false;
  }
  return true;
}

/**
 * Whether `path`, if vtkSTLReader takes it for a binary STL file, holds at
 * least the triangles its header announces (50 bytes each after 84 bytes).
 */
bool CheckStl(const std::string& path, std::string& error)
{
  if (vtksys::SystemTools::DetectFileType(path.c_str()) == vtksys::SystemTools::FileTypeText)
  {
    return true;
  }
  std::ifstream file(path, std::ios::binary);
  std::array<unsigned char, 84> header{};
  if (!file.read(reinterpret_cast<char*>(header.data()), header.size()))
  {
    error = path + ": too short for a binary STL file";
    return false;
  }
  const std::uint64_t announced =
    header[80] | header[81] << 8 | header[82] << 16 | std::uint64_t(header[83]) << 24;
  std::error_code code;
  const std::uint64_t held = (std::filesystem::file_size(path, code) - header.size()) / 50;
  if (announced > held)
  {
    error = path + ": the binary STL header announces " + std::to_string(announced) +
      " triangles, but the file holds " + std::to_string(held);
    return false;
  }
  return true;
}

/**
 * Whether an OBJ id (a word) refers to an element: 1-based up to `total`, or
 * negative back from the `soFar` elements before its line.
 */
bool ObjIdInRange(std::string_view word, std::int64_t soFar, std::int64_t total)
{
  std::int64_t id = 0;
  const char* end = word.data() + word.size();
  const auto [stop, code] = std::from_chars(word.data(), end, id);
  return code == std::errc() && stop == end && (id > 0 ? id <= total : id < 0 && soFar + id >= 0);
}

/**
 * Whether vtkOBJReader can read `path` safely. It uses the ids of the faces'
 * vertices, texture coordinates and normals (and of the lines' and points'
 * vertices) unchecked, and copies material names into a 100-byte buffer: so
 * every id ("v", "v/t", "v//n" or "v/t/n") must refer to an element and every
 * material name be shorter. Positive ids may refer forward: VTK reads all the
 * file before it builds cells.
 */
bool CheckObj(const std::string& path, std::string& error)
{
  std::string text;
  if (!ReadFile(path, text, error))
  {
    return false;
  }
  std::vector<std::vector<std::string_view>> lines;
  for (size_t position = 0; position < text.size();)
  {
    const size_t end = std::min(text.find('\n', position), text.size());
    lines.push_back(Words(std::string_view(text).substr(position, end - position)));
    position = end + 1;
  }
  const auto count = [&lines](std::string_view command) {
    return static_cast<std::int64_t>(std::count_if(
      lines.begin(), lines.end(), [command](const std::vector<std::string_view>& words) {
        return !words.empty() && words[0] == command;
      }));
  };
  const std::int64_t vertices = count("v"), tcoords = count("vt"), normals = count("vn");
  std::int64_t verticesSoFar = 0, tcoordsSoFar = 0, normalsSoFar = 0;
  for (size_t l = 0; l < lines.size(); ++l)
  {
    const std::string at = "line " + std::to_string(l + 1) + ": ";
    const std::vector<std::string_view>& words = lines[l];
    const std::string_view command = words.empty() ? std::string_view() : words[0];
    verticesSoFar += command == "v";
    tcoordsSoFar += command == "vt";
    normalsSoFar += command == "vn";
    if (command == "usemtl" && words.size() > 1 && words[1].size() >= 100)
    {
      error = path + ": " + at + "a material name of 100 characters or more";
      return false;
    }
    if (command != "f" && command != "l" && command != "p")
    {
      continue;
    }
    // The ids, continued on the next lines after a lone backslash.
    std::vector<std::string_view> ids(words.begin() + 1, words.end());
    while (!ids.empty() && ids.back() == "\\" && l + 1 < lines.size())
    {
      ids.pop_back();
      ++l;
      ids.insert(ids.end(), lines[l].begin(), lines[l].end());
    }
    for (const std::string_view id : ids)
    {
      // Lines and points use the vertex id only.
      const size_t slash = id.find('/');
      const std::string_view vertex = id.substr(0, slash);
      std::string problem;
      if (!ObjIdInRange(vertex, verticesSoFar, vertices))
      {
        problem = "vertex id " + Quoted(vertex);
      }
      else if (command == "f" && slash != std::string_view::npos)
      {
        const std::string_view rest = id.substr(slash + 1);
        const size_t second = rest.find('/');
        const std::string_view tcoord = rest.substr(0, second);
        // VTK's sscanf would read "v/" on into the next id: only "v//n" leaves one out.
        if (second != 0 && !ObjIdInRange(tcoord, tcoordsSoFar, tcoords))
        {
          problem = "texture coordinate id " + Quoted(tcoord);
        }
        else if (second != std::string_view::npos &&
          !ObjIdInRange(rest.substr(second + 1), normalsSoFar, normals))
        {
          problem = "normal id " + Quoted(rest.substr(second + 1));
        }
      }
      if (!problem.empty())
      {
        error = path + ": " + at + problem + " refers to nothing";
        return false;
      }
    }
  }
  return true;
}

/**
 * Whether `mesh` as a reader made it is sound: consistent cell arrays whose ids
 * refer to its points, and point and cell data arrays with a tuple for every
 * point and cell (corrupt files, such as legacy ones with wrong counts, break
 * these; vtkOBJReader leaves extra ones when it skips faces). Else sets `error`.
 */
bool CheckStructure(vtkPolyData* mesh, const std::string& path, std::string& error)
{
  const vtkIdType numberOfPoints = mesh->GetNumberOfPoints();
  for (vtkCellArray* cells :
    { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(), mesh->GetStrips() })
  {
    vtkDataArray* ids = cells->GetConnectivityArray();
    double range[2] = { 0.0, 0.0 };
    if (ids->GetNumberOfValues() > 0)
    {
      ids->GetRange(range, 0);
    }
    if (!cells->IsValid() || range[0] < 0.0 || range[1] >= static_cast<double>(numberOfPoints))
    {
      error = path + ": a cell refers to a point the file does not have";
      return false;
    }
  }
  const std::pair<vtkFieldData*, vtkIdType> attributes[] = {
    { mesh->GetPointData(), numberOfPoints }, { mesh->GetCellData(), mesh->GetNumberOfCells() }
  };
  for (const auto& [data, count] : attributes)
  {
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = data->GetAbstractArray(a);
      if (array->GetNumberOfTuples() < count)
      {
        error = path + ": the array '" + (array->GetName() ? array->GetName() : "") + "' has " +
          std::to_string(array->GetNumberOfTuples()) + " values for " + std::to_string(count) +
          (data == mesh->GetPointData() ? " points" : " cells");
        return false;
      }
    }
  }
  return true;
}

// --- VTK readers and writers ---------------------------------------------------------
// They report their problems to the MessageTrap of the ReadMesh() or WriteMesh() call.

/// Runs a VTK reader of polygonal data on `path`; its output, complete or not.
template <typename Reader>
vtkSmartPointer<vtkPolyData> ReadWith(const std::string& path, MessageTrap* trap)
{
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  trap->Watch(reader);
  if constexpr (std::is_base_of_v<vtkXMLReader, Reader>)
  {
    reader->SetParserErrorObserver(trap); // the XML parser reports its own errors
  }
  reader->Update();
  return Detached(reader->GetOutput());
}

/// Reads a PLY file, its colour arrays renamed PointColorsName and FaceColorsName.
vtkSmartPointer<vtkPolyData> ReadPly(const std::string& path, MessageTrap* trap)
{
  vtkSmartPointer<vtkPolyData> mesh = ReadWith<vtkPLYReader>(path, trap);
  // vtkPLYReader names them "RGB" or "RGBA".
  const std::pair<vtkDataSetAttributes*, const char*> renames[] = {
    { mesh->GetPointData(), PointColorsName }, { mesh->GetCellData(), FaceColorsName }
  };
  for (const auto& [data, name] : renames)
  {
    for (const char* plyName : { "RGB", "RGBA" })
    {
      if (vtkDataArray* colors = data->GetArray(plyName))
      {
        colors->SetName(name);
        data->SetActiveScalars(name);
      }
    }
  }
  return mesh;
}

/// Reads a legacy VTK file of polydata, or of an unstructured grid whose surface is taken.
vtkSmartPointer<vtkPolyData> ReadLegacy(
  const std::string& path, MessageTrap* trap, std::string& error)
{
  vtkNew<vtkPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  trap->Watch(reader);
  if (reader->IsFilePolyData())
  {
    reader->Update();
    return Detached(reader->GetOutput());
  }
  vtkNew<vtkUnstructuredGridReader> gridReader;
  gridReader->SetFileName(path.c_str());
  trap->Watch(gridReader);
  if (!gridReader->IsFileUnstructuredGrid())
  {
    // Unless the header checks reported why (not a VTK file).
    error = path + ": the legacy VTK file holds neither polydata nor an unstructured grid";
    return nullptr;
  }
  vtkNew<vtkGeometryFilter> surface;
  surface->SetInputConnection(gridReader->GetOutputPort());
  trap->Watch(surface);
  surface->Update();
  return Detached(surface->GetOutput());
}

/// Runs a VTK writer whose input and file name are set; false with `error` set if it fails.
template <typename Writer>
bool RunWriter(Writer* writer, const std::string& path, MessageTrap* trap, std::string& error)
{
  trap->Watch(writer);
  if (writer->Write() != 1)
  {
    error = path + ": writing failed";
    return false;
  }
  return true;
}

/// Writes a binary PLY file, with the colours, normals and texture coordinates vtkPLYWriter takes.
bool WritePly(vtkPolyData* mesh, const std::string& path, MessageTrap* trap, std::string& error)
{
  const vtkSmartPointer<vtkPolyData> faces = FacesOnly(mesh);
  if (const vtkIdType largest = LargestPolygon(faces); largest > 255)
  {
    error = path + ": a polygon has " + std::to_string(largest) +
      " points; PLY polygons have at most 255";
    return false;
  }
  // vtkPLYWriter takes the point and the face colours from arrays of one name
  // and reads normals and texture coordinates as floats only: it gets a copy
  // made so, which leaves the caller's arrays alone.
  const char* colorsName = "PLYColors";
  vtkNew<vtkPolyData> copy;
  copy->SetPoints(faces->GetPoints());
  copy->SetPolys(faces->GetPolys());
  const std::tuple<vtkDataSetAttributes*, vtkDataSetAttributes*, const char*, vtkIdType>
    colorSources[] = { { faces->GetPointData(), copy->GetPointData(), PointColorsName,
                         faces->GetNumberOfPoints() },
      { faces->GetCellData(), copy->GetCellData(), FaceColorsName, faces->GetNumberOfPolys() } };
  for (const auto& [from, to, name, count] : colorSources)
  {
    if (vtkUnsignedCharArray* colors = FindColors(from, name, count))
    {
      vtkNew<vtkUnsignedCharArray> renamed;
      renamed->ShallowCopy(colors);
      renamed->SetName(colorsName);
      to->AddArray(renamed);
    }
  }
  const auto asFloat = [](vtkDataArray* array) {
    auto floats = vtkSmartPointer<vtkFloatArray>::New();
    floats->DeepCopy(array);
    return floats;
  };
  vtkPointData* pointData = faces->GetPointData();
  if (vtkDataArray* normals = pointData->GetNormals();
      normals && normals->GetNumberOfComponents() == 3)
  {
    copy->GetPointData()->SetNormals(asFloat(normals));
  }
  if (vtkDataArray* tcoords = pointData->GetTCoords();
      tcoords && tcoords->GetNumberOfComponents() == 2)
  {
    copy->GetPointData()->SetTCoords(asFloat(tcoords));
  }
  vtkNew<vtkPLYWriter> writer;
  writer->SetInputData(copy);
  writer->SetFileTypeToBinary();
  writer->SetArrayName(colorsName);
  writer->SetEnableAlpha(true); // RGBA arrays keep their alpha, RGB ones stay RGB
  // vtkPLY appends ".ply" to a file name that does not end so (".PLY" included):
  // such a file is written under a name that does, then renamed.
  const bool plyName = path.size() >= 4 && path.compare(path.size() - 4, 4, ".ply") == 0;
  const std::string written = plyName ? path : path + ".shockio.ply";
  writer->SetFileName(written.c_str());
  bool ok = RunWriter(writer.GetPointer(), path, trap, error);
  std::error_code code;
  if (!plyName && ok)
  {
    std::filesystem::rename(written, path, code);
    ok = !code;
    error = ok
      ? error
      : path + ": cannot rename the file written as " + written + " (" + code.message() + ")";
  }
  if (!plyName && !ok)
  {
    std::filesystem::remove(written, code);
  }
  return ok;
}

/// Writes a binary STL file of the triangulated polygons and strips of `mesh`.
bool WriteStl(vtkPolyData* mesh, const std::string& path, MessageTrap* trap, std::string& error)
{
  if (mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
  {
    error = path + ": STL files hold triangles, and the mesh has no polygons";
    return false;
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mesh);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  trap->Watch(triangles);
  vtkNew<vtkSTLWriter> writer;
  writer->SetInputConnection(triangles->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->SetFileTypeToBinary();
  return RunWriter(writer.GetPointer(), path, trap, error);
}

/// Reads the file in `format`; null with `error` set when a check of this module fails.
vtkSmartPointer<vtkPolyData> ReadFormat(
  Format format, const std::string& path, MessageTrap* trap, std::string& error)
{
  switch (format)
  {
    case Format::PLY:
      return CheckPly(path, error) ? ReadPly(path, trap) : nullptr;
    case Format::OBJ:
      return CheckObj(path, error) ? ReadWith<vtkOBJReader>(path, trap) : nullptr;
    case Format::STL:
      return CheckStl(path, error) ? ReadWith<vtkSTLReader>(path, trap) : nullptr;
    case Format::VTP:
      return ReadWith<vtkXMLPolyDataReader>(path, trap);
    case Format::VTK:
      return ReadLegacy(path, trap, error);
    case Format::OFF:
      return ReadOff(path, error);
  }
  return nullptr;
}

/// Writes the file in `format`; false with `error` set when this module finds a problem.
bool WriteFormat(
  Format format, vtkPolyData* mesh, const std::string& path, MessageTrap* trap, std::string& error)
{
  switch (format)
  {
    case Format::PLY:
      return WritePly(mesh, path, trap, error);
    case Format::OBJ:
    {
      vtkNew<vtkOBJWriter> writer;
      writer->SetInputData(0, mesh);
      writer->SetFileName(path.c_str());
      return RunWriter(writer.GetPointer(), path, trap, error);
    }
    case Format::STL:
      return WriteStl(mesh, path, trap, error);
    case Format::VTP:
    {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetInputData(mesh);
      writer->SetFileName(path.c_str());
      return RunWriter(writer.GetPointer(), path, trap, error);
    }
    case Format::VTK:
    {
      vtkNew<vtkPolyDataWriter> writer;
      writer->SetInputData(mesh);
      writer->SetFileName(path.c_str());
      writer->SetFileTypeToBinary();
      return RunWriter(writer.GetPointer(), path, trap, error);
    }
    case Format::OFF:
      return WriteOff(mesh, path, error);
  }
  return false;
}

} // namespace

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error)
{
  error.clear();
  const std::optional<Format> format = FormatOf(path, error);
  if (!format || !CheckReadable(path, error))
  {
    return nullptr;
  }
  vtkNew<MessageTrap> trap;
  vtkSmartPointer<vtkPolyData> mesh;
  try
  {
    mesh = ReadFormat(*format, path, trap, error);
  }
  catch (const std::bad_alloc&)
  {
    // VTK's readers allocate what corrupt counts in binary files announce.
    error = path + ": out of memory (is the file corrupt?)";
  }
  // What VTK reported explains a failure best, even one found here after it.
  if (!trap->Finish(path, error) || !mesh)
  {
    return nullptr;
  }
  if (mesh->GetNumberOfPoints() == 0)
  {
    error = path + ": no points could be read (is the file valid for its extension?)";
    return nullptr;
  }
  return CheckStructure(mesh, path, error) ? mesh : nullptr;
}

bool WriteMesh(vtkPolyData* mesh, const std::string& path, std::string& error)
{
  error.clear();
  const std::optional<Format> format = FormatOf(path, error);
  if (!format)
  {
    return false;
  }
  if (!mesh || mesh->GetNumberOfPoints() == 0)
  {
    error = path + ": the mesh has no points to write";
    return false;
  }
  vtkNew<MessageTrap> trap;
  const bool written = WriteFormat(*format, mesh, path, trap, error);
  return trap->Finish(path, error) && written;
}

} // namespace shockio
