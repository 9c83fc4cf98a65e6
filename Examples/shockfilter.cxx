/**
 * @file   shockfilter.cxx
 * @brief  Command-line program for the unconditionally stable shock filters.
 *
 * `shockfilter` sharpens images and volumes with vtkImageShockAdvectionFilter,
 * the shock filter of F. Prada and M. Kazhdan, "Unconditionally Stable Shock
 * Filters for Image and Geometry Processing" (Computer Graphics Forum 34(5),
 * 2015): every sample is traced back along the flow u = 1/2 grad |grad I|^2 for
 * a flow time t and the input is resampled there, so blurred edges become sharp
 * and the result is stable for any t.
 *
 * Subcommands (the table is Commands()):
 *  - `image INPUT OUTPUT [options]` filters an image or volume file and writes
 *    the result (vtkImageShockAdvectionFilter);
 *  - `surface INPUT OUTPUT [options]` filters a point or cell array (e.g. the
 *    vertex colours) of a surface mesh (vtkPolyDataShockAdvectionFilter);
 *  - `sharpen INPUT OUTPUT [options]` sharpens the geometry of a surface mesh
 *    (vtkPolyDataShockSharpenFilter);
 *  - `demo OUTDIR [options]` builds a blurred synthetic picture and volume,
 *    sharpens them and writes inputs, results and side-by-side comparisons.
 * `--timings` prints one JSON object with the run times on stdout.
 * A subcommand is a function of its arguments and a help text (Dispatch()
 * answers --help); its options are an OptionSpec list parsed by
 * ParseCommandLine(), and the parameters shared by every shock filter are
 * ShockOptions (ShockOptionSpecs(), ConfigureFilter()).
 *
 * Errors print exactly one line "shockfilter: <message>" on stderr and exit
 * with code 2. The errors and warnings of VTK objects are caught by a
 * MessageCollector observer (and those nobody observes by a replacement of VTK's
 * output window) instead of being printed; the first error is folded into that
 * line, warnings become "shockfilter: warning: ..." lines.
 */

#include "ShockMeshIO.h"
#include "vtkImageShockAdvectionFilter.h"
#include "vtkPolyDataShockAdvectionFilter.h"
#include "vtkPolyDataShockSharpenFilter.h"

#include "vtkAlgorithm.h"
#include "vtkBMPReader.h"
#include "vtkBMPWriter.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageAppend.h"
#include "vtkImageData.h"
#include "vtkImageFlip.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkJPEGReader.h"
#include "vtkJPEGWriter.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPNMReader.h"
#include "vtkPNMWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStructuredPointsReader.h"
#include "vtkStructuredPointsWriter.h"
#include "vtkTIFFReader.h"
#include "vtkTIFFWriter.h"
#include "vtkType.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace
{
constexpr const char* ProgramName = "shockfilter";
constexpr int ExitError = 2;

/// A failure shown to the user as one line "shockfilter: <message>", exit code 2.
class CliError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

// =============================================================================
// Text helpers
// =============================================================================

std::string ToLower(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

/// Collapses every run of white space (newlines included) to one space; trims.
std::string SingleLine(const std::string& text)
{
  std::string line;
  bool pendingSpace = false;
  for (const unsigned char c : text)
  {
    if (std::isspace(c))
    {
      pendingSpace = true;
      continue;
    }
    if (pendingSpace && !line.empty())
    {
      line += ' ';
    }
    pendingSpace = false;
    line += static_cast<char>(c);
  }
  return line;
}

/// A number as text, 6 significant digits ("64", "0.001", "1e+06").
std::string NumberText(double value)
{
  std::ostringstream text;
  text << std::setprecision(6) << value;
  return text.str();
}

/// "0.123 s"
std::string SecondsText(double seconds)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << seconds << " s";
  return text.str();
}

/// 'text' as a JSON string literal, quotes included.
std::string JsonString(const std::string& text)
{
  std::ostringstream json;
  json << '"';
  for (const unsigned char c : text)
  {
    if (c == '"' || c == '\\')
    {
      json << '\\' << c;
    }
    else if (c < 0x20)
    {
      json << "\\u" << std::hex << std::setw(4) << std::setfill('0') << static_cast<int>(c)
           << std::dec << std::setfill(' ');
    }
    else
    {
      json << c;
    }
  }
  json << '"';
  return json.str();
}

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

/// "512x384x1"
std::string DimensionsText(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  return std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
}

/**
 * Turns a VTK message ("ERROR: In <file>, line <n>\n<class> (0x...): <text>")
 * into "<class>: <text>" on one line; an executive's "... returned failure for
 * request: <information dump>" loses the dump.
 */
std::string CleanVtkMessage(const char* raw)
{
  std::string text = raw ? raw : "";
  for (const char* header : { "ERROR: In ", "Warning: In ", "Generic Warning: In " })
  {
    if (text.rfind(header, 0) == 0)
    {
      const auto endOfLine = text.find('\n');
      text = endOfLine == std::string::npos ? std::string() : text.substr(endOfLine + 1);
    }
  }
  static const std::regex address(R"( ?\(0x[0-9a-fA-F]+\))");
  text = std::regex_replace(text, address, "");
  const auto dump = text.find(" for request:");
  if (dump != std::string::npos)
  {
    text.erase(dump);
  }
  return SingleLine(text);
}

// =============================================================================
// VTK error capture
// =============================================================================

/// A message of VTK's, reduced to one line.
struct VtkMessage
{
  bool error; ///< error, else warning
  std::string text;
};

/**
 * VTK's output window, replaced: keeps the messages that reach it (generic
 * warnings, errors of objects nobody observes) instead of printing them, until a
 * MessageCollector takes them. Installed once by InstallCapturingOutputWindow().
 */
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow);

  void DisplayText(const char* text) override { this->Keep(false, text); }
  void DisplayErrorText(const char* text) override { this->Keep(true, text); }
  void DisplayWarningText(const char* text) override { this->Keep(false, text); }
  void DisplayGenericWarningText(const char* text) override { this->Keep(false, text); }
  void DisplayDebugText(const char*) override {}

  /// The messages kept so far, which are forgotten.
  std::vector<VtkMessage> TakeMessages() { return std::exchange(this->Messages, {}); }

protected:
  CapturingOutputWindow() = default;
  ~CapturingOutputWindow() override = default;

private:
  void Keep(bool error, const char* text) { this->Messages.push_back({ error, CleanVtkMessage(text) }); }

  std::vector<VtkMessage> Messages;
};
vtkStandardNewMacro(CapturingOutputWindow);

/// Routes all of VTK's unobserved messages to a CapturingOutputWindow (VTK's output window is global).
void InstallCapturingOutputWindow()
{
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // the logger would print them too
  vtkNew<CapturingOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
}

/// The messages the capturing output window holds, if it is installed.
std::vector<VtkMessage> TakeUnobservedMessages()
{
  auto* window = CapturingOutputWindow::SafeDownCast(vtkOutputWindow::GetInstance());
  return window ? window->TakeMessages() : std::vector<VtkMessage>();
}

/**
 * Observer of ErrorEvent and WarningEvent: keeps the first error and all
 * warnings instead of letting VTK print them, so that a failure becomes the one
 * line of CliError. Messages no observer caught (the output window's) are
 * added when the collector is checked.
 */
class MessageCollector : public vtkCommand
{
public:
  static MessageCollector* New() { return new MessageCollector; }

  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    const std::string text = CleanVtkMessage(static_cast<const char*>(callData));
    if (event == vtkCommand::ErrorEvent)
    {
      this->AddError(text);
    }
    else if (event == vtkCommand::WarningEvent)
    {
      this->Warnings.push_back(text);
    }
  }

  /// Observes an object's errors and warnings.
  void Watch(vtkObject* object)
  {
    object->AddObserver(vtkCommand::ErrorEvent, this);
    object->AddObserver(vtkCommand::WarningEvent, this);
  }

  /// Observes an algorithm and its executive (which reports failed requests).
  void WatchAlgorithm(vtkAlgorithm* algorithm)
  {
    this->Watch(algorithm);
    this->Watch(algorithm->GetExecutive());
  }

  /// Takes the messages of the output window as if observed.
  void CollectUnobserved()
  {
    for (const VtkMessage& message : TakeUnobservedMessages())
    {
      if (message.error)
      {
        this->AddError(message.text);
      }
      else
      {
        this->Warnings.push_back(message.text);
      }
    }
  }

  /// Makes the first warning an error (for readers: a warning means the data is not as declared).
  void TreatWarningsAsErrors()
  {
    this->CollectUnobserved();
    if (!this->Warnings.empty())
    {
      this->AddError(this->Warnings.front());
      this->Warnings.clear();
    }
  }

  /// Throws "<context>: <first VTK error>" when an error was reported.
  void ThrowIfFailed(const std::string& context)
  {
    this->CollectUnobserved();
    if (this->Failed)
    {
      throw CliError(this->FirstError.empty() ? context : context + ": " + this->FirstError);
    }
  }

  /// Prints the collected warnings on stderr, one line each, and forgets them.
  void PrintWarnings()
  {
    this->CollectUnobserved();
    for (const std::string& warning : this->Warnings)
    {
      std::cerr << ProgramName << ": warning: " << warning << '\n';
    }
    this->Warnings.clear();
  }

private:
  MessageCollector() = default;

  void AddError(const std::string& text)
  {
    if (!this->Failed)
    {
      this->Failed = true;
      this->FirstError = text;
    }
  }

  bool Failed = false;
  std::string FirstError;
  std::vector<std::string> Warnings;
};

/// What to make of the warnings of an update.
enum class Warnings
{
  Print,   ///< one "shockfilter: warning: ..." line each on stderr
  AreErrors ///< the first one fails the update
};

/**
 * Checks the outcome of an update ('ok': what the executive returned): throws
 * "<context>: <VTK error>" if it failed or reported an error, else prints the
 * warnings.
 */
void CheckUpdate(
  bool ok, MessageCollector* messages, const std::string& context, Warnings warnings = Warnings::Print)
{
  if (warnings == Warnings::AreErrors)
  {
    messages->TreatWarningsAsErrors();
  }
  messages->ThrowIfFailed(context);
  if (!ok)
  {
    throw CliError(context);
  }
  messages->PrintWarnings();
}

/// Runs an algorithm's pipeline and checks it with CheckUpdate().
void UpdateOrThrow(vtkAlgorithm* algorithm, MessageCollector* messages, const std::string& context,
  Warnings warnings = Warnings::Print)
{
  const bool ok = algorithm->GetExecutive()->Update() != 0;
  CheckUpdate(ok, messages, context, warnings);
}

// =============================================================================
// Option parsing (shared by every subcommand)
// =============================================================================

/// One option: "--name VALUE" / "--name=VALUE", or a flag "--name" when valueName is empty.
struct OptionSpec
{
  std::string name;      ///< with the dashes, e.g. "--time"
  std::string valueName; ///< e.g. "T"; empty for a flag
  std::string help;      ///< one line for the usage text
  std::function<void(const std::string& value)> apply; ///< stores the value; throws CliError if bad
};

/// True when "-h" or "--help" appears before any "--".
bool IsHelpRequest(const std::vector<std::string>& args)
{
  for (const std::string& arg : args)
  {
    if (arg == "--")
    {
      return false;
    }
    if (arg == "-h" || arg == "--help")
    {
      return true;
    }
  }
  return false;
}

const OptionSpec* FindOption(const std::vector<OptionSpec>& options, const std::string& name)
{
  for (const OptionSpec& option : options)
  {
    if (option.name == name)
    {
      return &option;
    }
  }
  return nullptr;
}

/**
 * Applies the options found in 'args' and returns the positional arguments.
 * Options may come anywhere; "--" ends them. Throws CliError on an unknown
 * option, a missing value or a value the option rejects.
 */
std::vector<std::string> ParseArguments(
  const std::string& command, const std::vector<std::string>& args, const std::vector<OptionSpec>& options)
{
  std::vector<std::string> positionals;
  bool optionsEnded = false;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (optionsEnded || arg.size() < 2 || arg[0] != '-')
    {
      positionals.push_back(arg);
      continue;
    }
    if (arg == "--")
    {
      optionsEnded = true;
      continue;
    }
    const auto equals = arg.find('=');
    const std::string name = arg.substr(0, equals);
    const OptionSpec* option = FindOption(options, name);
    if (!option)
    {
      throw CliError(command + ": unknown option '" + name + "' (see '" + ProgramName + " " +
        command + " --help')");
    }
    if (option->valueName.empty())
    {
      if (equals != std::string::npos)
      {
        throw CliError(command + ": option " + name + " takes no value");
      }
      option->apply("");
      continue;
    }
    std::string value;
    if (equals != std::string::npos)
    {
      value = arg.substr(equals + 1);
    }
    else if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0)
    {
      value = args[++i];
    }
    else
    {
      throw CliError(command + ": option " + name + " needs a value " + option->valueName);
    }
    option->apply(value);
  }
  return positionals;
}

/**
 * ParseArguments(), then checks that the positional arguments are exactly
 * 'names' (e.g. {"INPUT", "OUTPUT"}) and returns them.
 */
std::vector<std::string> ParseCommandLine(const std::string& command, const std::vector<std::string>& args,
  const std::vector<OptionSpec>& options, const std::vector<std::string>& names)
{
  std::vector<std::string> positionals = ParseArguments(command, args, options);
  if (positionals.size() != names.size())
  {
    std::string expected;
    for (std::size_t i = 0; i < names.size(); ++i)
    {
      expected += (i == 0 ? "" : (i + 1 == names.size() ? " and " : ", ")) + names[i];
    }
    throw CliError(command + ": expected " + expected + ", got " + std::to_string(positionals.size()) +
      " argument(s) (see '" + ProgramName + " " + command + " --help')");
  }
  return positionals;
}

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

/// A named choice of an enumerated option, e.g. {"fixed", FIXED}.
using Choice = std::pair<const char*, int>;

/// Returns the value of the choice named 'text' (case-insensitive); throws on an unknown name.
int ParseChoice(const std::string& option, const std::string& text, const std::vector<Choice>& choices)
{
  const std::string wanted = ToLower(text);
  std::string names;
  for (const Choice& choice : choices)
  {
    if (wanted == choice.first)
    {
      return choice.second;
    }
    names += (names.empty() ? "" : "|") + std::string(choice.first);
  }
  throw CliError(option + ": unknown value '" + text + "' (expected " + names + ")");
}

/// The name of 'value' among 'choices' (for reports).
const char* ChoiceName(int value, const std::vector<Choice>& choices)
{
  for (const Choice& choice : choices)
  {
    if (choice.second == value)
    {
      return choice.first;
    }
  }
  return "?";
}

/// Formats option help lines, aligned: "  --time T          help".
std::string FormatOptions(const std::vector<OptionSpec>& options)
{
  std::ostringstream text;
  for (const OptionSpec& option : options)
  {
    const std::string head = option.name + (option.valueName.empty() ? "" : " " + option.valueName);
    text << "  " << std::left << std::setw(20) << head << " " << option.help << '\n';
  }
  return text.str();
}

// =============================================================================
// Shock-filter parameters (shared by every command)
// =============================================================================

const std::vector<Choice>& FlowModeChoices()
{
  static const std::vector<Choice> choices = { { "fixed", vtkShockAdvectionFilter::FIXED },
    { "composed", vtkShockAdvectionFilter::COMPOSED }, { "naive", vtkShockAdvectionFilter::NAIVE } };
  return choices;
}

const std::vector<Choice>& MethodChoices()
{
  static const std::vector<Choice> choices = { { "advection", vtkImageShockAdvectionFilter::ADVECTION },
    { "pde", vtkImageShockAdvectionFilter::PDE } };
  return choices;
}

const std::vector<Choice>& SamplingChoices()
{
  static const std::vector<Choice> choices = { { "linear", vtkShockAdvectionFilter::LINEAR },
    { "nearest", vtkShockAdvectionFilter::NEAREST } };
  return choices;
}

const std::vector<Choice>& TracingChoices()
{
  static const std::vector<Choice> choices = { { "exact", vtkShockAdvectionFilter::FACE_CROSSING },
    { "stepped", vtkShockAdvectionFilter::STEPPED } };
  return choices;
}

/// The filter parameters given on the command line; unset ones keep the filter's defaults.
struct ShockOptions
{
  std::optional<double> time;
  std::optional<int> smoothingPasses;
  std::optional<int> flowMode;
  std::optional<int> flowUpdates;
  std::optional<int> sampling;
  std::optional<int> tracingMode;
  std::optional<double> stepFraction;
  std::optional<int> threads;
};

/// Which of the shared shock options a command accepts.
enum class ShockOptionSet
{
  All,        ///< every parameter
  ThreadsOnly ///< only --threads (the demo fixes the rest)
};

/// " (default <value>)", for option help lines.
std::string DefaultText(const std::string& value)
{
  return " (default " + value + ")";
}

/**
 * The options setting ShockOptions. Ranges are those of vtkShockAdvectionFilter
 * (whose setters would clamp silently); the defaults shown are those of
 * 'defaults', a new filter of the kind the command runs.
 */
std::vector<OptionSpec> ShockOptionSpecs(
  ShockOptions& target, ShockOptionSet set, vtkShockAdvectionFilter* defaults)
{
  std::vector<OptionSpec> specs;
  if (set == ShockOptionSet::All)
  {
    specs.push_back({ "--time", "T",
      "flow time t >= 0, normalised units" + DefaultText(NumberText(defaults->GetFlowTime())),
      [&target](const std::string& v)
      { target.time = ParseInRange("--time", v, 0.0, std::numeric_limits<double>::max()); } });
    specs.push_back({ "--smoothing", "N",
      "smoothing passes, 0..10000" +
        DefaultText(std::to_string(defaults->GetSmoothingPasses())),
      [&target](const std::string& v) { target.smoothingPasses = ParseInRange("--smoothing", v, 0, 10000); } });
    specs.push_back({ "--flow", "MODE",
      "fixed|composed|naive" + DefaultText(ChoiceName(defaults->GetFlowMode(), FlowModeChoices())),
      [&target](const std::string& v) { target.flowMode = ParseChoice("--flow", v, FlowModeChoices()); } });
    specs.push_back({ "--updates", "K",
      "flow updates of composed/naive, 1..100000" +
        DefaultText(std::to_string(defaults->GetNumberOfFlowUpdates())),
      [&target](const std::string& v) { target.flowUpdates = ParseInRange("--updates", v, 1, 100000); } });
    specs.push_back({ "--sampling", "MODE",
      "linear|nearest" + DefaultText(ChoiceName(defaults->GetSampling(), SamplingChoices())),
      [&target](const std::string& v) { target.sampling = ParseChoice("--sampling", v, SamplingChoices()); } });
    specs.push_back({ "--tracing", "MODE",
      "exact (face crossing)|stepped" + DefaultText(ChoiceName(defaults->GetTracingMode(), TracingChoices())),
      [&target](const std::string& v) { target.tracingMode = ParseChoice("--tracing", v, TracingChoices()); } });
    specs.push_back({ "--step-fraction", "F",
      "step of stepped tracing (edges), 0.001..1" +
        DefaultText(NumberText(defaults->GetStepFraction())),
      [&target](const std::string& v)
      { target.stepFraction = ParseInRange("--step-fraction", v, 0.001, 1.0); } });
  }
  specs.push_back({ "--threads", "N", "OpenMP threads, 0..4096, 0 = all cores" +
      DefaultText(std::to_string(defaults->GetNumberOfThreads())),
    [&target](const std::string& v) { target.threads = ParseInRange("--threads", v, 0, 4096); } });
  return specs;
}

/// Sets the given parameters on a filter; the others keep their defaults.
void ConfigureFilter(vtkShockAdvectionFilter* filter, const ShockOptions& options)
{
  if (options.time)
  {
    filter->SetFlowTime(*options.time);
  }
  if (options.smoothingPasses)
  {
    filter->SetSmoothingPasses(*options.smoothingPasses);
  }
  if (options.flowMode)
  {
    filter->SetFlowMode(*options.flowMode);
  }
  if (options.flowUpdates)
  {
    filter->SetNumberOfFlowUpdates(*options.flowUpdates);
  }
  if (options.sampling)
  {
    filter->SetSampling(*options.sampling);
  }
  if (options.tracingMode)
  {
    filter->SetTracingMode(*options.tracingMode);
  }
  if (options.stepFraction)
  {
    filter->SetStepFraction(*options.stepFraction);
  }
  if (options.threads)
  {
    filter->SetNumberOfThreads(*options.threads);
  }
}

// =============================================================================
// Image file formats
// =============================================================================

enum class FileFormat
{
  Png,
  Jpeg,
  Tiff,
  Bmp,
  Pnm,
  Vti,
  LegacyVtk
};

/// What the program knows about a file format.
struct FormatInfo
{
  FileFormat format;
  const char* name;
  std::vector<std::string> extensions; ///< lower case, without the dot
  std::vector<int> storableTypes;      ///< scalar types the writer takes; empty = any
  std::vector<int> components;         ///< component counts the writer takes; empty = any
  bool volumes;                        ///< whether it stores images with several z-slices
};

const std::vector<FormatInfo>& Formats()
{
  static const std::vector<FormatInfo> formats = {
    { FileFormat::Png, "PNG", { "png" }, { VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT }, { 1, 2, 3, 4 },
      false },
    { FileFormat::Jpeg, "JPEG", { "jpg", "jpeg" }, { VTK_UNSIGNED_CHAR }, { 1, 3 }, false },
    { FileFormat::Tiff, "TIFF", { "tif", "tiff" }, { VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT, VTK_FLOAT },
      { 1, 3, 4 }, true },
    { FileFormat::Bmp, "BMP", { "bmp" }, { VTK_UNSIGNED_CHAR }, { 1, 3 }, false },
    { FileFormat::Pnm, "PNM", { "pnm", "ppm", "pgm" }, { VTK_UNSIGNED_CHAR }, { 1, 3 }, false },
    { FileFormat::Vti, "VTK XML image", { "vti" }, {}, {}, true },
    { FileFormat::LegacyVtk, "legacy VTK structured points", { "vtk" }, {}, {}, true },
  };
  return formats;
}

/**
 * The entry of a format table (items with an 'extensions' list, lower case,
 * without the dot) matching the case-insensitive extension of 'path'; throws
 * if there is none, listing the supported extensions.
 */
template <typename Format>
const Format& FormatByExtension(
  const std::vector<Format>& formats, const std::string& path, const std::string& role)
{
  const std::string extension = ToLower(std::filesystem::path(path).extension().string());
  std::string known;
  for (const Format& format : formats)
  {
    for (const std::string& candidate : format.extensions)
    {
      if (extension == "." + candidate)
      {
        return format;
      }
      known += (known.empty() ? "" : ", ") + candidate;
    }
  }
  throw CliError("unsupported " + role + " file extension '" + extension + "' of '" + path +
    "' (supported: " + known + ")");
}

/// The image format chosen by the extension of 'path'; throws if unsupported.
const FormatInfo& FormatOfPath(const std::string& path, const std::string& role)
{
  return FormatByExtension(Formats(), path, role);
}

/// Checks that 'path' is an existing, non-empty, readable regular file.
void RequireReadableFile(const std::string& path)
{
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status))
  {
    throw CliError("input file '" + path + "' does not exist");
  }
  if (!fs::is_regular_file(status))
  {
    throw CliError("input '" + path + "' is not a regular file");
  }
  std::ifstream probe(path, std::ios::binary);
  if (!probe)
  {
    throw CliError("cannot open input file '" + path + "' for reading");
  }
  if (fs::file_size(path, error) == 0)
  {
    throw CliError("input file '" + path + "' is empty");
  }
}

/**
 * Walks the chunks of a PNG file up to IEND and throws if the file ends first.
 * (libpng reports a truncated file by a longjmp that vtkPNGReader does not
 * catch: the program would crash instead of failing with a message.)
 */
void RequirePngChunksComplete(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  file.seekg(0, std::ios::end);
  const std::uint64_t size = static_cast<std::uint64_t>(file.tellg());
  std::uint64_t offset = 8; // the signature, checked by CanReadFile
  while (offset + 8 <= size)
  {
    unsigned char header[8];
    file.seekg(static_cast<std::streamoff>(offset));
    if (!file.read(reinterpret_cast<char*>(header), sizeof(header)))
    {
      break;
    }
    const std::uint64_t length = (std::uint64_t{ header[0] } << 24) | (std::uint64_t{ header[1] } << 16) |
      (std::uint64_t{ header[2] } << 8) | std::uint64_t{ header[3] };
    offset += 8 + length + 4; // header, data, CRC
    if (std::equal(header + 4, header + 8, "IEND"))
    {
      if (offset <= size)
      {
        return;
      }
      break;
    }
  }
  throw CliError("'" + path + "' is a truncated or damaged PNG file");
}

/// A reader of one of the vtkImageReader2 formats, checked with CanReadFile.
template <typename Reader>
vtkSmartPointer<vtkAlgorithm> MakeRasterReader(
  const std::string& path, const FormatInfo& format, MessageCollector* messages)
{
  auto reader = vtkSmartPointer<Reader>::New();
  messages->WatchAlgorithm(reader);
  if (!reader->CanReadFile(path.c_str()))
  {
    throw CliError("'" + path + "' is not a valid " + format.name + " file");
  }
  reader->SetFileName(path.c_str());
  return reader;
}

/// The reader for 'path', after checking that the file has the right format.
vtkSmartPointer<vtkAlgorithm> MakeReader(
  const std::string& path, const FormatInfo& format, MessageCollector* messages)
{
  switch (format.format)
  {
    case FileFormat::Png:
    {
      vtkSmartPointer<vtkAlgorithm> reader = MakeRasterReader<vtkPNGReader>(path, format, messages);
      RequirePngChunksComplete(path);
      return reader;
    }
    case FileFormat::Jpeg:
      return MakeRasterReader<vtkJPEGReader>(path, format, messages);
    case FileFormat::Tiff:
      return MakeRasterReader<vtkTIFFReader>(path, format, messages);
    case FileFormat::Bmp:
      return MakeRasterReader<vtkBMPReader>(path, format, messages);
    case FileFormat::Pnm:
      return MakeRasterReader<vtkPNMReader>(path, format, messages);
    case FileFormat::Vti:
    {
      auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
      messages->WatchAlgorithm(reader);
      reader->SetReaderErrorObserver(messages);
      reader->SetParserErrorObserver(messages);
      if (!reader->CanReadFile(path.c_str()))
      {
        throw CliError("'" + path + "' is not a valid VTK XML image data (.vti) file");
      }
      reader->SetFileName(path.c_str());
      return reader;
    }
    case FileFormat::LegacyVtk:
    {
      auto reader = vtkSmartPointer<vtkStructuredPointsReader>::New();
      messages->WatchAlgorithm(reader);
      reader->SetFileName(path.c_str());
      // Every array, not only the first of each attribute kind.
      reader->ReadAllScalarsOn();
      reader->ReadAllVectorsOn();
      reader->ReadAllNormalsOn();
      reader->ReadAllTensorsOn();
      reader->ReadAllColorScalarsOn();
      reader->ReadAllTCoordsOn();
      reader->ReadAllFieldsOn();
      if (!reader->IsFileStructuredPoints())
      {
        throw CliError(
          "'" + path + "' is not a legacy VTK file of structured points (image data)");
      }
      return reader;
    }
  }
  throw CliError("no reader for '" + path + "'");
}

/**
 * vtkTIFFReader puts the first row of a TIFF with the usual top-left orientation
 * at y = 0, upside down with respect to the other readers and to vtkTIFFWriter;
 * this flips such images along y so that every format reads the same way up.
 */
vtkSmartPointer<vtkImageData> UprightTiff(vtkAlgorithm* reader, vtkImageData* image)
{
  auto* tiffReader = vtkTIFFReader::SafeDownCast(reader);
  const unsigned int topLeft = 1; // ORIENTATION_TOPLEFT
  if (!tiffReader || tiffReader->GetOrientationType() != topLeft)
  {
    return image;
  }
  vtkNew<vtkImageFlip> flip;
  flip->SetInputData(image);
  flip->SetFilteredAxis(1);
  vtkNew<MessageCollector> messages;
  messages->WatchAlgorithm(flip);
  UpdateOrThrow(flip, messages, "cannot flip the TIFF image");
  return flip->GetOutput();
}

/// Reads an image or volume; throws CliError when the file is missing, invalid or empty.
vtkSmartPointer<vtkImageData> ReadImage(const std::string& path)
{
  const FormatInfo& format = FormatOfPath(path, "input");
  RequireReadableFile(path);
  vtkNew<MessageCollector> messages;
  vtkSmartPointer<vtkAlgorithm> reader = MakeReader(path, format, messages);
  UpdateOrThrow(reader, messages, "cannot read '" + path + "'", Warnings::AreErrors);
  vtkImageData* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!image || image->GetNumberOfPoints() == 0)
  {
    throw CliError("no image data in '" + path + "'");
  }
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->ShallowCopy(UprightTiff(reader, image));
  return copy;
}

/**
 * Rounds every value times 'scale' to the nearest integer in [0, 255] (NaN
 * gives 0); 'clamped' counts the values that were out of range.
 */
vtkSmartPointer<vtkUnsignedCharArray> QuantizeToBytes(
  vtkDataArray* values, double scale, vtkIdType* clamped = nullptr)
{
  auto bytes = vtkSmartPointer<vtkUnsignedCharArray>::New();
  bytes->SetName(values->GetName());
  bytes->SetNumberOfComponents(values->GetNumberOfComponents());
  bytes->SetNumberOfTuples(values->GetNumberOfTuples());
  vtkIdType outside = 0;
  const vtkIdType count = values->GetNumberOfValues();
  const int components = values->GetNumberOfComponents();
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double v = std::round(values->GetComponent(i / components, static_cast<int>(i % components)) * scale);
    const double inRange = std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 255.0);
    outside += inRange != v ? 1 : 0;
    bytes->SetValue(i, static_cast<unsigned char>(inRange));
  }
  if (clamped)
  {
    *clamped = outside;
  }
  return bytes;
}

/// A float copy of an array (for TIFF; exact except for integers beyond 2^24).
vtkSmartPointer<vtkFloatArray> ConvertToFloat(vtkDataArray* values)
{
  auto floats = vtkSmartPointer<vtkFloatArray>::New();
  floats->DeepCopy(values);
  floats->SetName(values->GetName());
  return floats;
}

/**
 * Throws unless 'format' can store the point array 'arrayName' of 'image' (its
 * type aside, which PrepareRasterImage converts): number of components, and a
 * single z-slice for the 2D formats.
 */
void RequireStorable(
  vtkImageData* image, const std::string& arrayName, const FormatInfo& format, const std::string& path)
{
  vtkDataArray* array = image->GetPointData()->GetArray(arrayName.c_str());
  if (!array)
  {
    return; // not a numeric point array: the filter reports it
  }
  const std::string where = "cannot write '" + path + "': ";
  int dims[3];
  image->GetDimensions(dims);
  if (!format.volumes && dims[2] > 1)
  {
    throw CliError(where + format.name + " holds one 2D image, the data is " + DimensionsText(image) +
      " (write .vti, .vtk or .tif)");
  }
  const auto& counts = format.components;
  const int components = array->GetNumberOfComponents();
  if (!counts.empty() && std::find(counts.begin(), counts.end(), components) == counts.end())
  {
    std::string allowed;
    for (std::size_t i = 0; i < counts.size(); ++i)
    {
      allowed += (i == 0 ? "" : (i + 1 == counts.size() ? " or " : ", ")) + std::to_string(counts[i]);
    }
    throw CliError(where + format.name + " stores " + allowed + " components per pixel, array '" +
      arrayName + "' has " + std::to_string(components) + " (write .vti or .vtk)");
  }
}

/**
 * The image a raster writer gets: the grid of 'image' with the single point
 * array 'arrayName' as scalars, converted when the format cannot store its type
 * (TIFF: to float; 8-bit formats: rounded and clamped to unsigned char 0..255).
 */
vtkSmartPointer<vtkImageData> PrepareRasterImage(
  vtkImageData* image, const std::string& arrayName, const FormatInfo& format, const std::string& path)
{
  vtkDataArray* array = image->GetPointData()->GetArray(arrayName.c_str());
  if (!array)
  {
    throw CliError("cannot write '" + path + "': no point array '" + arrayName + "'");
  }
  RequireStorable(image, arrayName, format, path);
  vtkSmartPointer<vtkDataArray> stored = array;
  const auto& types = format.storableTypes;
  if (std::find(types.begin(), types.end(), array->GetDataType()) == types.end())
  {
    if (std::find(types.begin(), types.end(), VTK_FLOAT) != types.end())
    {
      stored = ConvertToFloat(array);
    }
    else
    {
      vtkIdType clamped = 0;
      stored = QuantizeToBytes(array, 1.0, &clamped);
      std::cerr << ProgramName << ": note: " << array->GetDataTypeAsString() << " array '"
                << arrayName << "' written to " << format.name
                << " as unsigned char (rounded, clamped to 0..255";
      if (clamped > 0)
      {
        std::cerr << "; " << clamped << " values clamped";
      }
      std::cerr << ")\n";
    }
  }
  auto raster = vtkSmartPointer<vtkImageData>::New();
  raster->CopyStructure(image);
  raster->GetPointData()->SetScalars(stored);
  return raster;
}

/// Sets up a writer of any kind, writes, and throws "cannot write ..." on failure.
template <typename Writer>
void RunWriter(vtkImageData* image, const std::string& path, const std::function<void(Writer*)>& setup = {})
{
  vtkNew<Writer> writer;
  vtkNew<MessageCollector> messages;
  messages->WatchAlgorithm(writer);
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  if (setup)
  {
    setup(writer);
  }
  writer->Write();
  const std::string context = "cannot write '" + path + "'";
  messages->ThrowIfFailed(context);
  if (writer->GetErrorCode() != 0)
  {
    throw CliError(context);
  }
  messages->PrintWarnings();
}

/// Throws unless the directory 'path' would be written into exists.
void RequireOutputDirectory(const std::string& path)
{
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  std::error_code error;
  if (!parent.empty() && !fs::is_directory(parent, error))
  {
    throw CliError("cannot write '" + path + "': directory '" + parent.string() + "' does not exist");
  }
  if (fs::is_directory(path, error))
  {
    throw CliError("cannot write '" + path + "': it is a directory");
  }
}

/// Writes 'image' in the format of the extension of 'path'; 'arrayName' is the array raster formats store.
void WriteImage(vtkImageData* image, const std::string& path, const std::string& arrayName)
{
  const FormatInfo& format = FormatOfPath(path, "output");
  RequireOutputDirectory(path);
  switch (format.format)
  {
    case FileFormat::Vti:
      RunWriter<vtkXMLImageDataWriter>(image, path);
      return;
    case FileFormat::LegacyVtk:
      RunWriter<vtkStructuredPointsWriter>(
        image, path, [](vtkStructuredPointsWriter* w) { w->SetFileTypeToBinary(); });
      return;
    default:
      break;
  }
  vtkSmartPointer<vtkImageData> raster = PrepareRasterImage(image, arrayName, format, path);
  switch (format.format)
  {
    case FileFormat::Png:
      RunWriter<vtkPNGWriter>(raster, path);
      break;
    case FileFormat::Jpeg:
      RunWriter<vtkJPEGWriter>(raster, path, [](vtkJPEGWriter* w) { w->SetQuality(95); });
      break;
    case FileFormat::Tiff:
      RunWriter<vtkTIFFWriter>(raster, path);
      break;
    case FileFormat::Bmp:
      RunWriter<vtkBMPWriter>(raster, path);
      break;
    case FileFormat::Pnm:
      RunWriter<vtkPNMWriter>(raster, path);
      break;
    default:
      break;
  }
}

// =============================================================================
// Running the filters
// =============================================================================

/**
 * Runs the pipeline of a shock filter whose input is set: returns the wall time
 * of the update in seconds, prints its warnings, throws "shock filter failed:
 * <VTK error>" when it fails.
 */
double TimedUpdate(vtkAlgorithm* filter)
{
  vtkNew<MessageCollector> messages;
  messages->WatchAlgorithm(filter);
  const auto start = std::chrono::steady_clock::now();
  const bool ok = filter->GetExecutive()->Update() != 0;
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  CheckUpdate(ok, messages, "shock filter failed");
  return elapsed.count();
}

const std::vector<Choice>& AssociationChoices()
{
  static const std::vector<Choice> choices = { { "point", vtkDataObject::FIELD_ASSOCIATION_POINTS },
    { "cell", vtkDataObject::FIELD_ASSOCIATION_CELLS } };
  return choices;
}

/// The array a command filters.
struct SelectedArray
{
  std::string name;
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS; ///< points or cells
  vtkDataArray* array = nullptr;
};

/// Names of the arrays of 'attributes', for messages ("none" if there are none).
std::string ArrayNames(vtkDataSetAttributes* attributes)
{
  std::string names;
  for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
  {
    const char* name = attributes->GetArrayName(i);
    names += (names.empty() ? "" : ", ") + std::string(name ? name : "(unnamed)");
  }
  return names.empty() ? "none" : names;
}

/**
 * The array to filter: the numeric array named 'requested', looked for in the
 * point data then in the cell data (only in those of 'association' when given);
 * without a name, the active scalars of 'association' (default: the point
 * data), named 'unnamedName' if they have no name. Throws, listing the arrays
 * there are, when there is no such array.
 */
SelectedArray SelectArray(vtkDataSet* data, const std::string& requested, std::optional<int> association,
  const char* unnamedName)
{
  const auto attributesOf = [data](int where) -> vtkDataSetAttributes*
  {
    return where == vtkDataObject::FIELD_ASSOCIATION_CELLS
      ? static_cast<vtkDataSetAttributes*>(data->GetCellData())
      : data->GetPointData();
  };
  const auto kind = [](int where) { return std::string(ChoiceName(where, AssociationChoices())); };
  std::vector<int> searched = { vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataObject::FIELD_ASSOCIATION_CELLS };
  if (association)
  {
    searched = { *association };
  }
  std::string available;
  for (const int where : searched)
  {
    available += (available.empty() ? "" : "; ") + kind(where) + " arrays: " + ArrayNames(attributesOf(where));
  }

  SelectedArray selected;
  if (requested.empty())
  {
    selected.association = association.value_or(vtkDataObject::FIELD_ASSOCIATION_POINTS);
    selected.array = attributesOf(selected.association)->GetScalars();
    if (!selected.array)
    {
      throw CliError("the input has no active " + kind(selected.association) +
        " scalars; choose an array with --array (" + available + ")");
    }
    if (!selected.array->GetName() || !*selected.array->GetName())
    {
      selected.array->SetName(unnamedName);
    }
    selected.name = selected.array->GetName();
    return selected;
  }
  for (const int where : searched)
  {
    vtkAbstractArray* found = attributesOf(where)->GetAbstractArray(requested.c_str());
    if (!found)
    {
      continue;
    }
    selected.array = vtkDataArray::SafeDownCast(found);
    if (!selected.array)
    {
      throw CliError("the " + kind(where) + " array '" + requested + "' is not numeric (" +
        found->GetClassName() + ")");
    }
    selected.name = requested;
    selected.association = where;
    return selected;
  }
  const std::string what = association ? kind(*association) + " array" : "point or cell array";
  throw CliError("the input has no " + what + " '" + requested + "' (" + available + ")");
}

/// The result and measurements of one image filter execution.
struct FilterRun
{
  vtkSmartPointer<vtkImageData> output;
  double time = 0.0;
  int flowMode = 0;
  int threads = 0;
  int components = 0;
  double totalSeconds = 0.0; ///< wall time of Update()
  double flowSeconds = 0.0;
  double advectionSeconds = 0.0;
  vtkTypeUInt64 traceSteps = 0;
  int method = vtkImageShockAdvectionFilter::ADVECTION; ///< image filter only
  vtkTypeInt64 iterations = 0;                           ///< PDE steps (image filter only)
};

/// The image filter's own parameters (the PDE baseline); unset ones keep the defaults.
struct ImageMethodOptions
{
  std::optional<int> method;
  std::optional<double> courantNumber;
  std::optional<int> maximumIterations;
};

/// Filters the point array 'arrayName' of 'input'; throws "shock filter failed: ..." on error.
FilterRun RunImageFilter(vtkImageData* input, const std::string& arrayName,
  const ShockOptions& options, const ImageMethodOptions& methodOptions = ImageMethodOptions())
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  ConfigureFilter(filter, options);
  if (methodOptions.method)
  {
    filter->SetMethod(*methodOptions.method);
  }
  if (methodOptions.courantNumber)
  {
    filter->SetCourantNumber(*methodOptions.courantNumber);
  }
  if (methodOptions.maximumIterations)
  {
    filter->SetMaximumIterations(*methodOptions.maximumIterations);
  }
  filter->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, arrayName.c_str());
  filter->SetInputData(input);

  FilterRun run;
  run.totalSeconds = TimedUpdate(filter);
  run.output = vtkSmartPointer<vtkImageData>::New();
  run.output->ShallowCopy(filter->GetOutput());
  run.time = filter->GetFlowTime();
  run.flowMode = filter->GetFlowMode();
  run.threads = filter->GetNumberOfThreads();
  vtkDataArray* array = input->GetPointData()->GetArray(arrayName.c_str());
  run.components = array ? array->GetNumberOfComponents() : 0;
  run.flowSeconds = filter->GetLastFlowSeconds();
  run.advectionSeconds = filter->GetLastAdvectionSeconds();
  run.traceSteps = filter->GetLastTraceSteps();
  run.method = filter->GetMethod();
  run.iterations = filter->GetLastIterations();
  return run;
}

/// The --timings report of the image command: one JSON object on one line.
std::string TimingsJson(const std::string& command, vtkImageData* image, const FilterRun& run)
{
  int dims[3];
  image->GetDimensions(dims);
  JsonObject json;
  json.Add("command", command)
    .AddRaw("dimensions",
      "[" + std::to_string(dims[0]) + "," + std::to_string(dims[1]) + "," + std::to_string(dims[2]) + "]")
    .Add("samples", image->GetNumberOfPoints())
    .Add("components", run.components)
    .Add("time", run.time)
    .Add("flow_mode", ChoiceName(run.flowMode, FlowModeChoices()))
    .Add("threads", run.threads)
    .Add("flow", run.flowSeconds)
    .Add("advection", run.advectionSeconds)
    .Add("total", run.totalSeconds)
    .Add("trace_steps", run.traceSteps)
    .Add("method", ChoiceName(run.method, MethodChoices()))
    .Add("iterations", run.iterations);
  return json.Text();
}

// =============================================================================
// Options shared by the file commands
// =============================================================================

/// --array NAME (not empty).
OptionSpec ArrayOptionSpec(std::string& target, const std::string& help)
{
  return { "--array", "NAME", help,
    [&target](const std::string& v)
    {
      if (v.empty())
      {
        throw CliError("--array: the name is empty");
      }
      target = v;
    } };
}

/// --timings (a flag).
OptionSpec TimingsOptionSpec(bool& target)
{
  return { "--timings", "", "print the run times as one JSON object on stdout",
    [&target](const std::string&) { target = true; } };
}

/// Help lines "  --timings prints {"key",...} on stdout;" (wrapped at 78 columns), then 'notes'.
std::string TimingsHelp(const std::vector<std::string>& keys, const std::string& notes)
{
  std::string text = "  --timings prints {";
  std::size_t column = text.size();
  for (std::size_t i = 0; i < keys.size(); ++i)
  {
    const std::string item = "\"" + keys[i] + "\"" + (i + 1 < keys.size() ? "," : "} on stdout;");
    if (column + item.size() > 78)
    {
      text += "\n  ";
      column = 2;
    }
    text += item;
    column += item.size();
  }
  return text + "\n" + notes;
}

// =============================================================================
// The "image" command
// =============================================================================

struct ImageSettings
{
  ShockOptions shock;
  ImageMethodOptions method;
  std::string arrayName;
  bool timings = false;
};

std::vector<OptionSpec> ImageOptionSpecs(ImageSettings& settings)
{
  vtkNew<vtkImageShockAdvectionFilter> defaults;
  std::vector<OptionSpec> specs;
  ImageMethodOptions& method = settings.method;
  specs.push_back({ "--method", "METHOD",
    "advection|pde (the Osher-Rudin PDE baseline, linear in t)" +
      DefaultText(ChoiceName(defaults->GetMethod(), MethodChoices())),
    [&method](const std::string& v) { method.method = ParseChoice("--method", v, MethodChoices()); } });
  const std::vector<OptionSpec> shared = ShockOptionSpecs(settings.shock, ShockOptionSet::All, defaults);
  specs.insert(specs.end(), shared.begin(), shared.end());
  specs.push_back({ "--courant", "C",
    "pde: Courant number of the explicit step, 0.01..1" +
      DefaultText(NumberText(defaults->GetCourantNumber())),
    [&method](const std::string& v) { method.courantNumber = ParseInRange("--courant", v, 0.01, 1.0); } });
  specs.push_back({ "--max-iterations", "N",
    "pde: most explicit steps, 1..100000000" +
      DefaultText(std::to_string(defaults->GetMaximumIterations())),
    [&method](const std::string& v)
    { method.maximumIterations = ParseInRange("--max-iterations", v, 1, 100000000); } });
  specs.push_back(
    ArrayOptionSpec(settings.arrayName, "point array to filter (default: active point scalars)"));
  specs.push_back(TimingsOptionSpec(settings.timings));
  return specs;
}

std::string ImageHelp()
{
  ImageSettings unused;
  std::ostringstream text;
  text << "shockfilter image INPUT OUTPUT [options]\n"
          "  Sharpens the selected point array of an image or volume and writes it.\n"
          "  Formats, chosen by extension (case-insensitive):\n"
          "    read:  png jpg jpeg tif tiff bmp pnm ppm pgm vti vtk (structured points)\n"
          "    write: png jpg jpeg tif tiff bmp pnm ppm pgm vti vtk\n"
          "  The filtered array keeps its type; vti and vtk store all arrays unchanged.\n"
          "  The raster formats store the filtered array only:\n"
          "    png          unsigned char or unsigned short, 1 to 4 components, 2D\n"
          "    tif          unsigned char, unsigned short or float (other types are\n"
          "                 converted to float), 1, 3 or 4 components, 2D or 3D\n"
          "    jpg bmp pnm  unsigned char, 1 or 3 components, 2D\n"
          "  For png/jpg/bmp/pnm other types are rounded and clamped to 0..255 (a note\n"
          "  on stderr says so); other component counts and volumes are refused.\n"
       << TimingsHelp({ "command", "dimensions", "samples", "components", "time", "flow_mode",
                        "threads", "flow", "advection", "total", "trace_steps", "method",
                        "iterations" },
            "  times in seconds, total = wall time of the filter only (no reading/writing);\n"
            "  for --method pde, advection = the explicit updates, iterations = their number.\n")
       << "  Options:\n"
       << FormatOptions(ImageOptionSpecs(unused));
  return text.str();
}

int RunImageCommand(const std::vector<std::string>& args)
{
  ImageSettings settings;
  const std::vector<std::string> paths =
    ParseCommandLine("image", args, ImageOptionSpecs(settings), { "INPUT", "OUTPUT" });
  const std::string& inputPath = paths[0];
  const std::string& outputPath = paths[1];
  FormatOfPath(inputPath, "input");
  const FormatInfo& outputFormat = FormatOfPath(outputPath, "output"); // before the work
  RequireOutputDirectory(outputPath);

  vtkSmartPointer<vtkImageData> input = ReadImage(inputPath);
  const std::string arrayName =
    SelectArray(input, settings.arrayName, vtkDataObject::FIELD_ASSOCIATION_POINTS, "ImageScalars").name;
  RequireStorable(input, arrayName, outputFormat, outputPath);
  const FilterRun run = RunImageFilter(input, arrayName, settings.shock, settings.method);
  WriteImage(run.output, outputPath, arrayName);

  if (settings.timings)
  {
    std::cout << TimingsJson("image", input, run) << std::endl;
  }
  std::cerr << "image: " << DimensionsText(input) << ", " << run.components << " component(s) of '"
            << arrayName << "', t=" << NumberText(run.time)
            << (run.method == vtkImageShockAdvectionFilter::PDE
                   ? " (pde, " + std::to_string(run.iterations) + " steps)"
                   : std::string())
            << ": " << std::fixed
            << std::setprecision(3) << run.totalSeconds << " s -> " << outputPath << '\n';
  return 0;
}

// =============================================================================
// Mesh files (read and written by ShockMeshIO)
// =============================================================================

/// What a mesh format keeps of a mesh's arrays (see ShockMeshIO.h).
enum class MeshArrays
{
  None,    ///< geometry only (and for PLY normals, texture coordinates)
  Colours, ///< unsigned char RGB(A) point and cell colours
  All      ///< every array
};

struct MeshFormatInfo
{
  const char* name;
  std::vector<std::string> extensions; ///< lower case, without the dot
  MeshArrays arrays;
};

/// The formats of ShockMeshIO.h, to check file names before any work is done.
const std::vector<MeshFormatInfo>& MeshFormats()
{
  static const std::vector<MeshFormatInfo> formats = {
    { "PLY", { "ply" }, MeshArrays::Colours },
    { "OFF", { "off" }, MeshArrays::Colours },
    { "OBJ", { "obj" }, MeshArrays::None },
    { "STL", { "stl" }, MeshArrays::None },
    { "VTK XML polydata", { "vtp" }, MeshArrays::All },
    { "legacy VTK", { "vtk" }, MeshArrays::All },
  };
  return formats;
}

const MeshFormatInfo& MeshFormatOfPath(const std::string& path, const std::string& role)
{
  return FormatByExtension(MeshFormats(), path, role);
}

/// ".ply, .off, .vtp or .vtk": the extensions of the formats keeping at least 'arrays'.
std::string MeshExtensionsKeeping(MeshArrays arrays)
{
  std::vector<std::string> extensions;
  for (const MeshFormatInfo& format : MeshFormats())
  {
    if (format.arrays >= arrays)
    {
      extensions.insert(extensions.end(), format.extensions.begin(), format.extensions.end());
    }
  }
  std::string text;
  for (std::size_t i = 0; i < extensions.size(); ++i)
  {
    text += (i == 0 ? "." : (i + 1 == extensions.size() ? " or ." : ", .")) + extensions[i];
  }
  return text;
}

/// Reads a mesh file; throws CliError with ShockMeshIO's one-line message.
vtkSmartPointer<vtkPolyData> ReadMeshFile(const std::string& path)
{
  MeshFormatOfPath(path, "input");
  RequireReadableFile(path);
  std::string error;
  vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(path, error);
  if (!mesh)
  {
    throw CliError(error.empty() ? "cannot read '" + path + "'" : error);
  }
  vtkNew<MessageCollector> warnings; // those of a successful read wait in the output window
  warnings->PrintWarnings();
  return mesh;
}

/// Writes a mesh file; throws CliError with ShockMeshIO's one-line message.
void WriteMeshFile(vtkPolyData* mesh, const std::string& path)
{
  std::string error;
  if (!shockio::WriteMesh(mesh, path, error))
  {
    throw CliError(error.empty() ? "cannot write '" + path + "'" : error);
  }
  vtkNew<MessageCollector> warnings;
  warnings->PrintWarnings();
}

/// Number of triangles the filters make of the polygons and strips (n - 2 per cell of n points).
vtkIdType CountTriangles(vtkPolyData* mesh)
{
  vtkIdType triangles = 0;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
    {
      triangles += std::max<vtkIdType>(0, cells->GetCellSize(c) - 2);
    }
  }
  return triangles;
}

/// The help lines on mesh file formats.
std::string MeshFormatsHelp()
{
  std::string extensions;
  for (const MeshFormatInfo& format : MeshFormats())
  {
    for (const std::string& extension : format.extensions)
    {
      extensions += " " + extension;
    }
  }
  return "  Mesh formats, chosen by extension (case-insensitive), read and written:\n   " + extensions +
    " (vtk: legacy polydata, or an unstructured\n"
    "    grid read as its surface). ply and off keep vertex and face colours\n"
    "    (unsigned char RGB or RGBA), obj and stl the geometry only, vtp and vtk\n"
    "    every array.\n";
}

// =============================================================================
// The "surface" command
// =============================================================================

struct SurfaceSettings
{
  ShockOptions shock;
  std::string arrayName;
  std::optional<int> association;
  bool timings = false;
};

std::vector<OptionSpec> SurfaceOptionSpecs(SurfaceSettings& settings)
{
  vtkNew<vtkPolyDataShockAdvectionFilter> defaults;
  std::vector<OptionSpec> specs = ShockOptionSpecs(settings.shock, ShockOptionSet::All, defaults);
  specs.push_back(ArrayOptionSpec(settings.arrayName, "point or cell array to filter (default: active scalars)"));
  specs.push_back({ "--association", "WHERE",
    "point|cell data only, for --array and the default scalars",
    [&settings](const std::string& v)
    { settings.association = ParseChoice("--association", v, AssociationChoices()); } });
  specs.push_back(TimingsOptionSpec(settings.timings));
  return specs;
}

std::string SurfaceHelp()
{
  SurfaceSettings unused;
  std::ostringstream text;
  text << "shockfilter surface INPUT OUTPUT [options]\n"
          "  Sharpens a point or cell array of a surface mesh (e.g. its vertex colours)\n"
          "  by advection over the surface and writes the mesh with the filtered array.\n"
       << MeshFormatsHelp()
       << "  The array: --array NAME is looked for in the point data, then in the cell\n"
          "  data (only in those of --association when given); by default, the active\n"
          "  scalars of the point data (of the cell data with --association cell), e.g.\n"
          "  the \"Colors\" of a PLY or OFF file. It keeps its name and type; an OUTPUT\n"
          "  that cannot store it (e.g. float values in ply) is refused.\n"
       << TimingsHelp({ "command", "points", "triangles", "array", "association", "components",
                        "time", "flow_mode", "threads", "setup", "flow", "advection", "total",
                        "trace_steps" },
            "  times in seconds: setup = mesh preparation, flow = smoothing, potential and\n"
            "  flow, advection = tracing and sampling, total = wall time of the filter\n"
            "  only (no reading/writing).\n")
       << "  Options:\n"
       << FormatOptions(SurfaceOptionSpecs(unused));
  return text.str();
}

/**
 * Throws unless 'format' keeps the array to filter (checked before the work):
 * ply and off keep unsigned char colours of 3 or 4 components, obj and stl no array.
 */
void RequireMeshStorable(const MeshFormatInfo& format, const SelectedArray& selected, const std::string& path)
{
  const std::string where = "cannot write '" + path + "': ";
  const std::string kind = ChoiceName(selected.association, AssociationChoices());
  vtkDataArray* array = selected.array;
  switch (format.arrays)
  {
    case MeshArrays::All:
      return;
    case MeshArrays::Colours:
      if (array->GetDataType() == VTK_UNSIGNED_CHAR &&
        (array->GetNumberOfComponents() == 3 || array->GetNumberOfComponents() == 4))
      {
        return;
      }
      throw CliError(where + format.name + " stores only unsigned char RGB or RGBA colours; " + kind +
        " array '" + selected.name + "' is " + array->GetDataTypeAsString() + " with " +
        std::to_string(array->GetNumberOfComponents()) + " component(s) (write " +
        MeshExtensionsKeeping(MeshArrays::All) + ")");
    case MeshArrays::None:
      throw CliError(where + format.name + " does not store the filtered " + kind + " array '" +
        selected.name + "' (write " + MeshExtensionsKeeping(MeshArrays::Colours) + ")");
  }
}

int RunSurfaceCommand(const std::vector<std::string>& args)
{
  SurfaceSettings settings;
  const std::vector<std::string> paths =
    ParseCommandLine("surface", args, SurfaceOptionSpecs(settings), { "INPUT", "OUTPUT" });
  const std::string& inputPath = paths[0];
  const std::string& outputPath = paths[1];
  MeshFormatOfPath(inputPath, "input");
  const MeshFormatInfo& outputFormat = MeshFormatOfPath(outputPath, "output"); // before the work
  RequireOutputDirectory(outputPath);

  vtkSmartPointer<vtkPolyData> input = ReadMeshFile(inputPath);
  const SelectedArray selected = SelectArray(input, settings.arrayName, settings.association, "Scalars");
  RequireMeshStorable(outputFormat, selected, outputPath);

  vtkNew<vtkPolyDataShockAdvectionFilter> filter;
  ConfigureFilter(filter, settings.shock);
  filter->SetInputArrayToProcess(0, 0, 0, selected.association, selected.name.c_str());
  filter->SetInputData(input);
  const double seconds = TimedUpdate(filter);

  vtkPolyData* output = filter->GetOutput();
  // The mesh writers store the active scalars as colours: make them the filtered array.
  vtkDataSetAttributes* attributes = selected.association == vtkDataObject::FIELD_ASSOCIATION_CELLS
    ? static_cast<vtkDataSetAttributes*>(output->GetCellData())
    : output->GetPointData();
  attributes->SetActiveScalars(selected.name.c_str());
  WriteMeshFile(output, outputPath);

  const char* kind = ChoiceName(selected.association, AssociationChoices());
  if (settings.timings)
  {
    JsonObject json;
    json.Add("command", "surface")
      .Add("points", input->GetNumberOfPoints())
      .Add("triangles", CountTriangles(input))
      .Add("array", selected.name)
      .Add("association", kind)
      .Add("components", selected.array->GetNumberOfComponents())
      .Add("time", filter->GetFlowTime())
      .Add("flow_mode", ChoiceName(filter->GetFlowMode(), FlowModeChoices()))
      .Add("threads", filter->GetNumberOfThreads())
      .Add("setup", filter->GetLastSetupSeconds())
      .Add("flow", filter->GetLastFlowSeconds())
      .Add("advection", filter->GetLastAdvectionSeconds())
      .Add("total", seconds)
      .Add("trace_steps", filter->GetLastTraceSteps());
    std::cout << json.Text() << std::endl;
  }
  std::cerr << "surface: " << input->GetNumberOfPoints() << " points, " << CountTriangles(input)
            << " triangles, " << selected.array->GetNumberOfComponents() << " component(s) of " << kind
            << " array '" << selected.name << "', t=" << NumberText(filter->GetFlowTime()) << ": "
            << std::fixed << std::setprecision(3) << seconds << " s -> " << outputPath << '\n';
  return 0;
}

// =============================================================================
// The "sharpen" command
// =============================================================================

const std::vector<Choice>& SolverChoices()
{
  static const std::vector<Choice> choices = {
    { "cg", vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT },
    { "cg-tolerance", vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT_TOLERANCE },
    { "exact", vtkPolyDataShockSharpenFilter::EXACT },
  };
  return choices;
}

struct SharpenSettings
{
  ShockOptions shock;
  std::optional<int> normalSmoothingPasses;
  std::optional<double> screeningWeight;
  std::optional<int> solver;
  std::optional<int> iterations;
  std::optional<double> tolerance;
  bool timings = false;
};

std::vector<OptionSpec> SharpenOptionSpecs(SharpenSettings& settings)
{
  vtkNew<vtkPolyDataShockSharpenFilter> defaults;
  std::vector<OptionSpec> specs = ShockOptionSpecs(settings.shock, ShockOptionSet::All, defaults);
  specs.push_back({ "--normal-smoothing", "N",
    "smoothing passes of the normals before, 0..1000" +
      DefaultText(std::to_string(defaults->GetNormalSmoothingPasses())),
    [&settings](const std::string& v)
    { settings.normalSmoothingPasses = ParseInRange("--normal-smoothing", v, 0, 1000); } });
  specs.push_back({ "--screening", "EPS",
    "screening weight of the fit, 1e-6..1e6" + DefaultText(NumberText(defaults->GetScreeningWeight())),
    [&settings](const std::string& v)
    { settings.screeningWeight = ParseInRange("--screening", v, 1e-6, 1e6); } });
  specs.push_back({ "--solver", "NAME",
    "cg|cg-tolerance|exact" + DefaultText(ChoiceName(defaults->GetSolver(), SolverChoices())),
    [&settings](const std::string& v) { settings.solver = ParseChoice("--solver", v, SolverChoices()); } });
  specs.push_back({ "--iterations", "K",
    "CG iterations (cap of cg-tolerance), 0..100000" +
      DefaultText(std::to_string(defaults->GetSolverIterations())),
    [&settings](const std::string& v) { settings.iterations = ParseInRange("--iterations", v, 0, 100000); } });
  specs.push_back({ "--tolerance", "X",
    "stop residual of cg-tolerance (implied), 0..1" +
      DefaultText(NumberText(defaults->GetSolverTolerance())),
    [&settings](const std::string& v) { settings.tolerance = ParseInRange("--tolerance", v, 0.0, 1.0); } });
  specs.push_back(TimingsOptionSpec(settings.timings));
  return specs;
}

std::string SharpenHelp()
{
  SharpenSettings unused;
  std::ostringstream text;
  text << "shockfilter sharpen INPUT OUTPUT [options]\n"
          "  Sharpens the geometry of a surface mesh: its face normals are shock-filtered,\n"
          "  then the points are fitted to them (screened Poisson equation). Creases\n"
          "  and corners become sharp; flat and smooth parts stay. Arrays pass through.\n"
       << MeshFormatsHelp()
       << TimingsHelp({ "command", "points", "triangles", "time", "smoothing", "normal_smoothing",
                        "flow_mode", "solver", "threads", "preprocessing", "setup", "fit_setup",
                        "flow", "advection", "fitting", "total", "trace_steps", "solver_iterations",
                        "solver_residual", "flipped_triangles", "max_displacement" },
            "  times in seconds, the phases of the paper's Table 3: preprocessing = setup\n"
            "  (mesh preparation) + fit_setup (system set-up), flow = normals, smoothing,\n"
            "  potential and flow, advection, fitting = solve; total = wall time of the\n"
            "  filter only (no reading/writing). max_displacement is relative to the\n"
            "  bounding-box diagonal.\n")
       << "  Options:\n"
       << FormatOptions(SharpenOptionSpecs(unused));
  return text.str();
}

int RunSharpenCommand(const std::vector<std::string>& args)
{
  SharpenSettings settings;
  const std::vector<std::string> paths =
    ParseCommandLine("sharpen", args, SharpenOptionSpecs(settings), { "INPUT", "OUTPUT" });
  const int tolerantSolver = vtkPolyDataShockSharpenFilter::CONJUGATE_GRADIENT_TOLERANCE;
  if (settings.tolerance && settings.solver.value_or(tolerantSolver) != tolerantSolver)
  {
    throw CliError("sharpen: --tolerance applies to --solver cg-tolerance only");
  }
  const std::string& inputPath = paths[0];
  const std::string& outputPath = paths[1];
  MeshFormatOfPath(inputPath, "input");
  MeshFormatOfPath(outputPath, "output"); // before the work
  RequireOutputDirectory(outputPath);
  vtkSmartPointer<vtkPolyData> input = ReadMeshFile(inputPath);

  vtkNew<vtkPolyDataShockSharpenFilter> filter;
  ConfigureFilter(filter, settings.shock);
  if (settings.normalSmoothingPasses)
  {
    filter->SetNormalSmoothingPasses(*settings.normalSmoothingPasses);
  }
  if (settings.screeningWeight)
  {
    filter->SetScreeningWeight(*settings.screeningWeight);
  }
  if (settings.solver || settings.tolerance)
  {
    filter->SetSolver(settings.solver.value_or(tolerantSolver));
  }
  if (settings.iterations)
  {
    filter->SetSolverIterations(*settings.iterations);
  }
  if (settings.tolerance)
  {
    filter->SetSolverTolerance(*settings.tolerance);
  }
  filter->SetInputData(input);
  const double seconds = TimedUpdate(filter);
  WriteMeshFile(filter->GetOutput(), outputPath);

  if (settings.timings)
  {
    JsonObject json;
    json.Add("command", "sharpen")
      .Add("points", input->GetNumberOfPoints())
      .Add("triangles", CountTriangles(input))
      .Add("time", filter->GetFlowTime())
      .Add("smoothing", filter->GetSmoothingPasses())
      .Add("normal_smoothing", filter->GetNormalSmoothingPasses())
      .Add("flow_mode", ChoiceName(filter->GetFlowMode(), FlowModeChoices()))
      .Add("solver", ChoiceName(filter->GetSolver(), SolverChoices()))
      .Add("threads", filter->GetNumberOfThreads())
      .Add("preprocessing", filter->GetLastSetupSeconds() + filter->GetLastFitSetupSeconds())
      .Add("setup", filter->GetLastSetupSeconds())
      .Add("fit_setup", filter->GetLastFitSetupSeconds())
      .Add("flow", filter->GetLastFlowSeconds())
      .Add("advection", filter->GetLastAdvectionSeconds())
      .Add("fitting", filter->GetLastFitSolveSeconds())
      .Add("total", seconds)
      .Add("trace_steps", filter->GetLastTraceSteps())
      .Add("solver_iterations", filter->GetLastSolverIterations())
      .Add("solver_residual", filter->GetLastSolverResidual())
      .Add("flipped_triangles", filter->GetLastFlippedTriangles())
      .Add("max_displacement", filter->GetLastMaxDisplacement());
    std::cout << json.Text() << std::endl;
  }
  std::cerr << "sharpen: " << input->GetNumberOfPoints() << " points, " << CountTriangles(input)
            << " triangles, t=" << NumberText(filter->GetFlowTime()) << ": " << std::fixed
            << std::setprecision(3) << seconds << " s (" << filter->GetLastSolverIterations()
            << " solver iterations, relative residual " << NumberText(filter->GetLastSolverResidual())
            << ", " << filter->GetLastFlippedTriangles() << " flipped triangles, max displacement "
            << NumberText(filter->GetLastMaxDisplacement()) << " of the diagonal) -> " << outputPath
            << '\n';
  return 0;
}

// =============================================================================
// The "demo" command
// =============================================================================

/// Flow times of the picture demo, and the one shown in before_after.png.
constexpr std::array<double, 4> PictureDemoTimes = { 256, 1024, 4096, 16384 };
constexpr double PictureDemoShownTime = 4096;
/// Flow time of the volume demo.
constexpr double VolumeDemoTime = 4096;

/// An RGB colour, 0..255.
using Rgb = std::array<double, 3>;

/// Colour of the synthetic picture at pixel (x, y): gradient background and shapes, painted in order.
Rgb DemoPictureColour(int x, int y, int width, int height)
{
  const double fx = static_cast<double>(x) / (width - 1);
  const double fy = static_cast<double>(y) / (height - 1);
  Rgb colour = { 40 + 150 * fy, 70 + 120 * fy + 30 * fx, 140 + 90 * fy }; // blue-grey sky gradient

  const auto inDisk = [&](double cx, double cy, double r)
  { return (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r; };

  // Thin stripes (4 px black/white) at the lower left: the hardest case after blurring.
  if (x >= 30 && x < 190 && y >= 30 && y < 130)
  {
    colour = ((x - 30) / 4) % 2 == 0 ? Rgb{ 20, 20, 20 } : Rgb{ 235, 235, 235 };
  }
  // Wider stripes (10 px) above them.
  if (x >= 30 && x < 190 && y >= 150 && y < 210)
  {
    colour = ((x - 30) / 10) % 2 == 0 ? Rgb{ 30, 30, 90 } : Rgb{ 250, 240, 200 };
  }
  // Red disk.
  if (inDisk(120, 290, 65))
  {
    colour = { 220, 40, 35 };
  }
  // Green rectangle.
  if (x >= 230 && x < 370 && y >= 40 && y < 170)
  {
    colour = { 40, 170, 70 };
  }
  // Orange ring.
  if (inDisk(400, 270, 80) && !inDisk(400, 270, 52))
  {
    colour = { 245, 150, 20 };
  }
  // Purple diamond inside the ring.
  if (std::abs(x - 400) + std::abs(y - 270) < 30)
  {
    colour = { 150, 40, 170 };
  }
  // Yellow bar crossing the rectangle.
  if (x >= 200 && x < 480 && y >= 95 && y < 115)
  {
    colour = { 250, 225, 40 };
  }
  return colour;
}

/// An image of the given size whose point scalars 'array' are filled by 'value(x, y, z, component)'.
vtkSmartPointer<vtkImageData> MakeImage(const std::array<int, 3>& dims, int components,
  const std::string& arrayName, const std::function<double(int, int, int, int)>& value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims.data());
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName(arrayName.c_str());
  scalars->SetNumberOfComponents(components);
  scalars->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x, ++id)
      {
        for (int c = 0; c < components; ++c)
        {
          scalars->SetTypedComponent(id, c, static_cast<float>(value(x, y, z, c)));
        }
      }
    }
  }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

/// Gaussian blur with standard deviation 'sigma' samples along the image's first 'dimensionality' axes.
vtkSmartPointer<vtkImageData> GaussianBlur(vtkImageData* image, int dimensionality, double sigma)
{
  vtkNew<vtkImageGaussianSmooth> blur;
  blur->SetInputData(image);
  blur->SetDimensionality(dimensionality);
  blur->SetStandardDeviations(sigma, sigma, sigma);
  blur->SetRadiusFactors(3.0, 3.0, 3.0);
  vtkNew<MessageCollector> messages;
  messages->WatchAlgorithm(blur);
  UpdateOrThrow(blur, messages, "Gaussian blur failed");
  auto blurred = vtkSmartPointer<vtkImageData>::New();
  blurred->ShallowCopy(blur->GetOutput());
  blurred->GetPointData()->GetScalars()->SetName(image->GetPointData()->GetScalars()->GetName());
  return blurred;
}

/// Adds Gaussian noise of standard deviation 'sigma' to every value (fixed seed: reproducible).
void AddNoise(vtkDataArray* values, double sigma, unsigned seed)
{
  std::mt19937 generator(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const int components = values->GetNumberOfComponents();
  for (vtkIdType t = 0; t < values->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < components; ++c)
    {
      values->SetComponent(t, c, values->GetComponent(t, c) + noise(generator));
    }
  }
}

/// Replaces the point scalars of 'image' by their rounded, clamped unsigned char version.
void QuantizeScalars(vtkImageData* image, double scale)
{
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  image->GetPointData()->SetScalars(QuantizeToBytes(scalars, scale));
}

/**
 * Sharpness figure: the root mean square over the interior samples of |grad L|,
 * L the luminance (Rec. 601 weights for 3 or more components, else the first
 * component), by central differences in sample units. (The mean of |grad L|
 * would not do: across a monotone edge it sums to the edge height however
 * sharp the edge is; the mean square grows as the edge narrows.)
 */
double RmsLuminanceGradient(vtkImageData* image, const std::string& arrayName)
{
  vtkDataArray* array = image->GetPointData()->GetArray(arrayName.c_str());
  int dims[3];
  image->GetDimensions(dims);
  const vtkIdType count = image->GetNumberOfPoints();
  std::vector<double> luminance(static_cast<std::size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    luminance[i] = array->GetNumberOfComponents() >= 3
      ? 0.299 * array->GetComponent(i, 0) + 0.587 * array->GetComponent(i, 1) +
        0.114 * array->GetComponent(i, 2)
      : array->GetComponent(i, 0);
  }
  const std::array<vtkIdType, 3> stride = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const auto interior = [&](int axis, int index)
  { return dims[axis] == 1 || (index > 0 && index < dims[axis] - 1); };
  double sum = 0.0;
  vtkIdType samples = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        if (!interior(0, i) || !interior(1, j) || !interior(2, k))
        {
          continue;
        }
        const vtkIdType id = i + j * stride[1] + k * stride[2];
        for (int a = 0; a < 3; ++a)
        {
          if (dims[a] > 1)
          {
            const double g = 0.5 * (luminance[id + stride[a]] - luminance[id - stride[a]]);
            sum += g * g;
          }
        }
        ++samples;
      }
    }
  }
  return samples > 0 ? std::sqrt(sum / static_cast<double>(samples)) : 0.0;
}

/// A 2D image of the given size filled with one byte value, for gaps between pictures.
vtkSmartPointer<vtkImageData> MakeFilledBytes(
  int width, int height, int components, const std::string& arrayName, unsigned char value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetName(arrayName.c_str());
  bytes->SetNumberOfComponents(components);
  bytes->SetNumberOfTuples(image->GetNumberOfPoints());
  bytes->FillValue(value);
  image->GetPointData()->SetScalars(bytes);
  return image;
}

/**
 * Two 2D byte images of the same height side by side along X, separated by a
 * white gap of 'gap' pixels. Their point scalars must have the same name and
 * number of components; only the scalars are kept.
 */
vtkSmartPointer<vtkImageData> SideBySide(vtkImageData* left, vtkImageData* right, int gap)
{
  vtkDataArray* scalars = left->GetPointData()->GetScalars();
  const std::string name = scalars->GetName() ? scalars->GetName() : "Scalars";
  int dims[3];
  left->GetDimensions(dims);
  vtkSmartPointer<vtkImageData> whiteGap =
    MakeFilledBytes(gap, dims[1], scalars->GetNumberOfComponents(), name, 255);
  vtkNew<vtkImageAppend> append;
  append->SetAppendAxis(0);
  append->PreserveExtentsOff();
  for (vtkImageData* piece : { left, whiteGap.Get(), right })
  {
    // Only the scalars, so that the pieces append array by array.
    auto scalarsOnly = vtkSmartPointer<vtkImageData>::New();
    scalarsOnly->CopyStructure(piece);
    scalarsOnly->GetPointData()->SetScalars(piece->GetPointData()->GetScalars());
    append->AddInputData(scalarsOnly);
  }
  vtkNew<MessageCollector> messages;
  messages->WatchAlgorithm(append);
  UpdateOrThrow(append, messages, "cannot put images side by side");
  auto result = vtkSmartPointer<vtkImageData>::New();
  result->ShallowCopy(append->GetOutput());
  return result;
}

/**
 * The middle z-slice of a one-component volume as a 2D unsigned char image:
 * values times 'scale', pixels enlarged 'zoom' times (nearest neighbour).
 */
vtkSmartPointer<vtkImageData> MiddleSliceAsBytes(
  vtkImageData* volume, const std::string& arrayName, double scale, int zoom)
{
  int dims[3];
  volume->GetDimensions(dims);
  vtkDataArray* values = volume->GetPointData()->GetArray(arrayName.c_str());
  const vtkIdType sliceStart = static_cast<vtkIdType>(dims[0]) * dims[1] * (dims[2] / 2);
  vtkSmartPointer<vtkImageData> slice =
    MakeImage({ dims[0] * zoom, dims[1] * zoom, 1 }, 1, arrayName, [&](int x, int y, int, int)
      { return values->GetComponent(sliceStart + x / zoom + static_cast<vtkIdType>(dims[0]) * (y / zoom), 0); });
  QuantizeScalars(slice, scale);
  return slice;
}

/// Creates 'directory' (and parents) if missing.
void CreateDirectory(const std::filesystem::path& directory)
{
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory))
  {
    throw CliError("cannot create directory '" + directory.string() + "'" +
      (error ? ": " + error.message() : ""));
  }
}

/// Writes 'image' to 'directory'/'name' and tells so on stderr.
void WriteDemoFile(vtkImageData* image, const std::filesystem::path& directory, const std::string& name,
  const std::string& arrayName, const std::string& description)
{
  const std::string path = (directory / name).string();
  WriteImage(image, path, arrayName);
  std::cerr << "demo: wrote " << path << " (" << description << ")\n";
}

/// "0.123 s (flow 0.010 s, advection 0.113 s)"
std::string RunTimesText(const FilterRun& run)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << run.totalSeconds << " s (flow " << run.flowSeconds
       << " s, advection " << run.advectionSeconds << " s)";
  return text.str();
}

/// The 2D part of the demo: picture, sharpened pictures for several t, before/after.
/// Returns whether its check holds: the sharpness increases with t.
bool RunPictureDemo(const std::filesystem::path& directory, const ShockOptions& common)
{
  const std::string arrayName = "Picture";
  const int width = 512;
  const int height = 384;
  const double blurSigma = 3.0;
  const double noiseSigma = 2.0;

  vtkSmartPointer<vtkImageData> sharp = MakeImage({ width, height, 1 }, 3, arrayName,
    [&](int x, int y, int, int c) { return DemoPictureColour(x, y, width, height)[c]; });
  vtkSmartPointer<vtkImageData> picture = GaussianBlur(sharp, 2, blurSigma);
  AddNoise(picture->GetPointData()->GetScalars(), noiseSigma, 2015u);
  QuantizeScalars(picture, 1.0);
  WriteDemoFile(picture, directory, "input.png", arrayName,
    "512x384 RGB, Gaussian blur sigma 3 px, noise sigma 2");

  const double inputSharpness = RmsLuminanceGradient(picture, arrayName);
  std::cerr << "demo: sharpness (RMS luminance gradient) of the input: " << NumberText(inputSharpness)
            << '\n';
  double previousSharpness = inputSharpness;
  bool increasing = true;
  vtkSmartPointer<vtkImageData> shown;
  for (const double t : PictureDemoTimes)
  {
    ShockOptions options = common;
    options.time = t;
    options.flowMode = vtkShockAdvectionFilter::FIXED;
    const FilterRun run = RunImageFilter(picture, arrayName, options);
    const std::string name = "sharpened_t" + NumberText(t) + ".png";
    const double sharpness = RmsLuminanceGradient(run.output, arrayName);
    increasing = increasing && sharpness > previousSharpness;
    previousSharpness = sharpness;
    WriteDemoFile(run.output, directory, name, arrayName,
      "t=" + NumberText(t) + ", fixed flow: " + RunTimesText(run));
    std::cerr << "demo: sharpness at t=" << NumberText(t) << ": " << NumberText(sharpness) << " (input "
              << NumberText(inputSharpness) << ")\n";
    if (t == PictureDemoShownTime)
    {
      shown = run.output;
    }
  }
  std::cerr << "demo: sharpness " << (increasing ? "increases" : "does NOT increase")
            << " with t\n";
  WriteDemoFile(SideBySide(picture, shown, 8), directory, "before_after.png", arrayName,
    "input | t=" + NumberText(PictureDemoShownTime));
  return increasing;
}

/// Value of the synthetic volume at voxel (x, y, z): spheres and a box, 0..1.
double DemoVolumeValue(int x, int y, int z)
{
  const auto inBall = [&](double cx, double cy, double cz, double r)
  { return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) <= r * r; };
  if (inBall(22, 24, 32, 14))
  {
    return 1.0;
  }
  if (inBall(46, 44, 30, 10))
  {
    return 0.75;
  }
  if (inBall(18, 50, 36, 6))
  {
    return 0.9;
  }
  if (x >= 34 && x < 56 && y >= 8 && y < 24 && z >= 16 && z < 48)
  {
    return 0.5;
  }
  return 0.05;
}

/// The 3D part of the demo: blurred volume, sharpened at VolumeDemoTime, middle slices side by side.
void RunVolumeDemo(const std::filesystem::path& directory, const ShockOptions& common)
{
  const std::string arrayName = "Density";
  const int size = 64;
  vtkSmartPointer<vtkImageData> sharp = MakeImage({ size, size, size }, 1, arrayName,
    [](int x, int y, int z, int) { return DemoVolumeValue(x, y, z); });
  vtkSmartPointer<vtkImageData> volume = GaussianBlur(sharp, 3, 2.0);
  WriteDemoFile(volume, directory, "volume_input.vti", arrayName,
    "64^3 float, 3 spheres and a box, Gaussian blur sigma 2 voxels");

  ShockOptions options = common;
  options.time = VolumeDemoTime;
  options.flowMode = vtkShockAdvectionFilter::FIXED;
  const FilterRun run = RunImageFilter(volume, arrayName, options);
  WriteDemoFile(run.output, directory, "volume_sharpened.vti", arrayName,
    "t=" + NumberText(VolumeDemoTime) + ": " + RunTimesText(run));
  std::cerr << "demo: volume sharpness (RMS gradient): input "
            << NumberText(RmsLuminanceGradient(volume, arrayName)) << ", t=" << NumberText(VolumeDemoTime) << " "
            << NumberText(RmsLuminanceGradient(run.output, arrayName)) << '\n';

  const int zoom = 4;
  vtkSmartPointer<vtkImageData> before = MiddleSliceAsBytes(volume, arrayName, 255.0, zoom);
  vtkSmartPointer<vtkImageData> after = MiddleSliceAsBytes(run.output, arrayName, 255.0, zoom);
  WriteDemoFile(SideBySide(before, after, 8), directory, "volume_before_after.png", arrayName,
    "middle z-slice, input | t=" + NumberText(VolumeDemoTime) + ", 0..1 shown as 0..255, " +
      "pixels enlarged " + std::to_string(zoom) + "x");
}

/// Flow times of the mesh demo: the sphere's colours and the rounded box's geometry.
constexpr double SphereDemoTime = 1024;
constexpr double BoxDemoTime = 2048;

/**
 * The surface of the cube [-1, 1]^3 with n x n squares per face, two triangles
 * each (counter-clockwise seen from outside; edge and corner points shared),
 * with its creases rounded to radius 'rounding' in [0, 1] (1 gives the unit sphere).
 */
vtkSmartPointer<vtkPolyData> MakeRoundedCube(int n, double rounding)
{
  const int m = n + 1;
  std::vector<vtkIdType> ids(static_cast<std::size_t>(m) * m * m, -1); // lattice point -> point id
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const double inner = 1.0 - rounding;
  const auto pointId = [&](const std::array<int, 3>& lattice)
  {
    vtkIdType& id = ids[(static_cast<std::size_t>(lattice[2]) * m + lattice[1]) * m + lattice[0]];
    if (id < 0)
    {
      // The rounded box is the inner cube grown by a ball: a point moves to distance
      // 'rounding' from its nearest point on the inner cube.
      std::array<double, 3> x, nearest;
      double distance = 0.0;
      for (int a = 0; a < 3; ++a)
      {
        x[a] = 2.0 * lattice[a] / n - 1.0;
        nearest[a] = std::clamp(x[a], -inner, inner);
        distance += (x[a] - nearest[a]) * (x[a] - nearest[a]);
      }
      distance = std::sqrt(distance);
      for (int a = 0; a < 3 && distance > 0.0; ++a)
      {
        x[a] = nearest[a] + rounding * (x[a] - nearest[a]) / distance;
      }
      id = points->InsertNextPoint(x.data());
    }
    return id;
  };
  vtkNew<vtkCellArray> triangles;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const int side : { 0, n })
    {
      for (int u = 0; u < n; ++u)
      {
        for (int v = 0; v < n; ++v)
        {
          // Axes (axis + 1, axis + 2) turn counter-clockwise seen from the + side.
          const auto corner = [&](int du, int dv)
          {
            std::array<int, 3> lattice;
            lattice[axis] = side;
            lattice[(axis + 1) % 3] = u + du;
            lattice[(axis + 2) % 3] = v + dv;
            return pointId(lattice);
          };
          std::array<vtkIdType, 4> square = { corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1) };
          if (side == 0)
          {
            std::swap(square[1], square[3]);
          }
          triangles->InsertNextCell({ square[0], square[1], square[2] });
          triangles->InsertNextCell({ square[0], square[2], square[3] });
        }
      }
    }
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  return mesh;
}

/// Colour of the sphere demo at a point of the unit sphere: three regions with blurred borders.
Rgb DemoSphereColour(const double p[3])
{
  const auto step = [](double signedDistance) { return 0.5 + 0.5 * std::tanh(signedDistance / 0.1); };
  const double a = step(p[0] + 0.3 * p[1]); // across a tilted great circle
  const double b = step(p[2] - 0.45);       // across a latitude
  const Rgb blue = { 30, 70, 190 }, orange = { 240, 140, 25 }, white = { 235, 235, 225 };
  Rgb colour;
  for (int c = 0; c < 3; ++c)
  {
    colour[c] = (1.0 - b) * ((1.0 - a) * blue[c] + a * orange[c]) + b * white[c];
  }
  return colour;
}

/// Writes 'mesh' to 'directory'/'name' and tells so on stderr.
void WriteDemoMesh(vtkPolyData* mesh, const std::filesystem::path& directory, const std::string& name,
  const std::string& description)
{
  const std::string path = (directory / name).string();
  WriteMeshFile(mesh, path);
  std::cerr << "demo: wrote " << path << " (" << description << ")\n";
}

/// The mesh part of the demo: blurred colours on a sphere, the geometry of a rounded box.
void RunMeshDemo(const std::filesystem::path& directory, const ShockOptions& common)
{
  vtkSmartPointer<vtkPolyData> sphere = MakeRoundedCube(40, 1.0);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName(shockio::PointColorsName);
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(sphere->GetNumberOfPoints());
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    const Rgb colour = DemoSphereColour(sphere->GetPoint(p));
    for (int c = 0; c < 3; ++c)
    {
      colours->SetTypedComponent(p, c, static_cast<unsigned char>(std::lround(colour[c])));
    }
  }
  sphere->GetPointData()->SetScalars(colours);
  WriteDemoMesh(sphere, directory, "sphere_input.ply",
    std::to_string(sphere->GetNumberOfPoints()) + "-point sphere, blurred vertex colours");
  vtkNew<vtkPolyDataShockAdvectionFilter> surface;
  ConfigureFilter(surface, common);
  surface->SetFlowTime(SphereDemoTime);
  surface->SetInputData(sphere);
  const double surfaceSeconds = TimedUpdate(surface);
  WriteDemoMesh(surface->GetOutput(), directory, "sphere_sharpened.ply",
    "colours filtered at t=" + NumberText(SphereDemoTime) + ": " + SecondsText(surfaceSeconds));

  vtkSmartPointer<vtkPolyData> box = MakeRoundedCube(32, 0.3);
  WriteDemoMesh(box, directory, "rounded_box_input.ply",
    std::to_string(box->GetNumberOfPoints()) + "-point cube, creases rounded to 0.3 of the half side");
  vtkNew<vtkPolyDataShockSharpenFilter> sharpen;
  ConfigureFilter(sharpen, common);
  sharpen->SetFlowTime(BoxDemoTime);
  sharpen->SetInputData(box);
  const double sharpenSeconds = TimedUpdate(sharpen);
  WriteDemoMesh(sharpen->GetOutput(), directory, "rounded_box_sharpened.ply",
    "geometry sharpened at t=" + NumberText(BoxDemoTime) + ": " + SecondsText(sharpenSeconds) +
      ", largest displacement " + NumberText(sharpen->GetLastMaxDisplacement()) + " of the diagonal");
}

struct DemoSettings
{
  ShockOptions shock;
};

std::vector<OptionSpec> DemoOptionSpecs(DemoSettings& settings)
{
  vtkNew<vtkImageShockAdvectionFilter> defaults;
  return ShockOptionSpecs(settings.shock, ShockOptionSet::ThreadsOnly, defaults);
}

std::string DemoHelp()
{
  DemoSettings unused;
  std::ostringstream text;
  std::string times;
  for (const double t : PictureDemoTimes)
  {
    times += (times.empty() ? "" : ", ") + NumberText(t);
  }
  text << "shockfilter demo OUTDIR [options]\n"
          "  Runs the filter on built-in data and writes to OUTDIR (created if missing):\n"
          "    input.png               blurred, slightly noisy 512x384 RGB test picture\n"
          "    sharpened_t<T>.png      the picture filtered at T = "
       << times << "\n"
       << "    before_after.png        input | t=" << NumberText(PictureDemoShownTime) << "\n"
       << "    volume_input.vti        blurred 64^3 float volume of spheres and a box\n"
          "    volume_sharpened.vti    the volume filtered at t="
       << NumberText(VolumeDemoTime) << "\n"
       << "    volume_before_after.png middle z-slices, input | t=" << NumberText(VolumeDemoTime)
       << "\n"
          "    sphere_input.ply        sphere with blurred vertex colours\n"
          "    sphere_sharpened.ply    its colours filtered at t="
       << NumberText(SphereDemoTime) << "\n"
       << "    rounded_box_input.ply   cube with rounded creases\n"
          "    rounded_box_sharpened.ply  its geometry sharpened at t="
       << NumberText(BoxDemoTime) << "\n"
       << "  Fixed flow, other parameters at their defaults. Prints on stderr what it\n"
          "  wrote, the run times and a sharpness figure per t of the picture.\n"
          "  Options:\n"
       << FormatOptions(DemoOptionSpecs(unused));
  return text.str();
}

int RunDemoCommand(const std::vector<std::string>& args)
{
  DemoSettings settings;
  const std::filesystem::path directory =
    ParseCommandLine("demo", args, DemoOptionSpecs(settings), { "OUTDIR" })[0];
  CreateDirectory(directory);
  const bool sharper = RunPictureDemo(directory, settings.shock);
  RunVolumeDemo(directory, settings.shock);
  RunMeshDemo(directory, settings.shock);
  if (!sharper)
  {
    std::cerr << "demo: FAILED: the pictures do not get sharper with t\n";
    return 1;
  }
  return 0;
}

// =============================================================================
// Subcommand table and main
// =============================================================================

/// A subcommand: its name, a one-line summary, its help text and its entry point.
struct Command
{
  const char* name;
  const char* summary;
  std::string (*help)();
  int (*run)(const std::vector<std::string>& args);
};

const std::vector<Command>& Commands()
{
  static const std::vector<Command> commands = {
    { "image", "sharpen an image or volume file", ImageHelp, RunImageCommand },
    { "surface", "sharpen the colours (or another array) of a surface mesh file", SurfaceHelp,
      RunSurfaceCommand },
    { "sharpen", "sharpen the geometry of a surface mesh file", SharpenHelp, RunSharpenCommand },
    { "demo", "sharpen built-in test data, write the results to a directory", DemoHelp,
      RunDemoCommand },
  };
  return commands;
}

const Command* FindCommand(const std::string& name)
{
  for (const Command& command : Commands())
  {
    if (name == command.name)
    {
      return &command;
    }
  }
  return nullptr;
}

/// The short usage: synopsis and command list.
std::string ShortUsage()
{
  std::ostringstream text;
  text << "Usage: shockfilter COMMAND ARGUMENTS [options]\n"
          "       shockfilter --help | COMMAND --help\n"
          "Commands:\n";
  for (const Command& command : Commands())
  {
    text << "  " << std::left << std::setw(8) << command.name << " " << command.summary << '\n';
  }
  return text.str();
}

/// The full help: short usage, every command's help, exit status.
std::string FullHelp()
{
  std::ostringstream text;
  text << "shockfilter: unconditionally stable shock filters (Prada and Kazhdan 2015):\n"
          "sharpen edges by advecting the signal along u = 1/2 grad |grad I|^2.\n\n"
       << ShortUsage();
  for (const Command& command : Commands())
  {
    text << '\n' << command.help();
  }
  text << "\nExit status: 0 on success, 2 on any error (one line \"shockfilter: ...\"\non stderr).\n";
  return text.str();
}

int Dispatch(const std::vector<std::string>& args)
{
  if (args.empty())
  {
    std::cerr << ShortUsage() << "Run 'shockfilter --help' for the options.\n";
    return ExitError;
  }
  if (args[0] == "-h" || args[0] == "--help")
  {
    std::cout << FullHelp();
    return 0;
  }
  const Command* command = FindCommand(args[0]);
  if (!command)
  {
    std::string names;
    for (const Command& known : Commands())
    {
      names += (names.empty() ? "" : ", ") + std::string(known.name);
    }
    throw CliError("unknown command '" + args[0] + "' (commands: " + names + "; see '" +
      ProgramName + " --help')");
  }
  const std::vector<std::string> commandArgs(args.begin() + 1, args.end());
  if (IsHelpRequest(commandArgs))
  {
    std::cout << command->help();
    return 0;
  }
  return command->run(commandArgs);
}
} // namespace

int main(int argc, char* argv[])
{
  InstallCapturingOutputWindow();
  try
  {
    return Dispatch(std::vector<std::string>(argv + 1, argv + argc));
  }
  catch (const CliError& error)
  {
    std::cerr << ProgramName << ": " << SingleLine(error.what()) << '\n';
  }
  catch (const std::exception& error)
  {
    std::cerr << ProgramName << ": internal error: " << SingleLine(error.what()) << '\n';
  }
  return ExitError;
}
