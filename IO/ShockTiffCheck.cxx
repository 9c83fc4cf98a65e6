// The TIFF check with libtiff itself: every directory (page) of the file must
// read without an error. vtkTIFFReader does not look at what TIFFReadDirectory
// returns for the pages after the first, and reads scanlines of a directory
// libtiff refused (the fuzz search found one that ends in a division by zero
// inside libtiff).
#include "ShockImageChecks.h"

#include "vtk_tiff.h"

#include <cstdarg>
#include <cstdio>
#include <string>

namespace
{
/// The first error libtiff reported during a check (libtiff's handlers are global).
std::string& FirstTiffError()
{
  static std::string error;
  return error;
}

void RecordTiffError(const char* module, const char* format, va_list arguments)
{
  char text[512];
  std::vsnprintf(text, sizeof(text), format, arguments);
  if (FirstTiffError().empty())
  {
    FirstTiffError() = std::string(module ? module : "libtiff") + ": " + text;
  }
}

void IgnoreTiffWarning(const char*, const char*, va_list) {}
} // namespace

namespace shockio
{

bool CheckTiffDirectories(const std::string& path, std::uint64_t directories, std::string& problem)
{
  FirstTiffError().clear();
  const TIFFErrorHandler previousError = TIFFSetErrorHandler(RecordTiffError);
  const TIFFErrorHandler previousWarning = TIFFSetWarningHandler(IgnoreTiffWarning);
  std::uint64_t read = 0;
  if (TIFF* tiff = TIFFOpen(path.c_str(), "r"))
  {
    do
    {
      ++read;
    } while (FirstTiffError().empty() && read < directories && TIFFReadDirectory(tiff));
    TIFFClose(tiff);
  }
  TIFFSetErrorHandler(previousError);
  TIFFSetWarningHandler(previousWarning);
  if (!FirstTiffError().empty() || read != directories)
  {
    problem = "a damaged TIFF file (" +
      (FirstTiffError().empty() ? "libtiff reads " + std::to_string(read) + " of its " +
            std::to_string(directories) + " directories"
                                : FirstTiffError()) +
      ")";
    return false;
  }
  return true;
}

} // namespace shockio
