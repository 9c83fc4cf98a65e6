// Reads every seed of the fuzz targets (Testing/Fuzz/seeds/<format>/*, the
// inputs that once crashed them included) with the checks and readers of
// VTK::IOShock, in the regular test suite (and under the sanitizers):
//   ReplaySeeds SEEDS_DIR
// Exit 0 after all of them; a crash fails the test.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

void ReadAsFile(const std::string& extension, const std::uint8_t* data, std::size_t size);

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::cerr << "usage: ReplaySeeds SEEDS_DIR\n";
    return 2;
  }
  int count = 0;
  for (const auto& format : std::filesystem::directory_iterator(argv[1]))
  {
    for (const auto& seed : std::filesystem::directory_iterator(format.path()))
    {
      std::ifstream file(seed.path(), std::ios::binary);
      const std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
      ReadAsFile(format.path().filename().string(), reinterpret_cast<const std::uint8_t*>(bytes.data()),
        bytes.size());
      ++count;
    }
  }
  std::cout << "read " << count << " seeds without a crash\n";
  return count > 0 ? 0 : 1;
}
