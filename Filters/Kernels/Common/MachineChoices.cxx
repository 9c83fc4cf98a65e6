#include "MachineChoices.h"

#include <omp.h>
#ifdef __linux__
#include <sched.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <cstdlib>

namespace shock
{

namespace
{
/// The processes an MPI launcher started on this node, or 0 when none says.
int LocalProcesses()
{
  for (const char* name : { "OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "MV2_COMM_WORLD_LOCAL_SIZE" })
  {
    if (const char* value = std::getenv(name))
    {
      return std::atoi(value);
    }
  }
  return 0;
}
}

bool UseTheWholeNodeWhenAlone()
{
  // Open MPI binds each process to one core when it starts two or fewer, so
  // `mpirun -np 1` would run every thread on one core. A process alone on its
  // node takes the node's cores back, once, for itself and its OpenMP threads
  // (the build option SHOCK_WIDEN_MPI_BINDING=OFF keeps the launcher's binding).
#ifndef __linux__
  return false; // the affinity calls below are Linux's
#else
  static const bool widened = []() {
    if (!SHOCK_WIDEN_MPI_BINDING || LocalProcesses() != 1)
    {
      return false;
    }
    cpu_set_t current;
    CPU_ZERO(&current);
    if (sched_getaffinity(0, sizeof(current), &current) != 0 ||
      CPU_COUNT(&current) >= sysconf(_SC_NPROCESSORS_ONLN))
    {
      return false;
    }
    cpu_set_t all;
    CPU_ZERO(&all);
    for (long cpu = 0; cpu < sysconf(_SC_NPROCESSORS_ONLN) && cpu < CPU_SETSIZE; ++cpu)
    {
      CPU_SET(cpu, &all);
    }
    if (sched_setaffinity(0, sizeof(all), &all) != 0)
    {
      return false;
    }
    // OpenMP threads made before keep the mask they were made with: widen theirs too
    // (as many as any later team may use).
    const int cores = std::max({ 1, CPU_COUNT(&all), omp_get_max_threads(), omp_get_num_procs() });
#pragma omp parallel num_threads(cores)
    {
      sched_setaffinity(0, sizeof(all), &all);
    }
    return true;
  }();
  return widened;
#endif
}

} // namespace shock
