/**
 * @file   main.cxx
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
 * A subcommand is a function of its arguments and a help text (Commands.h;
 * one file each); its options are an OptionSpec list parsed by
 * ParseCommandLine() (CliOptions.h), and the parameters shared by every shock
 * filter are ShockOptions (CliFilters.h). Files are read and written by the
 * IO library VTK::IOShock (CliFiles.h).
 *
 * Errors print exactly one line "shockfilter: <message>" on stderr and exit
 * with code 2. The errors and warnings of VTK objects are caught by a
 * shockio::MessageTrap instead of being printed; the first error is folded into
 * that line, warnings become "shockfilter: warning: ..." lines (the output
 * window InstallPrintingOutputWindow() sets). An allocation failure names the
 * memory the input needs (see the help of each command).
 */

#include "CliSupport.h"
#include "CliOptions.h"
#include "Commands.h"

#include "vtkVersion.h"

#include <csignal>
#include <iomanip>
#include <iostream>
#include <new>
#include <sstream>
#include <string>
#include <vector>

namespace shockcli
{
namespace
{

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
          "       shockfilter --help | --version | COMMAND --help\n"
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
  if (args[0] == "--version")
  {
    std::cout << ProgramName << " " << SHOCKFILTERS_VERSION << " (ShockFilters; VTK "
              << vtkVersion::GetVTKVersion() << ")\n";
    return 0;
  }
  const Command* command = FindCommand(args[0]);
  if (!command)
  {
    std::vector<std::string> names;
    std::string list;
    for (const Command& known : Commands())
    {
      names.emplace_back(known.name);
      list += (list.empty() ? "" : ", ") + std::string(known.name);
    }
    std::string hint = Suggestion(args[0], names);
    if (hint.empty() && args[0].rfind("--", 0) == 0)
    {
      hint = Suggestion(args[0], { "--help", "--version" });
    }
    throw CliError("unknown command '" + args[0] + "'" + hint + " (commands: " + list + "; see '" +
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
} // namespace shockcli

int main(int argc, char* argv[])
{
  using namespace shockcli;
  // A write beyond the file size limit (ulimit -f) then fails with EFBIG, as on
  // a full disk, instead of killing the program: the target stays untouched.
  std::signal(SIGXFSZ, SIG_IGN);
  InstallPrintingOutputWindow();
  try
  {
    return Dispatch(std::vector<std::string>(argv + 1, argv + argc));
  }
  catch (const CliError& error)
  {
    std::cerr << ProgramName << ": " << SingleLine(error.what()) << '\n';
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << ProgramName << ": out of memory (see 'shockfilter COMMAND --help' for the memory "
              << "each sample needs; try a smaller input or --threads 1)\n";
  }
  catch (const std::exception& error)
  {
    std::cerr << ProgramName << ": internal error: " << SingleLine(error.what()) << '\n';
  }
  return ExitError;
}
