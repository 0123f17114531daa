#include "Threads.h"

#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcbilateral
{

int ResolveThreadCount(int requested)
{
#ifdef _OPENMP
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

int HardwareThreadCount()
{
#ifdef _OPENMP
  return omp_get_num_procs();
#else
  return static_cast<int>(std::thread::hardware_concurrency());
#endif
}

int CurrentThreadIndex()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

} // namespace pcbilateral
