// The clocks of the benchmarks (pcb_benchmark, pcb_quality, pcb_edges).
#ifndef pcbilateral_benchmark_BenchmarkTiming_h
#define pcbilateral_benchmark_BenchmarkTiming_h

#include <chrono>

#include <sys/resource.h>

namespace pcbilateral_benchmark
{

/// Elapsed seconds since start.
inline double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// User and system time of this process so far, all threads: on a machine shared with other
/// work, it grows less than the elapsed time does when the cores are taken by others.
inline double CpuSeconds()
{
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

} // namespace pcbilateral_benchmark

#endif
