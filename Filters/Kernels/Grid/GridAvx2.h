/**
 * @file GridAvx2.h
 * @brief The AVX2 build of the grid advection, chosen at run time.
 *
 * Only with the build option SHOCK_ENABLE_AVX2 (off by default: MachineChoices.h).
 * The library is built for the baseline x86-64. Where the processor has AVX2,
 * AdvectVertices runs a second build of its loop and of the image tracer,
 * made for AVX2 with function attributes (VEX encoding: fewer register
 * moves), and reads 8-bit images with 3 or 4 components a sample at a time
 * (CombineByteReadsAvx2). Neither build fuses multiply-adds and both do
 * the same operations in the same order, so the values are the same: the
 * tests compare the two builds bit for bit.
 */
#ifndef GridAvx2_h
#define GridAvx2_h

#include "MachineChoices.h"

#include <atomic>

#if SHOCK_ENABLE_AVX2 && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/// The grid advection has an AVX2 build (see UsesAvx2).
#define SHOCK_GRID_AVX2 1
/// Builds a function for AVX2 (without FMA, which would change the values).
#define SHOCK_TARGET_AVX2 __attribute__((target("avx2")))
#endif

namespace shock
{
namespace grid
{
namespace detail
{
inline std::atomic<bool> Avx2Allowed{ true };
}

/// Allows (the default) or forbids the AVX2 build, so that tests can compare
/// it with the portable one. Not while a run is on. It acts on the copy of the
/// kernels linked into the caller (the library's symbols are hidden: the VTK
/// module has its own, which follows the build option only).
inline void AllowAvx2(bool allow)
{
  detail::Avx2Allowed.store(allow);
}

/// True when the grid advection runs its AVX2 build: it was built
/// (SHOCK_ENABLE_AVX2), the processor has AVX2, and AllowAvx2 did not forbid it.
inline bool UsesAvx2()
{
#ifdef SHOCK_GRID_AVX2
  static const bool available = __builtin_cpu_supports("avx2");
  return available && detail::Avx2Allowed.load();
#else
  return false;
#endif
}

} // namespace grid
} // namespace shock

#endif
