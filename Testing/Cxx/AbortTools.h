// What the abort tools (pcb_abort_latency, pcb_abort_gaps) share: the phases of a
// read-filter-write run they report on, in the order a run goes through them, and a way to call
// a function on an algorithm's events.
#ifndef pcbilateral_AbortTools_h
#define pcbilateral_AbortTools_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkNew.h"

#include <functional>

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

/// Calls `what` on the algorithm's `event` (the callback command owns nothing: `what` must
/// outlive the observation).
inline void Observe(vtkAlgorithm* algorithm, unsigned long event, std::function<void()>* what)
{
  vtkNew<vtkCallbackCommand> command;
  command->SetClientData(what);
  command->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { (*static_cast<std::function<void()>*>(data))(); });
  algorithm->AddObserver(event, command);
}

} // namespace pcbilateral_testing

#endif
