#include "ShockMeshChecks.h"

#include "ShockIOFiles.h"
#include "ShockIOMessages.h"
#include "ShockTextWords.h"

#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>
#include <vector>

namespace shockio
{
namespace
{

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

/// Counts of the elements of an OBJ file that its ids refer to.
struct ObjElements
{
  std::int64_t vertices = 0;
  std::int64_t tcoords = 0;
  std::int64_t normals = 0;
};

/**
 * What is wrong with one id ("v", "v/t", "v//n" or "v/t/n") of a face, line or
 * point (`command` f, l or p), given the elements read so far and in all:
 * "vertex id ..." (or texture coordinate, normal) when it refers to none, ""
 * when it is right. Lines and points use the vertex id only.
 */
std::string ObjIdProblem(
  std::string_view command, std::string_view id, const ObjElements& soFar, const ObjElements& all)
{
  const size_t slash = id.find('/');
  const std::string_view vertex = id.substr(0, slash);
  if (!ObjIdInRange(vertex, soFar.vertices, all.vertices))
  {
    return "vertex id " + Quoted(vertex);
  }
  if (command != "f" || slash == std::string_view::npos)
  {
    return "";
  }
  const std::string_view rest = id.substr(slash + 1);
  const size_t second = rest.find('/');
  const std::string_view tcoord = rest.substr(0, second);
  // VTK's sscanf would read "v/" on into the next id: only "v//n" leaves one out.
  if (second != 0 && !ObjIdInRange(tcoord, soFar.tcoords, all.tcoords))
  {
    return "texture coordinate id " + Quoted(tcoord);
  }
  if (second != std::string_view::npos && !ObjIdInRange(rest.substr(second + 1), soFar.normals, all.normals))
  {
    return "normal id " + Quoted(rest.substr(second + 1));
  }
  return "";
}

} // namespace

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
  const ObjElements all{ count("v"), count("vt"), count("vn") };
  ObjElements soFar;
  for (size_t l = 0; l < lines.size(); ++l)
  {
    const std::string at = "line " + std::to_string(l + 1) + ": ";
    const std::vector<std::string_view>& words = lines[l];
    const std::string_view command = words.empty() ? std::string_view() : words[0];
    soFar.vertices += command == "v";
    soFar.tcoords += command == "vt";
    soFar.normals += command == "vn";
    if (command == "v" || command == "vn" || command == "vt")
    {
      // vtkOBJReader reads what is not a number ("nan", "1x") as 0.
      for (size_t w = 1; w < words.size(); ++w)
      {
        double value = 0.0;
        if (!ParseNumber(words[w], value))
        {
          error = path + ": " + at + "coordinate " + Quoted(words[w]) + " is not a finite number";
          return false;
        }
      }
    }
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
      const std::string problem = ObjIdProblem(command, id, soFar, all);
      if (!problem.empty())
      {
        error = path + ": " + at + problem + " refers to nothing";
        return false;
      }
    }
  }
  return true;
}

} // namespace shockio
