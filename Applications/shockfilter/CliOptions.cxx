#include "CliOptions.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace shockcli
{

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

/// The number of single-character edits (insert, delete, replace, swap two
/// neighbours) between `a` and `b` (the optimal string alignment distance).
std::size_t EditDistance(const std::string& a, const std::string& b)
{
  const std::size_t width = b.size() + 1;
  std::vector<std::size_t> d((a.size() + 1) * width);
  for (std::size_t i = 0; i <= a.size(); ++i)
  {
    for (std::size_t j = 0; j <= b.size(); ++j)
    {
      std::size_t& here = d[i * width + j];
      if (i == 0 || j == 0)
      {
        here = i + j;
        continue;
      }
      here = std::min({ d[(i - 1) * width + j] + 1, d[i * width + j - 1] + 1,
        d[(i - 1) * width + j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1) });
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
      {
        here = std::min(here, d[(i - 2) * width + j - 2] + 1);
      }
    }
  }
  return d.back();
}

std::string Suggestion(const std::string& typed, const std::vector<std::string>& known)
{
  std::string best;
  std::size_t bestDistance = 0;
  for (const std::string& name : known)
  {
    // A prefix of one name (e.g. "--tim" for "--time") or a few typing slips.
    const bool prefix = typed.size() >= 3 && name.compare(0, typed.size(), typed) == 0;
    const std::size_t distance = prefix ? 0 : EditDistance(typed, name);
    if ((prefix || distance <= std::max<std::size_t>(1, name.size() / 4)) &&
      (best.empty() || distance < bestDistance))
    {
      best = name;
      bestDistance = distance;
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
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
      std::vector<std::string> names;
      for (const OptionSpec& known : options)
      {
        names.push_back(known.name);
      }
      const std::string hint = Suggestion(name, names);
      throw CliError(command + ": unknown option '" + name + "'" +
        (hint.empty() ? std::string(" (see '") + ProgramName + " " + command + " --help')" : hint));
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

/// A choice name as compared: lower case, without spaces, hyphens or underscores
/// ("Face Crossing", "face-crossing" and "FACE_CROSSING" are one name).
std::string ChoiceKey(const std::string& text)
{
  std::string key;
  for (char c : ToLower(text))
  {
    if (c != ' ' && c != '-' && c != '_')
    {
      key += c;
    }
  }
  return key;
}

/**
 * Returns the value of the choice named 'text' (the ParaView names, in any case,
 * with spaces, hyphens or underscores); throws on an unknown name, suggesting the
 * closest one. Choices after the first with the same value are older spellings,
 * accepted but not listed.
 */
int ParseChoice(const std::string& option, const std::string& text, const std::vector<Choice>& choices)
{
  const std::string wanted = ChoiceKey(text);
  std::string names;
  std::vector<std::string> listed;
  for (const Choice& choice : choices)
  {
    if (wanted == ChoiceKey(choice.first))
    {
      return choice.second;
    }
    if (ChoiceName(choice.second, choices) == choice.first)
    {
      names += (names.empty() ? "" : "|") + std::string(choice.first);
    }
    listed.push_back(choice.first);
  }
  const std::string hint = Suggestion(ToLower(text), listed);
  throw CliError(option + ": unknown value '" + text + "'" + (hint.empty() ? "" : hint) + " (expected " +
    names + ")");
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

/// " (default <value>)", for option help lines.
std::string DefaultText(const std::string& value)
{
  return " (default " + value + ")";
}

std::string RangeText(double low, double high)
{
  return NumberText(low) + ".." + NumberText(high);
}

OptionSpec ChoiceOptionSpec(const std::string& name, const std::string& valueName, const std::string& text,
  std::optional<int>& target, const std::vector<Choice>& choices, int defaultValue)
{
  return { name, valueName, text + DefaultText(ChoiceName(defaultValue, choices)),
    [name, &target, &choices](const std::string& v) { target = ParseChoice(name, v, choices); } };
}

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

} // namespace shockcli
