// The octree, scheduler and per-point state of one run's points (BilateralFilter.cxx's engine).
#ifndef pcbilateral_IterationEngine_h
#define pcbilateral_IterationEngine_h

#include "BilateralKernel.h"
#include "CellColoringScheduler.h"
#include "PointCloudView.h"
#include "PointState.h"
#include "ProcessingOctree.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace pcbilateral
{

/**
 * The octree, the scheduler and the per-point state of the points being filtered: a whole
 * cloud for all its iterations, or one part and its ghosts for one iteration.
 */
class IterationEngine
{
public:
  /// The points' positions (the last `ghosts` of them ghosts), by id, are `positions`, or the
  /// state's when that is null.
  IterationEngine(PointState state,
    const double* positions,
    const CloudExtent& extent,
    double radius,
    double normalRadius,
    bool removeIsolatedPoints,
    int threads,
    const std::function<bool()>& shouldAbort)
    : Octree(extent.Min, extent.Max, radius)
    , Scheduler(this->Octree,
        KernelConstants(radius, normalRadius),
        radius,
        removeIsolatedPoints,
        threads)
    , State(std::move(state))
    , Threads(threads)
  {
    this->Loaded = this->Octree.Load(positions ? positions : this->State.Positions.data(),
      this->State.Removed.size(),
      threads,
      shouldAbort);
  }

  ProcessingOctree Octree;
  CellColoringScheduler Scheduler;
  PointState State;
  int Threads;
  /// Whether an iteration has placed the points since the octree's last layout (Load makes the
  /// first one).
  bool PointsPlaced = false;
  /// False when the run was aborted while the octree was built: the engine cannot iterate.
  bool Loaded = false;

  /// Writes the points' last moves from the octree's layout back to their ids; false if `stop`
  /// said stop.
  bool ScatterMoves(const std::function<bool()>& stop = nullptr)
  {
    const std::uint32_t* ids = this->Octree.GetIds();
    const double* moved[3] = {
      this->Octree.GetMovedX(), this->Octree.GetMovedY(), this->Octree.GetMovedZ()
    };
    const auto count = static_cast<std::int64_t>(this->Octree.GetNumberOfPoints());
    std::vector<double>& positions = this->State.Positions;
    const std::vector<std::uint8_t>& removed = this->State.Removed;
    // A million points at a time, `stop` asked before each (20 million points' moves took 0.09
    // to 0.17 s of a busy machine): stopped, the positions are moved in part.
    constexpr std::int64_t Block = std::int64_t(1) << 20;
    for (std::int64_t first = 0; first < count; first += Block)
    {
      if (stop && stop())
      {
        return false;
      }
      const std::int64_t end = std::min(count, first + Block);
#pragma omp parallel for schedule(static) num_threads(this->Threads)
      for (std::int64_t i = first; i < end; ++i)
      {
        if (!removed[ids[i]])
        {
          for (int axis = 0; axis < 3; ++axis)
          {
            positions[3 * static_cast<std::size_t>(ids[i]) + axis] = moved[axis][i];
          }
        }
      }
    }
    return true;
  }
};

} // namespace pcbilateral

#endif
