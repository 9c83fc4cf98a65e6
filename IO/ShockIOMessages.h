/**
 * @file   ShockIOMessages.h
 * @brief  The one trap for what VTK reports while a file is read or written
 *         (or a filter runs), so that a failure is told on one line.
 *
 * VTK prints its errors and warnings through a global output window (and
 * vtkLogger). A MessageTrap observes the algorithms it watches and, while it
 * lives, takes VTK's output window over and mutes vtkLogger's standard error
 * output; Finish() gives both back and turns what it caught into one line.
 * VTK's output window is global: not for concurrent use.
 */
#ifndef ShockIOMessages_h
#define ShockIOMessages_h

#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkSmartPointer.h"

#include <string>
#include <string_view>
#include <vector>

class vtkAlgorithm;
class vtkOutputWindow;

namespace shockio
{

/**
 * The message of a VTK error or warning on one line: without the first line
 * "ERROR: In <file>, line <n>" (or "Warning: ...", "Generic Warning: ..."), the
 * " (0x...)" address VTK adds after the class name and an executive's
 * " for request: <information dump>"; white space runs made single spaces.
 */
std::string CleanMessage(std::string_view text);

/// `text` quoted for a one-line message: at most 40 characters, non-printable ones as '?'.
std::string Quoted(std::string_view text);

/// What makes a call fail besides the errors of the watched objects.
enum class Strictness
{
  Lenient,          ///< only errors (observed, or through the output window)
  MessagesFail,     ///< also any message through the output window (the legacy readers' data errors)
  WarningsFail      ///< also the warnings of the watched objects (readers: data not as declared)
};

class MessageTrap : public vtkCommand
{
public:
  static MessageTrap* New() { return new MessageTrap; }

  void Execute(vtkObject* caller, unsigned long event, void* callData) override;

  /// Observes the errors and warnings of an object.
  void Watch(vtkObject* object);
  /// Observes an algorithm and its executive (whose errors only say that a request failed).
  void Watch(vtkAlgorithm* algorithm);

  /**
   * Gives VTK's output window back and tells whether nothing went wrong. Else
   * sets `error` to "<context>: <reason>", the reason being the first error,
   * else the first message of the output window, else the first warning
   * (vtkPLYReader only warns before it fails), else "VTK reported a failure". On success the warnings go on to the output window, where they would
   * have gone unobserved.
   */
  bool Finish(const std::string& context, std::string& error,
    Strictness strictness = Strictness::MessagesFail);

protected:
  MessageTrap();
  ~MessageTrap() override;

private:
  struct Message
  {
    bool error;
    std::string text;
  };
  class Window;
  void Restore();
  void Keep(bool error, const char* text);

  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkLogger::Verbosity LoggerVerbosity;
  vtkSmartPointer<Window> Unobserved;
  std::vector<Message> Printed; ///< through the output window
  std::string Error;
  std::vector<std::string> Warnings;
  bool RequestFailed = false;
};

} // namespace shockio

#endif
