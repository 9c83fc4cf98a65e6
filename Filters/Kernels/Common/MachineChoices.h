/**
 * @file MachineChoices.h
 * @brief The kernels' machine-dependent choices, in one place.
 *
 * Each one is a CMake option, compiled in, never read from the environment.
 * A choice is on by default only when it was measured to help on more than
 * one machine kind (Benchmarks/RESULTS.md, "Machine-dependent choices"):
 *
 *  - SHOCK_ENABLE_AVX2 (OFF): a second build of the image advection for AVX2,
 *    chosen at run time where the processor has AVX2 (GridAvx2.h). It gives
 *    the same values bit for bit. Its gain was within the noise on the one
 *    machine kind it was measured on.
 *  - SHOCK_HUGE_PAGES (OFF): large buffers are advised for transparent huge
 *    pages (AllocateLarge). This helps where the host leaves free huge pages
 *    backed, and costs several times more per page where a virtio balloon
 *    reports free pages to the host; on another kind it made no clear
 *    difference.
 *  - SHOCK_WIDEN_MPI_BINDING (ON): a process alone on its node under mpirun
 *    takes the node's cores back for its OpenMP threads (Open MPI binds a
 *    process to one core when it starts two or fewer). This corrects the
 *    launcher, not a processor: without it `mpirun -np 1` runs every thread on
 *    one core.
 */
#ifndef MachineChoices_h
#define MachineChoices_h

#ifndef SHOCK_ENABLE_AVX2
#define SHOCK_ENABLE_AVX2 0
#endif
#ifndef SHOCK_HUGE_PAGES
#define SHOCK_HUGE_PAGES 0
#endif
#ifndef SHOCK_WIDEN_MPI_BINDING
#define SHOCK_WIDEN_MPI_BINDING 1
#endif

namespace shock
{

/// Whether AllocateLarge advises transparent huge pages (SHOCK_HUGE_PAGES).
constexpr bool UseHugePages()
{
  return SHOCK_HUGE_PAGES != 0;
}

/**
 * When an MPI launcher says this is the only process on its node and bound it
 * to fewer cores than the node has, widen the affinity of the process's
 * threads to the whole node, once (SHOCK_WIDEN_MPI_BINDING). Called by
 * ResolveThreadCount; returns whether it widened.
 */
bool UseTheWholeNodeWhenAlone();

} // namespace shock

#endif
