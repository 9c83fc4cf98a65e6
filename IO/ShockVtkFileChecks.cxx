#include "ShockMeshChecks.h"

#include "ShockIOFiles.h"
#include "ShockTextWords.h"

#include <algorithm>
#include <fstream>
#include <filesystem>
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

namespace
{
/// The value of attribute `name` in the XML tag `tag` ("" when absent).
std::string Attribute(std::string_view tag, std::string_view name)
{
  for (size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1))
  {
    const bool word = at == 0 || std::isspace(static_cast<unsigned char>(tag[at - 1]));
    size_t eq = at + name.size();
    while (eq < tag.size() && std::isspace(static_cast<unsigned char>(tag[eq])))
    {
      ++eq;
    }
    if (!word || eq >= tag.size() || tag[eq] != '=')
    {
      continue;
    }
    const size_t open = tag.find('"', eq);
    const size_t close = open == std::string_view::npos ? open : tag.find('"', open + 1);
    if (close != std::string_view::npos)
    {
      return std::string(tag.substr(open + 1, close - open - 1));
    }
  }
  return "";
}

/// The integers of a space-separated list ("0 3 0 2 0 0"); empty when one is not an integer.
std::vector<std::int64_t> Numbers(const std::string& text)
{
  std::vector<std::int64_t> numbers;
  size_t at = 0;
  while (at < text.size())
  {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at])))
    {
      ++at;
    }
    const size_t end = std::min(text.find_first_of(" \t\r\n", at), text.size());
    if (end == at)
    {
      break;
    }
    std::int64_t value = 0;
    const bool negative = text[at] == '-';
    if (!ParseCount(std::string_view(text).substr(at + (negative ? 1 : 0), end - at - (negative ? 1 : 0)), value))
    {
      return {};
    }
    numbers.push_back(negative ? -value : value);
    at = end;
  }
  return numbers;
}

/// The unsigned integer of `bytes` bytes (little or big endian) at `at` of `text`.
std::uint64_t Unsigned(const std::string& text, size_t at, int bytes, bool bigEndian)
{
  std::uint64_t value = 0;
  for (int k = 0; k < bytes; ++k)
  {
    const auto byte = static_cast<unsigned char>(text[at + static_cast<size_t>(bigEndian ? k : bytes - 1 - k)]);
    value = (value << 8) | byte;
  }
  return value;
}

/**
 * False, with `problem`, for an image whose only piece covers part of its
 * whole extent (VTK would fill the rest with zeros); `header` is the XML part.
 */
bool OnlyPieceCoversWholeExtent(std::string_view header, std::string& problem)
{
  const std::string whole = Attribute(header.substr(0, header.find("<Piece")), "WholeExtent");
  const size_t piece = header.find("<Piece");
  if (!whole.empty() && piece != std::string_view::npos && header.find("<Piece", piece + 1) == std::string_view::npos)
  {
    const std::string extent = Attribute(header.substr(piece, header.find('>', piece) - piece), "Extent");
    std::vector<std::int64_t> a = Numbers(whole), b = Numbers(extent);
    if (a.size() == 6 && b.size() == 6 && a != b)
    {
      problem = "its only piece covers the extent " + extent + " of the whole extent " + whole +
        " (the rest would read as zeros)";
      return false;
    }
  }
  return true;
}

/**
 * Where the appended data that begin at `start` end: where the closing tag
 * begins, looked for in the last 256 bytes of the file of `size` bytes (a
 * truncated file has none: its end).
 */
std::uint64_t AppendedDataEnd(std::ifstream& file, std::uint64_t size, std::uint64_t start)
{
  const std::uint64_t tail = std::min<std::uint64_t>(size, 256);
  std::string last(static_cast<size_t>(tail), '\0');
  file.clear();
  file.seekg(static_cast<std::streamoff>(size - tail));
  file.read(&last[0], static_cast<std::streamsize>(tail));
  const size_t closing = last.rfind("</AppendedData>");
  return closing != std::string::npos && size - tail + closing >= start ? size - tail + closing : size;
}

/// The appended raw data of a VTK XML file, [start, end), as the header words describe them.
struct AppendedData
{
  std::ifstream& file;
  std::uint64_t start;
  std::uint64_t end;
  int headerBytes; ///< 4 or 8 (header_type UInt64)
  bool bigEndian;
  bool compressed;

  /// One header word at `at` (false when it lies beyond the data).
  bool Word(std::uint64_t at, std::uint64_t& value) const
  {
    if (at > end || end - at < static_cast<std::uint64_t>(headerBytes))
    {
      return false;
    }
    std::string bytes(static_cast<size_t>(headerBytes), '\0');
    file.clear();
    file.seekg(static_cast<std::streamoff>(at));
    file.read(&bytes[0], headerBytes);
    value = Unsigned(bytes, 0, headerBytes, bigEndian);
    return static_cast<bool>(file);
  }

  /**
   * Whether the block of an array at `first` (its byte count, or compressed
   * [blocks, block size, last block size, the blocks' compressed sizes...],
   * then its bytes) lies within the data: what it needs after its first word
   * is compared with what is left (subtractions only: a hostile size cannot
   * wrap around).
   */
  bool BlockFits(std::uint64_t first) const
  {
    std::uint64_t value = 0;
    bool fits = this->Word(first, value);
    std::uint64_t left = fits ? end - first - static_cast<std::uint64_t>(headerBytes) : 0;
    if (fits && !compressed)
    {
      return value <= left;
    }
    const std::uint64_t blocks = value;
    fits = fits && blocks <= left / static_cast<std::uint64_t>(headerBytes) &&
      2 + blocks <= left / static_cast<std::uint64_t>(headerBytes);
    if (fits)
    {
      left -= (2 + blocks) * static_cast<std::uint64_t>(headerBytes);
    }
    for (std::uint64_t k = 0; fits && k < blocks; ++k)
    {
      std::uint64_t blockBytes = 0;
      fits = this->Word(first + (3 + k) * static_cast<std::uint64_t>(headerBytes), blockBytes) && blockBytes <= left;
      left -= fits ? blockBytes : 0;
    }
    return fits;
  }
};
}

bool CheckXmlCompleteness(const std::string& path, std::string& problem)
{
  // The XML part (before the appended data) is read, not the data: a large
  // file is not held twice. It is the first few MB of any file with appended
  // data; an inline-data file has no appended blocks to check.
  std::ifstream file(path, std::ios::binary);
  std::error_code code;
  const std::uint64_t size = std::filesystem::file_size(path, code);
  if (!file || code)
  {
    problem = "cannot be read";
    return false;
  }
  std::string text(static_cast<size_t>(std::min<std::uint64_t>(size, 8u << 20)), '\0');
  file.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(file.gcount()));
  const size_t appendedTag = text.find("<AppendedData");
  const std::string_view header = std::string_view(text).substr(0, std::min(appendedTag, text.size()));
  if (!OnlyPieceCoversWholeExtent(header, problem))
  {
    return false;
  }
  if (appendedTag == std::string::npos)
  {
    return true;
  }
  // Appended raw data: every array's block (its byte count, then its bytes) within the file.
  const size_t tagEnd = text.find('>', appendedTag);
  if (tagEnd == std::string::npos ||
    Attribute(std::string_view(text).substr(appendedTag, tagEnd - appendedTag), "encoding") != "raw")
  {
    return true; // base64: VTK's decoder reports what is missing
  }
  const size_t marker = text.find('_', tagEnd);
  if (marker == std::string::npos)
  {
    return true; // the reader reports the missing data
  }
  const std::uint64_t start = marker + 1;
  // The attributes of the <VTKFile> element (a file may start with an <?xml ...?> declaration).
  const size_t vtkFile = header.find("<VTKFile");
  const std::string_view fileTag = vtkFile == std::string_view::npos
    ? std::string_view()
    : header.substr(vtkFile, header.find('>', vtkFile) - vtkFile);
  const AppendedData data{ file, start, AppendedDataEnd(file, size, start),
    Attribute(fileTag, "header_type") == "UInt64" ? 8 : 4, Attribute(fileTag, "byte_order") == "BigEndian",
    !Attribute(fileTag, "compressor").empty() };
  for (size_t at = header.find("<DataArray"); at != std::string_view::npos; at = header.find("<DataArray", at + 1))
  {
    const std::string_view tag = header.substr(at, header.find('>', at) - at);
    if (Attribute(tag, "format") != "appended")
    {
      continue;
    }
    std::int64_t offset = 0;
    if (!ParseCount(Attribute(tag, "offset"), offset))
    {
      continue; // the reader reports a malformed offset
    }
    const std::string name = Attribute(tag, "Name");
    if (!data.BlockFits(start + static_cast<std::uint64_t>(offset)))
    {
      problem = "the appended data of array '" + name + "' ends beyond the end of the file (truncated)";
      return false;
    }
  }
  return true;
}

} // namespace shockio
