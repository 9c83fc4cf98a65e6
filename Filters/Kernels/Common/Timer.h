/**
 * @file Timer.h
 * @brief The wall clock of the kernels' reports (AdvectionReport and friends).
 */
#ifndef ShockTimer_h
#define ShockTimer_h

#include <chrono>

namespace shock
{

using Clock = std::chrono::steady_clock;

/// Seconds of wall time since `start`.
inline double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

} // namespace shock

#endif
