// The file checks and readers of VTK::IOShock on one input: it is written as a
// file with the given extension and read the way shockfilter reads it (the
// checks, then VTK's reader when they pass). With SHOCK_FUZZ_EXTENSION, a
// libFuzzer target for that format (Testing/Fuzz/CMakeLists.txt; run by
// scripts/test.sh from the seeds in Testing/Fuzz/seeds/<format>, where every
// input that ever crashed a target stays, named crash-*); without, the
// function ReplaySeeds.cxx calls on every seed in the regular test suite.
#include "ShockIOFiles.h"
#include "ShockImageChecks.h"
#include "ShockImageIO.h"
#include "ShockMeshIO.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace
{
/// A small limit keeps each run fast; the limit itself is checked like any other.
constexpr std::uint64_t FuzzMaxSamples = 1 << 20;

/**
 * The scratch file of this process for inputs of `extension`. Its name has
 * the same length in every process (the process id in 10 digits): messages
 * that contain it then take the same code paths, and a search with a fixed
 * seed finds the same inputs on every run.
 */
std::string InputPath(const std::string& extension)
{
  const char* directory = std::getenv("TMPDIR");
  char id[16];
  std::snprintf(id, sizeof(id), "%010ld", static_cast<long>(::getpid()));
  return std::string(directory ? directory : "/tmp") + "/shockfuzz-" + id + "." + extension;
}
} // namespace

/// Reads `data` as a file of `extension` (png, off, ...) with the checks and readers of VTK::IOShock.
void ReadAsFile(const std::string& extension, const std::uint8_t* data, std::size_t size)
{
  const std::string path = InputPath(extension);
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::string error;
  bool image = false;
  for (const shockio::ImageFormat& format : shockio::ImageFormats())
  {
    for (const std::string& candidate : format.extensions)
    {
      image = image || candidate == extension;
    }
  }
  if (image)
  {
    if (extension == "png")
    {
      // The whole-file check in memory as well, without a file in between.
      shockio::ImageHeader header;
      shockio::CheckPng(std::string(reinterpret_cast<const char*>(data), size), header, FuzzMaxSamples, error);
    }
    shockio::ReadImage(path, FuzzMaxSamples, error);
  }
  else
  {
    shockio::ReadMesh(path, error, FuzzMaxSamples);
  }
  std::remove(path.c_str());
}

#ifdef SHOCK_FUZZ_EXTENSION
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  ReadAsFile(SHOCK_FUZZ_EXTENSION, data, size);
  return 0;
}
#endif
