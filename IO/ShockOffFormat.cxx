#include "ShockOffFormat.h"

#include "ShockIOFiles.h"
#include "ShockIOMessages.h"
#include "ShockMeshFaces.h"
#include "ShockTextWords.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

namespace shockio
{
namespace
{

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

/**
 * Reads an OFF text step by step (header, vertices, faces); each step returns
 * false with `Error` set to "<path>: [line <n>: ]<what>".
 */
class OffParser
{
public:
  OffParser(std::string_view text, const std::string& path)
    : Lines(text)
    , Path(path)
    , TextSize(text.size())
  {
  }

  bool ReadHeader();
  bool ReadVertices();
  bool ReadFaces();
  bool ReadEnd();
  vtkSmartPointer<vtkPolyData> MakeMesh();

  std::string Error;

private:
  bool Fail(const std::string& what, size_t line = 0)
  {
    this->Error = this->Path + ": " +
      (line > 0 ? "line " + std::to_string(line) + ": " : std::string()) + what;
    return false;
  }
  /// A count from the file, not trusted for allocations: a line takes at least two bytes.
  size_t Capacity(std::int64_t count) const
  {
    return static_cast<size_t>(std::min<std::int64_t>(count, static_cast<std::int64_t>(this->TextSize / 2)));
  }
  bool ReadFace(const OffLine& line, std::int64_t f, std::vector<vtkIdType>& ids);

  OffLines Lines;
  const std::string& Path;
  size_t TextSize;
  bool Colored = false;
  std::int64_t NumberOfVertices = 0;
  std::int64_t NumberOfFaces = 0;
  std::vector<double> Coordinates;
  OffColors VertexColors, FaceColors;
  bool RealColors = false;
  vtkNew<vtkCellArray> Polys;
};

/// The header: OFF or COFF, the counts after it or on the next line.
bool OffParser::ReadHeader()
{
  std::optional<OffLine> header = this->Lines.Next();
  if (!header)
  {
    return this->Fail("no OFF header (the file holds only blanks and comments)");
  }
  const std::string_view keyword = header->words[0];
  this->Colored = keyword == "COFF";
  if (!this->Colored && keyword != "OFF")
  {
    const bool variant = keyword.size() > 3 && keyword.substr(keyword.size() - 3) == "OFF";
    return this->Fail(variant
        ? "unsupported OFF variant " + Quoted(keyword) + " (only OFF and COFF are read)"
        : "not an OFF file: it starts with " + Quoted(keyword) + ", not OFF or COFF",
      header->number);
  }
  OffLine counts{ header->number, { header->words.begin() + 1, header->words.end() } };
  if (counts.words.empty())
  {
    std::optional<OffLine> next = this->Lines.Next();
    if (!next)
    {
      return this->Fail("the file ends before the counts of vertices and faces");
    }
    counts = *next;
  }
  if (counts.words.front() == "BINARY")
  {
    return this->Fail("binary OFF files are not supported", counts.number);
  }
  std::int64_t numberOfEdges = 0;
  if (counts.words.size() < 2 || counts.words.size() > 3 ||
    !ParseCount(counts.words[0], this->NumberOfVertices) ||
    !ParseCount(counts.words[1], this->NumberOfFaces) ||
    (counts.words.size() == 3 && !ParseCount(counts.words[2], numberOfEdges)))
  {
    return this->Fail(
      "expected the counts 'vertices faces edges' as non-negative integers", counts.number);
  }
  return true;
}

/// Vertices, one per line: x y z, and for COFF a colour.
bool OffParser::ReadVertices()
{
  this->Coordinates.reserve(3 * this->Capacity(this->NumberOfVertices));
  const size_t vertexWords = 3;
  for (std::int64_t v = 0; v < this->NumberOfVertices; ++v)
  {
    const std::optional<OffLine> line = this->Lines.Next();
    if (!line)
    {
      return this->Fail("the file ends after " + std::to_string(v) + " of its " +
        std::to_string(this->NumberOfVertices) + " vertices");
    }
    const std::string vertex = "vertex " + std::to_string(v) + ": ";
    if (line->words.size() < vertexWords || (!this->Colored && line->words.size() > vertexWords))
    {
      return this->Fail(vertex + std::to_string(line->words.size()) + " values, expected " +
          (this->Colored ? "x y z and an RGB or RGBA colour" : "the 3 coordinates x y z"),
        line->number);
    }
    for (size_t c = 0; c < vertexWords; ++c)
    {
      double value = 0.0;
      if (!ParseNumber(line->words[c], value))
      {
        return this->Fail(
          vertex + "coordinate " + Quoted(line->words[c]) + " is not a finite number", line->number);
      }
      this->Coordinates.push_back(value);
    }
    if (this->Colored)
    {
      if (line->words.size() == vertexWords)
      {
        return this->Fail(vertex + "no colour, but the file is COFF", line->number);
      }
      const std::string problem = ReadOffColor(
        line->words, vertexWords, line->number, this->VertexColors, this->RealColors, v == 0);
      if (!problem.empty())
      {
        return this->Fail(vertex + problem, line->number);
      }
    }
  }
  return true;
}

/// One face line: its size, the vertex ids, optionally a colour.
bool OffParser::ReadFace(const OffLine& line, std::int64_t f, std::vector<vtkIdType>& ids)
{
  const std::string face = "face " + std::to_string(f) + ": ";
  std::int64_t size = 0;
  if (!ParseCount(line.words[0], size))
  {
    return this->Fail(
      face + "the vertex count " + Quoted(line.words[0]) + " is not a non-negative integer",
      line.number);
  }
  if (size < 3)
  {
    return this->Fail(face + std::to_string(size) + " vertices; a face has at least 3", line.number);
  }
  if (static_cast<std::int64_t>(line.words.size()) - 1 < size)
  {
    return this->Fail(face + "announces " + std::to_string(size) + " vertex ids but lists " +
        std::to_string(line.words.size() - 1),
      line.number);
  }
  ids.clear();
  for (std::int64_t k = 1; k <= size; ++k)
  {
    std::int64_t id = 0;
    if (!ParseCount(line.words[static_cast<size_t>(k)], id) || id >= this->NumberOfVertices)
    {
      return this->Fail(face + "vertex id " + Quoted(line.words[static_cast<size_t>(k)]) +
          " is not an integer in 0.." + std::to_string(this->NumberOfVertices - 1),
        line.number);
    }
    ids.push_back(static_cast<vtkIdType>(id));
  }
  const std::string problem = ReadOffColor(line.words, static_cast<size_t>(size) + 1, line.number,
    this->FaceColors, this->RealColors, f == 0);
  return problem.empty() ? true : this->Fail(face + problem, line.number);
}

bool OffParser::ReadFaces()
{
  this->Polys->AllocateEstimate(static_cast<vtkIdType>(this->Capacity(this->NumberOfFaces)), 3);
  std::vector<vtkIdType> ids;
  for (std::int64_t f = 0; f < this->NumberOfFaces; ++f)
  {
    const std::optional<OffLine> line = this->Lines.Next();
    if (!line)
    {
      return this->Fail("the file ends after " + std::to_string(f) + " of its " +
        std::to_string(this->NumberOfFaces) + " faces");
    }
    if (!this->ReadFace(*line, f, ids))
    {
      return false;
    }
    this->Polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  return true;
}

bool OffParser::ReadEnd()
{
  if (const std::optional<OffLine> extra = this->Lines.Next())
  {
    return this->Fail("more data after the last of the " + std::to_string(this->NumberOfFaces) +
        " faces (do the counts match the file?)",
      extra->number);
  }
  return true;
}

vtkSmartPointer<vtkPolyData> OffParser::MakeMesh()
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(this->NumberOfVertices));
  std::copy(this->Coordinates.begin(), this->Coordinates.end(),
    static_cast<double*>(points->GetVoidPointer(0)));
  mesh->SetPoints(points);
  mesh->SetPolys(this->Polys);
  const std::pair<OffColors*, const char*> kinds[] = { { &this->VertexColors, PointColorsName },
    { &this->FaceColors, FaceColorsName } };
  for (const auto& [colors, name] : kinds)
  {
    if (colors->components == 0)
    {
      continue;
    }
    auto array = OffColorArray(*colors, this->RealColors, name, this->Path, this->Error);
    if (!array)
    {
      return nullptr;
    }
    vtkDataSetAttributes* data = colors == &this->VertexColors
      ? static_cast<vtkDataSetAttributes*>(mesh->GetPointData())
      : mesh->GetCellData();
    data->SetScalars(array);
  }
  return mesh;
}

} // namespace

vtkSmartPointer<vtkPolyData> ReadOff(const std::string& path, std::string& error)
{
  std::string text;
  if (!ReadFile(path, text, error))
  {
    return nullptr;
  }
  OffParser parser(text, path);
  vtkSmartPointer<vtkPolyData> mesh;
  if (parser.ReadHeader() && parser.ReadVertices() && parser.ReadFaces() && parser.ReadEnd())
  {
    mesh = parser.MakeMesh();
  }
  error = parser.Error;
  return mesh;
}

namespace
{

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

} // namespace

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

} // namespace shockio
