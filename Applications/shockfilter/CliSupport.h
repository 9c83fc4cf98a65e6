/**
 * @file   CliSupport.h
 * @brief  What every part of shockfilter shares: the one-line error, text and
 *         JSON helpers, and VTK's output window made to print one line per message.
 */
#ifndef CliSupport_h
#define CliSupport_h

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace shockcli
{

inline constexpr const char* ProgramName = "shockfilter";
inline constexpr int ExitError = 2;

/// A failure shown to the user as one line "shockfilter: <message>", exit code 2.
class CliError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Throws CliError(error) unless `ok` (for the shockio functions: false with a one-line error).
inline void Require(bool ok, const std::string& error)
{
  if (!ok)
  {
    throw CliError(error);
  }
}

std::string ToLower(std::string text);

/// Collapses every run of white space (newlines included) to one space; trims.
std::string SingleLine(const std::string& text);

/// A number as text, 6 significant digits ("64", "0.001", "1e+06").
std::string NumberText(double value);

/// "0.123 s"
std::string SecondsText(double seconds);

/// 'text' as a JSON string literal, quotes included.
std::string JsonString(const std::string& text);

/// A one-line JSON object, {"key":value,...}, members in the order added (the --timings reports).
class JsonObject
{
public:
  JsonObject& Add(const std::string& key, const std::string& text) { return this->AddRaw(key, JsonString(text)); }
  JsonObject& Add(const std::string& key, const char* text) { return this->Add(key, std::string(text)); }

  /// A number; 9 significant digits for floating point, null when not finite (JSON has no NaN).
  template <typename Number, typename = std::enable_if_t<std::is_arithmetic<Number>::value>>
  JsonObject& Add(const std::string& key, Number value)
  {
    static_assert(!std::is_same<Number, bool>::value && sizeof(Number) > 1, "not a number type");
    if constexpr (std::is_floating_point<Number>::value)
    {
      if (!std::isfinite(value))
      {
        return this->AddRaw(key, "null");
      }
    }
    std::ostringstream text;
    text << std::setprecision(9) << value;
    return this->AddRaw(key, text.str());
  }

  /// A member whose value is already JSON text (e.g. an array).
  JsonObject& AddRaw(const std::string& key, const std::string& json)
  {
    this->Body += (this->Body.empty() ? "" : ",") + JsonString(key) + ":" + json;
    return *this;
  }

  std::string Text() const { return "{" + this->Body + "}"; }

private:
  std::string Body;
};

/**
 * Routes VTK's messages that no MessageTrap catches (the warnings of a
 * successful read or update, handed on) to standard error, one line
 * "shockfilter: warning: <message>" each; mutes vtkLogger's copies.
 */
void InstallPrintingOutputWindow();

} // namespace shockcli

#endif
