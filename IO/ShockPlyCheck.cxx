#include "ShockMeshChecks.h"

#include "ShockPlyFormat.h"

#include "ShockIOFiles.h"
#include "ShockIOMessages.h"
#include "ShockTextWords.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace shockio
{
namespace
{
using namespace ply;

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

bool CheckPlyLayout(const std::vector<PlyElement>& elements, std::string& problem);

/**
 * Reads one line of a PLY header (its `words`, after the first line) into
 * `header` and `encoding`; false with `problem` set for a line vtkPLY would
 * misread or crash on: an unknown keyword, a second format line, a second
 * element or property of one name.
 */
bool ReadPlyHeaderLine(const std::vector<std::string_view>& words, const std::string& at,
  PlyHeader& header, std::optional<PlyEncoding>& encoding, std::string& problem)
{
  const std::string_view keyword = words[0];
  if (keyword == "format" && encoding)
  {
    problem = at + "a second format line";
    return false;
  }
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
    if (FindPlyElement(header.elements, words[1]) >= 0)
    {
      problem = at + "a second element " + Quoted(words[1]);
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
    if (FindPlyProperty(header.elements.back(), words.back()))
    {
      problem = at + "a second property " + Quoted(words.back());
      return false;
    }
    header.elements.back().properties.push_back({ words.back(), *type, countType });
  }
  else if (keyword != "comment" && keyword != "obj_info" && keyword != "end_header")
  {
    problem = at + "unknown PLY header line " + Quoted(keyword);
    return false;
  }
  return true;
}

/**
 * Reads the header of a PLY file (`text`, which it views) as vtkPLY does, and
 * checks that vtkPLYReader takes it (CheckPlyLayout()). False with a `problem`
 * text otherwise.
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
    if (header.lines > 1 && !ReadPlyHeaderLine(words, at, header, encoding, problem))
    {
      return false;
    }
    ended = words[0] == "end_header";
  }
  if (!ended || !encoding)
  {
    problem =
      !ended ? "the PLY header has no end_header line" : "the PLY header has no format line";
    return false;
  }
  header.encoding = *encoding;

  return CheckPlyLayout(header.elements, problem);
}

/**
 * The first of the properties `names` of `element` that VTK's PLY reader
 * would read as a colour but that is no 8-bit integer (a list is
 * MisdeclaredPlyProperty's concern); with `wholeSet`, none unless the first
 * three names are all there (VTK reads no partial triple). Null when all are bytes.
 */
const PlyProperty* NonByteColour(
  const PlyElement& element, std::initializer_list<const char*> names, bool wholeSet)
{
  std::vector<const PlyProperty*> found;
  for (const char* name : names)
  {
    if (const PlyProperty* property = FindPlyProperty(element, name))
    {
      found.push_back(property);
    }
  }
  if (wholeSet && found.size() < 3)
  {
    return nullptr; // no triple: VTK reads none of them
  }
  for (const PlyProperty* property : found)
  {
    if (!property->countType && !(property->type.integer && property->type.size == 1))
    {
      return property;
    }
  }
  return nullptr;
}

/**
 * VTK's PLY reader stores the colours it reads as 8-bit values whatever their
 * type: 0..1 floats would turn black and 16-bit values wrap (60000 -> 96). It
 * reads a vertex's red, green, blue (and alpha) triple, else its diffuse_red,
 * _green, _blue triple, a face's red, green, blue triple and its intensity;
 * those are checked, nothing it skips. `elements` are laid out as
 * CheckPlyLayout requires (vertices first, `faces` next when there are any).
 * False with a `problem` text when one is no byte.
 */
bool CheckPlyColourTypes(const std::vector<PlyElement>& elements, bool faces, std::string& problem)
{
  const bool vertexRgb = FindPlyProperty(elements[0], "red") && FindPlyProperty(elements[0], "green") &&
    FindPlyProperty(elements[0], "blue");
  const PlyProperty* wrong = vertexRgb ? NonByteColour(elements[0], { "red", "green", "blue", "alpha" }, true)
                                       : NonByteColour(elements[0], { "diffuse_red", "diffuse_green", "diffuse_blue" }, true);
  const PlyElement* wrongElement = &elements[0];
  if (!wrong && faces)
  {
    wrongElement = &elements[1];
    wrong = NonByteColour(elements[1], { "red", "green", "blue" }, true);
    wrong = wrong ? wrong : NonByteColour(elements[1], { "intensity" }, false);
  }
  if (wrong)
  {
    problem = "the PLY colour '" + std::string(wrong->name) + "' of the " + std::string(wrongElement->name) +
      " element is " + (wrong->type.integer ? std::to_string(8 * wrong->type.size) + "-bit" : "a real number") +
      ", but VTK's PLY reader reads colours as 8-bit (0..255) values and would change them; store them as uchar";
    return false;
  }
  return true;
}

/**
 * Whether vtkPLYReader takes the elements of a header: every element with
 * properties, the vertex element first, with x, y and z values, then optionally the face element with a list
 * of integer vertex_indices, and no property declared a list where it reads a
 * value or the other way round. False with a `problem` text otherwise.
 */
bool CheckPlyLayout(const std::vector<PlyElement>& elements, std::string& problem)
{
  // vtkPLY frees an uninitialised pointer when it closes a file with an
  // element of no properties (found by fuzzing).
  for (const PlyElement& element : elements)
  {
    if (element.properties.empty())
    {
      problem = "the PLY element " + Quoted(element.name) + " has no properties";
      return false;
    }
  }
  // vtkPLYReader reads the elements in file order but skips the data of
  // others than 'vertex' and 'face': those must come first.
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
  if (!CheckPlyColourTypes(elements, faceElement == 1, problem))
  {
    return false;
  }
  // An element of triangle strips is skipped by VTK's PLY reader: its triangles would be lost.
  const int strips = FindPlyElement(elements, "tristrips");
  if (strips >= 0 && elements[static_cast<size_t>(strips)].count > 0)
  {
    problem = "the PLY file holds its triangles as 'tristrips', which VTK's PLY reader skips; write them as a "
              "'face' element";
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
        if (faceIds && length < 3.0)
        {
          what = std::to_string(static_cast<std::int64_t>(length)) + " vertices; a face has at least 3";
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

} // namespace

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

} // namespace shockio
