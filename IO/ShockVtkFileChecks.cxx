#include "ShockMeshChecks.h"

#include "ShockIOFiles.h"
#include "ShockTextWords.h"

#include <algorithm>
#include <cctype>
#include <iterator>
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
  // A keyword, the word after it that counts elements (points, cells, tuples:
  // limited), their least bytes in the file, and the word that counts values.
  struct Count
  {
    std::string_view keyword, what;
    size_t elements, bytes, values;
  };
  static const Count counts[] = { { "POINTS", "points", 1, 3, 0 }, { "VERTICES", "cells", 1, 1, 2 },
    { "LINES", "cells", 1, 1, 2 }, { "POLYGONS", "cells", 1, 1, 2 }, { "TRIANGLE_STRIPS", "cells", 1, 1, 2 },
    { "CELLS", "cells", 1, 1, 2 }, { "CELL_TYPES", "cell types", 1, 1, 0 },
    { "POINT_DATA", "point data tuples", 1, 1, 0 }, { "CELL_DATA", "cell data tuples", 1, 1, 0 } };
  for (size_t at = 0; at < text.size();)
  {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::vector<std::string_view> words =
      Words(std::string_view(text).substr(at, std::min<size_t>(end - at, 200)));
    at = end + 1;
    for (const Count& count : counts)
    {
      std::int64_t elements = 0, values = 0;
      if (words.empty() || words[0] != count.keyword || words.size() <= count.elements ||
        !ParseCount(words[count.elements], elements))
      {
        continue;
      }
      const auto n = static_cast<std::uint64_t>(elements);
      if (!CountFits(path, count.what, n, text.size() / count.bytes, maxElements, error) ||
        (count.values > 0 && count.values < words.size() && ParseCount(words[count.values], values) &&
          !CountFits(path, "values after " + std::string(count.keyword), static_cast<std::uint64_t>(values),
            text.size(), ~std::uint64_t{ 0 }, error)))
      {
        return false;
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
  // NumberOfPoints="n" and the like, scanned by hand: no regular expression
  // (whose recursion a long run of blanks could overflow).
  static const std::string_view kinds[] = { "Points", "Verts", "Lines", "Strips", "Polys", "Cells" };
  for (size_t at = header.find("NumberOf"); at != std::string::npos; at = header.find("NumberOf", at + 1))
  {
    size_t end = at + 8;
    while (end < header.size() && std::isalpha(static_cast<unsigned char>(header[end])))
    {
      ++end;
    }
    const std::string_view kind = std::string_view(header).substr(at + 8, end - at - 8);
    if (std::find(std::begin(kinds), std::end(kinds), kind) == std::end(kinds))
    {
      continue;
    }
    const auto skipBlanks = [&header](size_t i) {
      while (i < header.size() && std::isspace(static_cast<unsigned char>(header[i])))
      {
        ++i;
      }
      return i;
    };
    end = skipBlanks(end);
    if (end >= header.size() || header[end] != '=' || (end = skipBlanks(end + 1)) >= header.size() ||
      header[end] != '"')
    {
      continue;
    }
    end = skipBlanks(end + 1);
    const size_t digits = header.find_first_not_of("-0123456789", end);
    const std::string_view number = std::string_view(header).substr(end, digits - end);
    if (number.empty())
    {
      continue;
    }
    if (number[0] == '-')
    {
      error = path + ": a negative count NumberOf" + std::string(kind) + "=\"" + std::string(number) + "\"";
      return false;
    }
    std::int64_t value = 0;
    const std::uint64_t declared = ParseCount(number, value) ? static_cast<std::uint64_t>(value) : ~0ull;
    if (!CountFits(path, kind, declared, compressed ? ~0ull : text.size(), maxElements, error))
    {
      return false;
    }
  }
  return true;
}

} // namespace shockio
