/**
 * @file   ShockTextWords.h
 * @brief  Words and numbers of the text mesh formats (OFF, PLY, OBJ), parsed
 *         whole and locale-independently.
 */
#ifndef ShockTextWords_h
#define ShockTextWords_h

#include <cstdint>
#include <string_view>
#include <vector>

namespace shockio
{

/// The words of a line, separated by any of `separators` (by default the C locale's white space).
std::vector<std::string_view> Words(
  std::string_view line, std::string_view separators = " \t\n\v\f\r");

/// Parses a whole word as a finite number (a leading '+' allowed).
bool ParseNumber(std::string_view word, double& value);

/// Parses a whole word as an integer.
bool ParseInteger(std::string_view word, std::int64_t& value);

/// Parses a whole word as a non-negative integer.
bool ParseCount(std::string_view word, std::int64_t& value);

} // namespace shockio

#endif
