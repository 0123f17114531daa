// The phases of a read-filter-write run that the abort tools (pcb_abort_latency, pcb_abort_gaps)
// report on, in the order a run goes through them.
#ifndef pcbilateral_AbortPhaseNames_h
#define pcbilateral_AbortPhaseNames_h

namespace pcbilateral_testing
{

enum PhaseIndex
{
  Reading,
  Measuring,
  Octree,
  Kernel,
  Output,
  Writing,
  NumberOfPhases
};

constexpr const char* PhaseNames[NumberOfPhases] = { "reading",
  "measuring",
  "octree",
  "kernel",
  "output",
  "writing" };

} // namespace pcbilateral_testing

#endif
