// libFuzzer target of the file checks and readers of VTK::IOShock: each fuzzed
// input is written as a file with the extension SHOCK_FUZZ_EXTENSION and read
// the way shockfilter reads it (the checks, then VTK's reader when they pass).
// Built once per format (Testing/Fuzz/CMakeLists.txt); run by scripts/test.sh
// from the seeds in Testing/Fuzz/seeds/<format>, where every input that ever
// crashed a target stays as a regression test (files named crash-*).
#include "ShockIOFiles.h"
#include "ShockImageChecks.h"
#include "ShockImageIO.h"
#include "ShockMeshIO.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

namespace
{
/// A small limit keeps each run fast; the limit itself is checked like any other.
constexpr std::uint64_t FuzzMaxSamples = 1 << 20;

const std::string& InputPath()
{
  static const std::string path = [] {
    const char* directory = std::getenv("TMPDIR");
    return std::string(directory ? directory : "/tmp") + "/shockfuzz-" + std::to_string(::getpid()) +
      "." SHOCK_FUZZ_EXTENSION;
  }();
  return path;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  {
    std::ofstream file(InputPath(), std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::string error;
  const std::string extension = SHOCK_FUZZ_EXTENSION;
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
    shockio::ReadImage(InputPath(), FuzzMaxSamples, error);
  }
  else
  {
    shockio::ReadMesh(InputPath(), error, FuzzMaxSamples);
  }
  return 0;
}
