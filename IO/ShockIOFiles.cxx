#include "ShockIOFiles.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace shockio
{
namespace fs = std::filesystem;

bool CheckReadable(const std::string& path, std::string& error)
{
  std::error_code code;
  const fs::file_status status = fs::status(path, code);
  if (!fs::exists(status))
  {
    error = path + ": no such file";
  }
  else if (fs::is_directory(status))
  {
    error = path + ": is a directory, not a file";
  }
  else if (!fs::is_regular_file(status))
  {
    error = path + ": not a regular file";
  }
  else if (!std::ifstream(path, std::ios::binary))
  {
    error = path + ": cannot be opened for reading";
  }
  else if (fs::file_size(path, code) == 0)
  {
    error = path + ": the file is empty";
  }
  else
  {
    return true;
  }
  return false;
}

bool CheckWritable(const std::string& path, std::string& error)
{
  const fs::path parent = fs::path(path).parent_path();
  std::error_code code;
  if (!parent.empty() && !fs::is_directory(parent, code))
  {
    error = path + ": cannot write, directory '" + parent.string() + "' does not exist";
    return false;
  }
  const fs::file_status status = fs::status(path, code);
  if (fs::is_directory(status))
  {
    error = path + ": cannot write, it is a directory";
    return false;
  }
  if (fs::exists(status) && !fs::is_regular_file(status))
  {
    // A device such as /dev/full: it cannot be replaced by a complete file.
    error = path + ": cannot write, it is not a regular file";
    return false;
  }
  return true;
}

std::string LowerExtension(const std::string& path)
{
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool ReadFile(const std::string& path, std::string& text, std::string& error)
{
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = file ? static_cast<std::streamoff>(file.tellg()) : -1;
  if (size >= 0)
  {
    text.resize(static_cast<size_t>(size));
    file.seekg(0);
    file.read(text.data(), size);
  }
  if (size < 0 || !file)
  {
    error = path + ": reading failed";
    return false;
  }
  return true;
}

OutputFile::OutputFile(std::string target)
  : Target(std::move(target))
{
}

OutputFile::~OutputFile()
{
  if (!this->Committed && !this->Temporary.empty())
  {
    std::error_code code;
    fs::remove(this->Temporary, code);
  }
}

bool OutputFile::Open(std::string& error)
{
  static std::atomic<unsigned> counter{ 0 };
  const fs::path target(this->Target);
  const fs::path directory = target.parent_path();
  for (int attempt = 0; attempt < 100; ++attempt)
  {
    const std::string tail = ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
      LowerExtension(this->Target);
    // The target's name, shortened when the whole would pass the file system's
    // limit on a name (255 bytes): a legal target name never fails for its
    // temporary file.
    std::string stem = target.filename().string();
    const size_t room = 255 - std::min<size_t>(255, 1 + tail.size());
    stem = stem.size() > room ? stem.substr(0, room) : stem;
    const std::string name = "." + stem + tail;
    const std::string candidate = (directory / name).string();
    const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd >= 0)
    {
      ::close(fd);
      this->Temporary = candidate;
      return true;
    }
    if (errno != EEXIST)
    {
      error = this->Target + ": cannot write: " + std::strerror(errno);
      return false;
    }
  }
  error = this->Target + ": cannot write: no free temporary file name";
  return false;
}

bool OutputFile::Commit(std::string& error)
{
  // The data must be on disk before the rename makes it the target.
  const int fd = ::open(this->Temporary.c_str(), O_RDONLY);
  const bool synced = fd >= 0 && ::fsync(fd) == 0;
  if (fd >= 0)
  {
    ::close(fd);
  }
  std::error_code code;
  if (!synced)
  {
    error = this->Target + ": writing failed (is the disk full?)";
    return false;
  }
  fs::rename(this->Temporary, this->Target, code);
  if (code)
  {
    error = this->Target + ": cannot write: " + code.message();
    return false;
  }
  this->Committed = true;
  return true;
}

bool WriteFile(const std::string& path, const std::string& text, std::string& error)
{
  OutputFile output(path);
  if (!output.Open(error))
  {
    return false;
  }
  std::ofstream file(output.Path(), std::ios::binary | std::ios::trunc);
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  file.close();
  if (!file)
  {
    error = path + ": writing failed (is the disk full?)";
    return false;
  }
  return output.Commit(error);
}

} // namespace shockio
