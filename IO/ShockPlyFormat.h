/**
 * @file ShockPlyFormat.h
 * @brief What CheckPly (ShockPlyCheck.cxx) knows of the PLY format as
 * vtkPLY reads it: the value types, the header's elements and properties, the
 * words of a line, and the values of the body in order (PlyBody). Private to
 * the module: included by ShockPlyCheck.cxx only.
 */
#ifndef ShockPlyFormat_h
#define ShockPlyFormat_h

#include "ShockIOMessages.h"
#include "ShockTextWords.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shockio
{
namespace ply
{

/// A PLY value type.
struct PlyType
{
  int size = 0; ///< bytes in binary files
  bool integer = false;
  bool isSigned = false;
};

/// The PLY type named `name` (the classic and the sized names).
inline std::optional<PlyType> PlyTypeNamed(std::string_view name)
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
inline bool PlyWords(std::string_view line, std::vector<std::string_view>& words, std::string& problem)
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
    // A last line without its line break: a truncated file when values are
    // missing (said by Next), else only the break VTK's reader needs (said by End).
    this->Unterminated = end == this->Data.size();
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
        problem = this->Unterminated ? "the file ends inside the data (truncated?)"
                                     : "fewer values than the header announces";
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
    if (this->Encoding == PlyEncoding::Ascii && this->Unterminated)
    {
      problem = "the last line has no line break, which VTK's PLY reader needs";
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
  bool Unterminated = false; ///< the current line is the last, without its line break
};

} // namespace ply
} // namespace shockio

#endif
