#include "CliSupport.h"

#include "ShockIOMessages.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"

#include <algorithm>
#include <cctype>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace shockcli
{

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

namespace
{

/**
 * VTK's output window, replaced: prints what reaches it (the warnings of a
 * successful call that a MessageTrap hands on, generic warnings) as one line
 * "shockfilter: warning: <message>" each.
 */
class PrintingOutputWindow : public vtkOutputWindow
{
public:
  static PrintingOutputWindow* New();
  vtkTypeMacro(PrintingOutputWindow, vtkOutputWindow);

  void DisplayText(const char* text) override
  {
    const std::string line = shockio::CleanMessage(text ? text : "");
    if (!line.empty())
    {
      std::cerr << ProgramName << ": warning: " << line << '\n';
    }
  }
  void DisplayDebugText(const char*) override {}
};
vtkStandardNewMacro(PrintingOutputWindow);

} // namespace

void InstallPrintingOutputWindow()
{
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // the logger would print them too
  vtkNew<PrintingOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
}

} // namespace shockcli
