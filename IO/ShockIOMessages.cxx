#include "ShockIOMessages.h"

#include "vtkAlgorithm.h"
#include "vtkExecutive.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"

#include <algorithm>
#include <cctype>

namespace shockio
{

std::string CleanMessage(std::string_view message)
{
  const size_t firstLineEnd = message.find('\n');
  if (firstLineEnd != std::string_view::npos &&
    message.substr(0, firstLineEnd).find(", line ") != std::string_view::npos)
  {
    message.remove_prefix(firstLineEnd + 1);
  }
  std::string text(message);
  // "<class> (0x55d0...): text" -> "<class>: text"
  for (size_t at = text.find(" (0x"); at != std::string::npos; at = text.find(" (0x", at))
  {
    const size_t close = text.find(')', at);
    if (close == std::string::npos)
    {
      break;
    }
    text.erase(at, close + 1 - at);
  }
  if (const size_t dump = text.find(" for request:"); dump != std::string::npos)
  {
    text.erase(dump);
  }
  std::string clean;
  for (const char c : text)
  {
    if (!std::isspace(static_cast<unsigned char>(c)))
    {
      clean += c;
    }
    else if (!clean.empty() && clean.back() != ' ')
    {
      clean += ' ';
    }
  }
  if (!clean.empty() && clean.back() == ' ')
  {
    clean.pop_back();
  }
  return clean;
}

std::string Quoted(std::string_view text)
{
  std::string quoted(text.substr(0, 40));
  std::replace_if(
    quoted.begin(), quoted.end(), [](unsigned char c) { return !std::isprint(c); }, '?');
  return "'" + quoted + (text.size() > 40 ? "...'" : "'");
}

/// The output window of a trap: hands every message to it instead of showing it.
class MessageTrap::Window : public vtkOutputWindow
{
public:
  static Window* New();
  vtkTypeMacro(Window, vtkOutputWindow);

  void DisplayText(const char* text) override { this->Trap->Keep(false, text); }
  void DisplayErrorText(const char* text) override { this->Trap->Keep(true, text); }
  void DisplayWarningText(const char* text) override { this->Trap->Keep(false, text); }
  void DisplayGenericWarningText(const char* text) override { this->Trap->Keep(false, text); }
  void DisplayDebugText(const char*) override {}

  MessageTrap* Trap = nullptr;
};
vtkStandardNewMacro(MessageTrap::Window);

MessageTrap::MessageTrap()
  : Previous(vtkOutputWindow::GetInstance())
  , LoggerVerbosity(vtkLogger::GetCurrentVerbosityCutoff())
  , Unobserved(vtkSmartPointer<Window>::New())
{
  this->Unobserved->Trap = this;
  vtkOutputWindow::SetInstance(this->Unobserved);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

MessageTrap::~MessageTrap()
{
  this->Restore();
}

void MessageTrap::Restore()
{
  if (this->Previous)
  {
    vtkOutputWindow::SetInstance(this->Previous);
    vtkLogger::SetStderrVerbosity(this->LoggerVerbosity);
    this->Previous = nullptr;
  }
}

void MessageTrap::Keep(bool error, const char* text)
{
  this->Printed.push_back({ error, text ? text : "" });
}

void MessageTrap::Execute(vtkObject* caller, unsigned long event, void* callData)
{
  const char* text = static_cast<const char*>(callData);
  if (event == vtkCommand::WarningEvent)
  {
    this->Warnings.emplace_back(text ? text : "");
  }
  else if (vtkExecutive::SafeDownCast(caller))
  {
    this->RequestFailed = true;
  }
  else if (this->Error.empty())
  {
    this->Error = CleanMessage(text ? text : "");
    this->Error = this->Error.empty() ? "unknown VTK error" : this->Error;
  }
}

void MessageTrap::Watch(vtkObject* object)
{
  object->AddObserver(vtkCommand::ErrorEvent, this);
  object->AddObserver(vtkCommand::WarningEvent, this);
}

void MessageTrap::Watch(vtkAlgorithm* algorithm)
{
  this->Watch(static_cast<vtkObject*>(algorithm));
  this->Watch(static_cast<vtkObject*>(algorithm->GetExecutive()));
}

bool MessageTrap::Finish(const std::string& context, std::string& error, Strictness strictness)
{
  this->Restore();
  const auto printedError = std::find_if(
    this->Printed.begin(), this->Printed.end(), [](const Message& m) { return m.error; });
  const bool failed = !this->Error.empty() || this->RequestFailed ||
    printedError != this->Printed.end() ||
    (strictness != Strictness::Lenient && !this->Printed.empty()) ||
    (strictness == Strictness::WarningsFail && !this->Warnings.empty());
  if (!failed)
  {
    for (const Message& message : this->Printed)
    {
      vtkOutputWindowDisplayWarningText(message.text.c_str());
    }
    for (const std::string& warning : this->Warnings)
    {
      vtkOutputWindowDisplayWarningText(warning.c_str());
    }
    return true;
  }
  std::string reason = this->Error;
  if (reason.empty() && !this->Printed.empty())
  {
    reason = CleanMessage(
      (printedError != this->Printed.end() ? *printedError : this->Printed.front()).text);
  }
  if (reason.empty() && !this->Warnings.empty())
  {
    reason = CleanMessage(this->Warnings.front());
  }
  // "vtkClass: Shock filter failed: x" under the context "shock filter failed"
  // says it once: "Shock filter failed: x".
  const size_t colon = reason.find(": ");
  if (reason.rfind("vtk", 0) == 0 && colon != std::string::npos && reason.find(' ') > colon)
  {
    std::string body = reason.substr(colon + 2);
    std::string lower = body;
    std::string lowerContext = context;
    for (std::string* text : { &lower, &lowerContext })
    {
      std::transform(text->begin(), text->end(), text->begin(), [](unsigned char c) { return std::tolower(c); });
    }
    if (!context.empty() && lower.rfind(lowerContext, 0) == 0)
    {
      error = body;
      return false;
    }
  }
  error = context + ": " + (reason.empty() ? "VTK reported a failure" : reason);
  return false;
}

} // namespace shockio
