#include "ShockTextWords.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

namespace shockio
{

std::vector<std::string_view> Words(std::string_view line, std::string_view separators)
{
  std::vector<std::string_view> words;
  const auto isSpace = [separators](char c) { return separators.find(c) != std::string_view::npos; };
  auto at = line.begin();
  while ((at = std::find_if_not(at, line.end(), isSpace)) != line.end())
  {
    const auto stop = std::find_if(at, line.end(), isSpace);
    words.emplace_back(&*at, static_cast<size_t>(stop - at));
    at = stop;
  }
  return words;
}

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

bool ParseInteger(std::string_view word, std::int64_t& value)
{
  const char* end = word.data() + word.size();
  const auto [stop, code] = std::from_chars(word.data(), end, value);
  return !word.empty() && code == std::errc() && stop == end;
}

bool ParseCount(std::string_view word, std::int64_t& value)
{
  return ParseInteger(word, value) && value >= 0;
}

} // namespace shockio
