/**
 * @file BenchmarkSupport.h
 * What the benchmark programs (shockbench, meshbench) share: the wall clock,
 * facts about the machine read from /proc, the CPU time other processes use
 * during a run (to discard disturbed runs), and number formatting for the
 * Markdown tables. Header-only, VTK-free, Linux (/proc, getrusage).
 */
#ifndef ShockBenchmarkSupport_h
#define ShockBenchmarkSupport_h

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

namespace shockbench
{

/// Monotonic wall clock in seconds (differences only).
inline double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The value after "key:" on the first line of 'file' starting with 'key', or "unknown"
/// (e.g. ProcField("/proc/cpuinfo", "model name")).
inline std::string ProcField(const char* file, const std::string& key)
{
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
  {
    if (line.rfind(key, 0) == 0 && line.find(':') != std::string::npos)
    {
      std::string value = line.substr(line.find(':') + 1);
      value.erase(0, value.find_first_not_of(" \t"));
      return value;
    }
  }
  return "unknown";
}

/// The 1-minute load average.
inline double LoadAverage1()
{
  std::ifstream in("/proc/loadavg");
  double load = 0.0;
  in >> load;
  return load;
}

/// The 1-, 5- and 15-minute load averages as "a, b, c".
inline std::string LoadAverages()
{
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + ", " + b + ", " + c;
}

/// Hardware threads of the machine, at least 1.
inline int HardwareThreads()
{
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/// CPU seconds used by the whole machine (busy time in /proc/stat) and by this process.
struct CpuClock
{
  double machine = 0.0;
  double self = 0.0;

  static CpuClock Read()
  {
    CpuClock clock;
    std::ifstream in("/proc/stat");
    std::string cpu;
    unsigned long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0,
                       steal = 0;
    in >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
    static const double tick = static_cast<double>(sysconf(_SC_CLK_TCK));
    clock.machine = static_cast<double>(user + nice + system + irq + softirq + steal) / tick;
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    clock.self = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
      1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    return clock;
  }

  /// CPU seconds other processes used since 'start'.
  double OthersSince(const CpuClock& start) const
  {
    return std::max(0.0, (this->machine - start.machine) - (this->self - start.self));
  }
};

/// 'value' with 'digits' decimals.
inline std::string Fixed(double value, int digits)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", digits, value);
  return text;
}

/// Seconds with about 3 significant digits.
inline std::string Seconds(double value)
{
  return value < 1.0 ? Fixed(value, 3) : (value < 100.0 ? Fixed(value, 2) : Fixed(value, 1));
}

/// A count in short form: 1234567 -> "1.23M", 12345 -> "12.3K", 999 -> "999".
inline std::string Count(double value)
{
  if (value >= 1e9)
  {
    return Fixed(value / 1e9, 2) + "G";
  }
  if (value >= 1e6)
  {
    return Fixed(value / 1e6, 2) + "M";
  }
  if (value >= 1e4)
  {
    return Fixed(value / 1e3, 1) + "K";
  }
  return Fixed(value, 0);
}

} // namespace shockbench

#endif
