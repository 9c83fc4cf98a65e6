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
 *    the result; `--timings` prints one JSON object with the run times on stdout;
 *  - `demo OUTDIR [options]` builds a blurred synthetic picture and volume,
 *    sharpens them and writes inputs, results and side-by-side comparisons.
 * The table is meant to grow (the mesh commands `surface` and `sharpen`): a
 * subcommand is a function of its arguments and a help text; its options are an
 * OptionSpec list parsed by ParseArguments(), and the parameters shared by every
 * shock filter are ShockOptions (ShockOptionSpecs(), ConfigureFilter()).
 *
 * Errors print exactly one line "shockfilter: <message>" on stderr and exit
 * with code 2. The errors and warnings of VTK objects are caught by a
 * MessageCollector observer (and those nobody observes by a replacement of VTK's
 * output window) instead of being printed; the first error is folded into that
 * line, warnings become "shockfilter: warning: ..." lines.
 */

#include "vtkImageShockAdvectionFilter.h"

#include "vtkAlgorithm.h"
#include "vtkBMPReader.h"
#include "vtkBMPWriter.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
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
// Shock-filter parameters (shared by the image command, the demo and, later,
// the mesh commands)
// =============================================================================

const std::vector<Choice>& FlowModeChoices()
{
  static const std::vector<Choice> choices = { { "fixed", vtkShockAdvectionFilter::FIXED },
    { "composed", vtkShockAdvectionFilter::COMPOSED }, { "naive", vtkShockAdvectionFilter::NAIVE } };
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

/**
 * The options setting ShockOptions. Ranges are those of vtkShockAdvectionFilter
 * (whose setters would clamp silently); the defaults shown are the filter's.
 */
std::vector<OptionSpec> ShockOptionSpecs(ShockOptions& target, ShockOptionSet set)
{
  vtkNew<vtkImageShockAdvectionFilter> defaults;
  const auto defaultText = [](const std::string& value) { return " (default " + value + ")"; };
  std::vector<OptionSpec> specs;
  if (set == ShockOptionSet::All)
  {
    specs.push_back({ "--time", "T",
      "flow time t >= 0, normalised units" + defaultText(NumberText(defaults->GetTimeStep())),
      [&target](const std::string& v)
      { target.time = ParseInRange("--time", v, 0.0, std::numeric_limits<double>::max()); } });
    specs.push_back({ "--smoothing", "N",
      "smoothing passes, 0..10000" +
        defaultText(std::to_string(defaults->GetSmoothingPasses())),
      [&target](const std::string& v) { target.smoothingPasses = ParseInRange("--smoothing", v, 0, 10000); } });
    specs.push_back({ "--flow", "MODE",
      "fixed|composed|naive" + defaultText(ChoiceName(defaults->GetFlowMode(), FlowModeChoices())),
      [&target](const std::string& v) { target.flowMode = ParseChoice("--flow", v, FlowModeChoices()); } });
    specs.push_back({ "--updates", "K",
      "flow updates of composed/naive, 1..100000" +
        defaultText(std::to_string(defaults->GetNumberOfFlowUpdates())),
      [&target](const std::string& v) { target.flowUpdates = ParseInRange("--updates", v, 1, 100000); } });
    specs.push_back({ "--sampling", "MODE",
      "linear|nearest" + defaultText(ChoiceName(defaults->GetSampling(), SamplingChoices())),
      [&target](const std::string& v) { target.sampling = ParseChoice("--sampling", v, SamplingChoices()); } });
    specs.push_back({ "--tracing", "MODE",
      "exact (face crossing)|stepped" + defaultText(ChoiceName(defaults->GetTracingMode(), TracingChoices())),
      [&target](const std::string& v) { target.tracingMode = ParseChoice("--tracing", v, TracingChoices()); } });
    specs.push_back({ "--step-fraction", "F",
      "step of stepped tracing (edges), 0.001..1" +
        defaultText(NumberText(defaults->GetStepFraction())),
      [&target](const std::string& v)
      { target.stepFraction = ParseInRange("--step-fraction", v, 0.001, 1.0); } });
  }
  specs.push_back({ "--threads", "N", "OpenMP threads, 0..4096, 0 = all cores" +
      defaultText(std::to_string(defaults->GetNumberOfThreads())),
    [&target](const std::string& v) { target.threads = ParseInRange("--threads", v, 0, 4096); } });
  return specs;
}

/// Sets the given parameters on a filter; the others keep their defaults.
void ConfigureFilter(vtkShockAdvectionFilter* filter, const ShockOptions& options)
{
  if (options.time)
  {
    filter->SetTimeStep(*options.time);
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

/// The format chosen by the (case-insensitive) extension of 'path'; throws if unsupported.
const FormatInfo& FormatOfPath(const std::string& path, const std::string& role)
{
  const std::string extension = ToLower(std::filesystem::path(path).extension().string());
  std::string known;
  for (const FormatInfo& format : Formats())
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
// Running the filter
// =============================================================================

/// The result and measurements of one filter execution.
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
};

/// Names of the point arrays of an image, for messages.
std::string PointArrayNames(vtkImageData* image)
{
  std::string names;
  vtkPointData* pointData = image->GetPointData();
  for (int i = 0; i < pointData->GetNumberOfArrays(); ++i)
  {
    const char* name = pointData->GetArrayName(i);
    names += (names.empty() ? "" : ", ") + std::string(name ? name : "(unnamed)");
  }
  return names.empty() ? "none" : names;
}

/**
 * The name of the point array to filter: 'requested', or the active point
 * scalars (named "ImageScalars" if they have no name). Throws if there is none.
 */
std::string SelectPointArray(vtkImageData* image, const std::string& requested)
{
  vtkPointData* pointData = image->GetPointData();
  if (!requested.empty())
  {
    if (!pointData->GetAbstractArray(requested.c_str()))
    {
      throw CliError("the input has no point array '" + requested +
        "' (point arrays: " + PointArrayNames(image) + ")");
    }
    return requested;
  }
  vtkDataArray* scalars = pointData->GetScalars();
  if (!scalars)
  {
    throw CliError("the input has no active point scalars; choose an array with --array "
                   "(point arrays: " + PointArrayNames(image) + ")");
  }
  if (!scalars->GetName() || !*scalars->GetName())
  {
    scalars->SetName("ImageScalars");
  }
  return scalars->GetName();
}

/// Filters the point array 'arrayName' of 'input'; throws "shock filter failed: ..." on error.
FilterRun RunImageFilter(vtkImageData* input, const std::string& arrayName, const ShockOptions& options)
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  ConfigureFilter(filter, options);
  filter->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, arrayName.c_str());
  filter->SetInputData(input);
  vtkNew<MessageCollector> messages;
  messages->WatchAlgorithm(filter);

  const auto start = std::chrono::steady_clock::now();
  const bool ok = filter->GetExecutive()->Update() != 0;
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  CheckUpdate(ok, messages, "shock filter failed");

  FilterRun run;
  run.output = vtkSmartPointer<vtkImageData>::New();
  run.output->ShallowCopy(filter->GetOutput());
  run.time = filter->GetTimeStep();
  run.flowMode = filter->GetFlowMode();
  run.threads = filter->GetNumberOfThreads();
  vtkDataArray* array = input->GetPointData()->GetArray(arrayName.c_str());
  run.components = array ? array->GetNumberOfComponents() : 0;
  run.totalSeconds = elapsed.count();
  run.flowSeconds = filter->GetLastFlowSeconds();
  run.advectionSeconds = filter->GetLastAdvectionSeconds();
  run.traceSteps = filter->GetLastTraceSteps();
  return run;
}

/// The --timings report: one JSON object on one line.
std::string TimingsJson(const std::string& command, vtkImageData* image, const FilterRun& run)
{
  int dims[3];
  image->GetDimensions(dims);
  std::ostringstream json;
  json << std::setprecision(9);
  json << "{\"command\":\"" << command << "\""
       << ",\"dimensions\":[" << dims[0] << "," << dims[1] << "," << dims[2] << "]"
       << ",\"samples\":" << image->GetNumberOfPoints() << ",\"components\":" << run.components
       << ",\"time\":" << run.time << ",\"flow_mode\":\""
       << ChoiceName(run.flowMode, FlowModeChoices()) << "\""
       << ",\"threads\":" << run.threads << ",\"flow\":" << run.flowSeconds
       << ",\"advection\":" << run.advectionSeconds << ",\"total\":" << run.totalSeconds
       << ",\"trace_steps\":" << run.traceSteps << "}";
  return json.str();
}

// =============================================================================
// The "image" command
// =============================================================================

struct ImageSettings
{
  ShockOptions shock;
  std::string arrayName;
  bool timings = false;
};

std::vector<OptionSpec> ImageOptionSpecs(ImageSettings& settings)
{
  std::vector<OptionSpec> specs = ShockOptionSpecs(settings.shock, ShockOptionSet::All);
  specs.push_back({ "--array", "NAME", "point array to filter (default: active point scalars)",
    [&settings](const std::string& v)
    {
      if (v.empty())
      {
        throw CliError("--array: the name is empty");
      }
      settings.arrayName = v;
    } });
  specs.push_back({ "--timings", "", "print the run times as one JSON object on stdout",
    [&settings](const std::string&) { settings.timings = true; } });
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
          "  --timings prints {\"command\",\"dimensions\",\"samples\",\"components\",\"time\",\n"
          "  \"flow_mode\",\"threads\",\"flow\",\"advection\",\"total\",\"trace_steps\"} on stdout;\n"
          "  times in seconds, total = wall time of the filter only (no reading/writing).\n"
          "  Options:\n"
       << FormatOptions(ImageOptionSpecs(unused));
  return text.str();
}

int RunImageCommand(const std::vector<std::string>& args)
{
  if (IsHelpRequest(args))
  {
    std::cout << ImageHelp();
    return 0;
  }
  ImageSettings settings;
  const std::vector<std::string> positionals = ParseArguments("image", args, ImageOptionSpecs(settings));
  if (positionals.size() != 2)
  {
    throw CliError("image: expected INPUT and OUTPUT, got " + std::to_string(positionals.size()) +
      " argument(s) (see '" + ProgramName + " image --help')");
  }
  const std::string& inputPath = positionals[0];
  const std::string& outputPath = positionals[1];
  FormatOfPath(inputPath, "input");
  const FormatInfo& outputFormat = FormatOfPath(outputPath, "output"); // before the work
  RequireOutputDirectory(outputPath);

  vtkSmartPointer<vtkImageData> input = ReadImage(inputPath);
  const std::string arrayName = SelectPointArray(input, settings.arrayName);
  RequireStorable(input, arrayName, outputFormat, outputPath);
  const FilterRun run = RunImageFilter(input, arrayName, settings.shock);
  WriteImage(run.output, outputPath, arrayName);

  if (settings.timings)
  {
    std::cout << TimingsJson("image", input, run) << std::endl;
  }
  std::cerr << "image: " << DimensionsText(input) << ", " << run.components << " component(s) of '"
            << arrayName << "', t=" << NumberText(run.time) << ": " << std::fixed
            << std::setprecision(3) << run.totalSeconds << " s -> " << outputPath << '\n';
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
void RunPictureDemo(const std::filesystem::path& directory, const ShockOptions& common)
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

struct DemoSettings
{
  ShockOptions shock;
};

std::vector<OptionSpec> DemoOptionSpecs(DemoSettings& settings)
{
  return ShockOptionSpecs(settings.shock, ShockOptionSet::ThreadsOnly);
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
          "  Fixed flow, other parameters at their defaults. Prints on stderr what it\n"
          "  wrote, the run times and a sharpness figure per t.\n"
          "  Options:\n"
       << FormatOptions(DemoOptionSpecs(unused));
  return text.str();
}

int RunDemoCommand(const std::vector<std::string>& args)
{
  if (IsHelpRequest(args))
  {
    std::cout << DemoHelp();
    return 0;
  }
  DemoSettings settings;
  const std::vector<std::string> positionals = ParseArguments("demo", args, DemoOptionSpecs(settings));
  if (positionals.size() != 1)
  {
    throw CliError("demo: expected OUTDIR, got " + std::to_string(positionals.size()) +
      " argument(s) (see '" + ProgramName + " demo --help')");
  }
  const std::filesystem::path directory = positionals[0];
  CreateDirectory(directory);
  RunPictureDemo(directory, settings.shock);
  RunVolumeDemo(directory, settings.shock);
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
  return command->run(std::vector<std::string>(args.begin() + 1, args.end()));
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
