// Files for the tests of the IO library (VTK::IOShock): paths in the build
// tree's test directory (SHOCK_IO_TEST_DIR), and a file size limit that makes
// writes fail as a full disk would.
#ifndef IOTestSupport_h
#define IOTestSupport_h

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <sys/resource.h>

namespace shocktest
{

/// A path for this test's file `name` in the test directory of the build tree.
inline std::string TempPath(const std::string& name)
{
  const std::filesystem::path directory(SHOCK_IO_TEST_DIR);
  std::filesystem::create_directories(directory);
  const auto* test = testing::UnitTest::GetInstance()->current_test_info();
  return (directory / (std::string(test->test_suite_name()) + "." + test->name() + "." + name))
    .string();
}

/// Writes `text` to a new file `name` and returns its path.
inline std::string TextFile(const std::string& name, const std::string& text)
{
  const std::string path = TempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// The bytes of a file ("" if it cannot be read).
inline std::string FileBytes(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

/**
 * The temporary files (".TARGET.partial-...") that a write of `target` left beside
 * it. Only that target's: tests running at the same time write other files into
 * the same folder.
 */
inline std::vector<std::string> PartialFiles(const std::string& target)
{
  const std::filesystem::path path(target);
  const std::string prefix = "." + path.filename().string() + ".partial-";
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path()))
  {
    if (entry.path().filename().string().rfind(prefix, 0) == 0)
    {
      names.push_back(entry.path().filename().string());
    }
  }
  return names;
}

/**
 * While it lives, no file of this process grows beyond `bytes`: a write beyond
 * fails (EFBIG; SIGXFSZ ignored) as on a full disk.
 */
class FileSizeLimit
{
public:
  explicit FileSizeLimit(rlim_t bytes)
  {
    getrlimit(RLIMIT_FSIZE, &this->Previous);
    this->PreviousHandler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = this->Previous;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit()
  {
    setrlimit(RLIMIT_FSIZE, &this->Previous);
    std::signal(SIGXFSZ, this->PreviousHandler);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
  rlimit Previous{};
  void (*PreviousHandler)(int) = nullptr;
};

} // namespace shocktest

#endif
