/**
 * @file   Commands.h
 * @brief  The subcommands of shockfilter: each a help text and an entry point
 *         taking the arguments after the command name (main.cxx dispatches).
 */
#ifndef Commands_h
#define Commands_h

#include <string>
#include <vector>

namespace shockcli
{

std::string ImageHelp();
int RunImageCommand(const std::vector<std::string>& args);

std::string SurfaceHelp();
int RunSurfaceCommand(const std::vector<std::string>& args);

std::string SharpenHelp();
int RunSharpenCommand(const std::vector<std::string>& args);

std::string DemoHelp();
int RunDemoCommand(const std::vector<std::string>& args);

} // namespace shockcli

#endif
