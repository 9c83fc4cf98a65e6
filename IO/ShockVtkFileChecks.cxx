#include "ShockMeshChecks.h"

#include "ShockIOFiles.h"
#include "ShockTextWords.h"

#include <algorithm>
#include <regex>
#include <string_view>
#include <vector>

namespace shockio
{
namespace
{

/// Whether a count a header declares is within `maxElements` and what `bytes` of data can hold.
bool CountFits(const std::string& path, std::string_view what, std::uint64_t count, std::uint64_t bytes,
  std::uint64_t maxElements, std::string& error)
{
  if (count > maxElements)
  {
    error = path + ": declares " + std::to_string(count) + " " + std::string(what) +
      ", more than the limit of " + std::to_string(maxElements) + " samples";
    return false;
  }
  if (count > bytes)
  {
    error = path + ": declares " + std::to_string(count) + " " + std::string(what) + " in a file of " +
      std::to_string(bytes) + " bytes (truncated or damaged)";
    return false;
  }
  return true;
}

} // namespace

bool CheckLegacyCounts(const std::string& path, std::uint64_t maxElements, std::string& error)
{
  std::string text;
  if (!ReadFile(path, text, error))
  {
    return false;
  }
  // Keyword, the words after it that count values.
  static const std::pair<std::string_view, std::vector<size_t>> keywords[] = { { "POINTS", { 1 } },
    { "VERTICES", { 1, 2 } }, { "LINES", { 1, 2 } }, { "POLYGONS", { 1, 2 } },
    { "TRIANGLE_STRIPS", { 1, 2 } }, { "CELLS", { 1, 2 } }, { "CELL_TYPES", { 1 } },
    { "POINT_DATA", { 1 } }, { "CELL_DATA", { 1 } } };
  for (size_t at = 0; at < text.size();)
  {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::vector<std::string_view> words = Words(std::string_view(text).substr(at, std::min<size_t>(end - at, 200)));
    at = end + 1;
    for (const auto& [keyword, counts] : keywords)
    {
      if (words.empty() || words[0] != keyword)
      {
        continue;
      }
      for (const size_t w : counts)
      {
        std::int64_t count = 0;
        if (w < words.size() && ParseCount(words[w], count) &&
          !CountFits(path, "values after " + std::string(keyword), static_cast<std::uint64_t>(count) *
              (keyword == "POINTS" ? 3 : 1), text.size(), maxElements * (keyword == "POINTS" ? 3 : 1), error))
        {
          return false;
        }
      }
    }
  }
  return true;
}

bool CheckXmlCounts(const std::string& path, std::uint64_t maxElements, std::string& error)
{
  std::string text;
  if (!ReadFile(path, text, error))
  {
    return false;
  }
  const size_t appended = text.find("<AppendedData");
  const std::string header = text.substr(0, std::min(appended, text.size()));
  // Compressed data may be far smaller than what it holds: then only the limit applies.
  const bool compressed = header.find("compressor=") != std::string::npos;
  static const std::regex count(R"(Number(Of(Points|Verts|Lines|Strips|Polys|Cells))\s*=\s*\"\s*(-?\d+))");
  for (auto match = std::sregex_iterator(header.begin(), header.end(), count);
       match != std::sregex_iterator(); ++match)
  {
    const std::string digits = (*match)[3].str();
    if (digits[0] == '-')
    {
      error = path + ": a negative count " + (*match)[0].str() + "\"";
      return false;
    }
    std::int64_t value = 0;
    const std::uint64_t declared = ParseCount(digits, value) ? static_cast<std::uint64_t>(value) : ~0ull;
    if (!CountFits(path, (*match)[2].str(), declared, compressed ? ~0ull : text.size(), maxElements, error))
    {
      return false;
    }
  }
  return true;
}

} // namespace shockio
