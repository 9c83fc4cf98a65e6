// firsttouch: the cost of touching fresh memory for the first time, the way the
// kernels get it (shock::AllocateLarge: 2 MiB aligned, advised for transparent
// huge pages) and with plain small pages, in milliseconds per run.
//
//   firsttouch MEBIBYTES huge|small
//
// Run it in fresh processes after some seconds idle and back to back (see
// Benchmarks/RESULTS.md, "Cold start"): on virtual machines whose balloon driver
// reports free pages to the host, the first touch of huge pages that the host
// took back costs far more than that of small pages.
#include "ShockTypes.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/mman.h>

int main(int argc, char* argv[])
{
  if (argc != 3 || (std::strcmp(argv[2], "huge") != 0 && std::strcmp(argv[2], "small") != 0))
  {
    std::fprintf(stderr, "usage: firsttouch MEBIBYTES huge|small\n");
    return 2;
  }
  const std::size_t bytes = std::strtoull(argv[1], nullptr, 10) << 20;
  const bool huge = std::strcmp(argv[2], "huge") == 0;
  const auto start = std::chrono::steady_clock::now();
  char* block = huge ? static_cast<char*>(shock::AllocateLarge(bytes))
                     : static_cast<char*>(mmap(nullptr, bytes, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
  if (!huge && block == MAP_FAILED)
  {
    std::fprintf(stderr, "firsttouch: cannot map %zu bytes\n", bytes);
    return 2;
  }
  for (std::size_t i = 0; i < bytes; i += 4096)
  {
    block[i] = 1;
  }
  const double ms =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s %s MiB: %.1f ms\n", argv[2], argv[1], ms);
  return 0;
}
