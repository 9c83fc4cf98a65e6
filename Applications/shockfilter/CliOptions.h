/**
 * @file   CliOptions.h
 * @brief  The option parser every subcommand of shockfilter shares.
 *
 * A subcommand lists its options as OptionSpecs, each storing its value
 * through a function that throws CliError on a bad value; ParseCommandLine()
 * applies them and returns the positional arguments.
 */
#ifndef CliOptions_h
#define CliOptions_h

#include "CliSupport.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace shockcli
{

/// One option: "--name VALUE" / "--name=VALUE", or a flag "--name" when valueName is empty.
struct OptionSpec
{
  std::string name;      ///< with the dashes, e.g. "--time"
  std::string valueName; ///< e.g. "T"; empty for a flag
  std::string help;      ///< one line for the usage text
  std::function<void(const std::string& value)> apply; ///< stores the value; throws CliError if bad
};

/// A named choice of an enumerated option, e.g. {"fixed", FIXED}.
using Choice = std::pair<const char*, int>;

/// True when "-h" or "--help" appears before any "--".
bool IsHelpRequest(const std::vector<std::string>& args);

/**
 * Applies the options found in 'args' (anywhere; "--" ends them), then checks
 * that the positional arguments are exactly 'names' (e.g. {"INPUT", "OUTPUT"})
 * and returns them. Throws CliError on an unknown option, a missing value, a
 * value the option rejects or a wrong number of arguments.
 */
std::vector<std::string> ParseCommandLine(const std::string& command, const std::vector<std::string>& args,
  const std::vector<OptionSpec>& options, const std::vector<std::string>& names);

/// Parses a whole string as a number of type T (locale-independent); finite for floating point.
template <typename T>
T ParseNumber(const std::string& option, const std::string& text)
{
  T value{};
  const char* first = text.data();
  const char* last = first + text.size();
  const auto [end, error] = std::from_chars(first, last, value);
  const char* expected = std::is_integral<T>::value ? "an integer" : "a number";
  if (text.empty() || error == std::errc::invalid_argument || end != last)
  {
    throw CliError(option + ": '" + text + "' is not " + expected);
  }
  if (error == std::errc::result_out_of_range)
  {
    throw CliError(option + ": " + text + " is out of range");
  }
  if constexpr (std::is_floating_point<T>::value)
  {
    if (!std::isfinite(value))
    {
      throw CliError(option + ": '" + text + "' is not a finite number");
    }
  }
  return value;
}

/// Parses a number and checks low <= value <= high (high = max() means no upper bound).
template <typename T>
T ParseInRange(const std::string& option, const std::string& text, T low, T high)
{
  const T value = ParseNumber<T>(option, text);
  if (value < low || value > high)
  {
    const std::string range = high == std::numeric_limits<T>::max()
      ? "must be >= " + NumberText(low)
      : "must be in [" + NumberText(low) + ", " + NumberText(high) + "]";
    throw CliError(option + ": " + text + " is out of range (" + range + ")");
  }
  return value;
}

/// " (did you mean 'NAME'?)" for the name of `known` closest to `typed`, or "" when none is close.
std::string Suggestion(const std::string& typed, const std::vector<std::string>& known);

/// Returns the value of the choice named 'text' (ParaView's names, any case, spaces or
/// hyphens); throws on an unknown name, with the closest name.
int ParseChoice(const std::string& option, const std::string& text, const std::vector<Choice>& choices);

/// The name of 'value' among 'choices' (for reports).
const char* ChoiceName(int value, const std::vector<Choice>& choices);

/// Formats option help lines, aligned: "  --time T          help".
std::string FormatOptions(const std::vector<OptionSpec>& options);

/// " (default <value>)", for option help lines.
std::string DefaultText(const std::string& value);

/// "low..high", for option help lines (the ranges are the filters' clamps).
std::string RangeText(double low, double high);

/// The text of a default value in help lines: integers in full, other numbers by NumberText().
template <typename T>
std::string ValueText(T value)
{
  if constexpr (std::is_integral<T>::value)
  {
    return std::to_string(value);
  }
  else
  {
    return NumberText(value);
  }
}

/**
 * "--name VALUE": a number in [low, high] (a filter's clamp: out of range is
 * refused, where the filter's setter would clamp silently) stored in `target`;
 * help "<text>, low..high<note> (default <defaultValue>)".
 */
template <typename T>
OptionSpec RangeOptionSpec(const std::string& name, const std::string& valueName, const std::string& text,
  std::optional<T>& target, T low, T high, T defaultValue, const std::string& note = "")
{
  return { name, valueName, text + ", " + RangeText(low, high) + note + DefaultText(ValueText(defaultValue)),
    [name, &target, low, high](const std::string& v) { target = ParseInRange(name, v, low, high); } };
}

/// "--name VALUE": one of `choices` (by name) stored in `target`; help "<text> (default <name>)".
OptionSpec ChoiceOptionSpec(const std::string& name, const std::string& valueName, const std::string& text,
  std::optional<int>& target, const std::vector<Choice>& choices, int defaultValue);

/// Calls (object->*set)(*value) when the option was given: an unset option keeps the default.
template <typename Object, typename Class, typename Argument, typename T>
void SetIfGiven(Object* object, void (Class::*set)(Argument), const std::optional<T>& value)
{
  if (value)
  {
    (object->*set)(*value);
  }
}

/// --array NAME (not empty).
OptionSpec ArrayOptionSpec(std::string& target, const std::string& help);

/// --timings (a flag).
OptionSpec TimingsOptionSpec(bool& target);

/// Help lines "  --timings prints {"key",...} on stdout;" (wrapped at 78 columns), then 'notes'.
std::string TimingsHelp(const std::vector<std::string>& keys, const std::string& notes);

} // namespace shockcli

#endif
