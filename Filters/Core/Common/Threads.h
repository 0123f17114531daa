// How the core's parallel loops pick and name their threads (OpenMP when built with it, one
// thread otherwise). Plain C++17.
#ifndef pcbilateral_Threads_h
#define pcbilateral_Threads_h

namespace pcbilateral
{

/// The number of threads a parallel loop uses for a requested number (0: all cores; 1 without
/// OpenMP).
int ResolveThreadCount(int requested);

/// The hardware threads this process may run on (its CPU affinity; with OpenMP, as OpenMP counts
/// them), 0 when unknown. More threads than this give the same result, only more slowly.
int HardwareThreadCount();

/// The index of the calling thread inside a parallel region (0 outside one, or without OpenMP).
int CurrentThreadIndex();

} // namespace pcbilateral

#endif
