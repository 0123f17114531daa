// Algorithm 2 of Digne & de Franchis (IPOL 2017): one iteration of the bilateral filter over
// all points, with the octree's processing cells run in parallel by colour class.
#ifndef pcbilateral_CellColoringScheduler_h
#define pcbilateral_CellColoringScheduler_h

#include "BilateralKernel.h"
#include "PointState.h"
#include "ProcessingOctree.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

namespace pcbilateral
{

/**
 * Runs iterations of the filter on the octree's layout (compacted before each). The processing
 * cells are sorted into 8 classes by colour (child index). The classes run one after another;
 * the cells of one class run in parallel. Each filtered point is placed into the octree's
 * next-iteration lists without locks (gathered per destination while its cell runs, handed
 * over when the cell is done): it moved by less than r, so it lands in a leaf of its cell's
 * r-dilation, and the dilations of two cells of one class share no leaf. The rare point that
 * lands in a cell not yet stored is placed after its class, serially.
 *
 * Every neighbour sum runs over the candidates in an order fixed by the octree's geometry
 * alone, so the result depends neither on the number of threads nor on how the points are
 * numbered.
 */
class CellColoringScheduler
{
public:
  CellColoringScheduler(ProcessingOctree& octree,
    const KernelConstants& constants,
    double radius,
    bool removeIsolatedPoints,
    int numberOfThreads);

  /// Hooks polled by the calling thread; both may be empty.
  std::function<void(std::size_t pointsDone)> ReportPoints;
  std::function<bool()> ShouldAbort;

  /// Filters every point of the octree's layout once: writes their moved positions (and
  /// normals), and leaves them placed in the octree for the next iteration.
  /// Returns false if aborted.
  bool RunIteration(PointState& state);

  /// The mean number of neighbours (|q - p| < r) of up to `samples` points spread over the
  /// octree's layout: a cheap look at what an iteration will cost.
  double EstimateNeighboursPerPoint(std::size_t samples);

  /// Number of points filtered in the last iteration (those placed in the octree).
  std::size_t GetNumberOfPointsProcessed() const { return this->PointsProcessed; }
  /// Neighbours visited in the last iteration, summed over its points.
  std::uint64_t GetNumberOfNeighbourEvaluations() const { return this->NeighbourEvaluations; }

private:
  /// One per thread, a cache line apart: each thread writes its own counters for every point.
  struct alignas(64) ThreadScratch
  {
    CandidateNeighbours Candidates;
    std::vector<std::uint32_t> Deferred;
    std::vector<StoppedPoint> Stopped;
    std::size_t PointsSinceReport = 0;
    std::uint64_t EvaluationsSinceReport = 0;
    std::uint64_t NeighbourEvaluations = 0;
  };

  struct CellPlacement;
  /// Filters the points of a cell, leaf by leaf, and places them for the next iteration.
  void ProcessCell(std::size_t cell, PointState& state, ThreadScratch& scratch, bool isMaster);
  /// Filters the points of one leaf of a cell; false if the run was stopped.
  bool ProcessLeaf(std::size_t cell,
    int localLeaf,
    CellPlacement& placement,
    PointState& state,
    ThreadScratch& scratch,
    bool isMaster);
  /// Writes a filtered point's move (or removal) and places it for the next iteration.
  void StoreFilteredPoint(std::uint32_t index,
    const double p[3],
    const FilteredPoint& filtered,
    CellPlacement& placement,
    PointState& state,
    ThreadScratch& scratch);
  /// Whether the run is to stop: aborted already, or (calling thread only) ShouldAbort says so.
  bool StopRequested(bool isMaster);
  /// Counts `points` done by a thread, and reports progress every so often (calling thread).
  void CountProgress(ThreadScratch& scratch, std::size_t points, bool isMaster);
  /// Calling thread only: asks ShouldAbort and reports progress.
  void PollObserver();
  /// The points of the leaves within reach of a leaf of a cell (given the cell's 27
  /// neighbours, GetNeighbourCells), in an order fixed by geometry; for a leaf of several
  /// points, only those near the leaf's box.
  void GatherCandidates(std::size_t cell,
    const std::int32_t* neighbours,
    int localLeaf,
    std::size_t pointsToFilter,
    CandidateNeighbours& candidates) const;

  ProcessingOctree& Octree;
  KernelConstants Constants;
  bool RemoveIsolatedPoints;
  int NumberOfThreads;
  /// Leaves that can hold a neighbour of a point of a given leaf of a cell: runs of
  /// consecutive leaves of one of the 27 cells around (CellSlot: ProcessingOctree::NeighbourSlot).
  struct LeafRun
  {
    /// The run's leaves as bits of a cell's leaf mask: a run of empty leaves costs one test.
    std::uint64_t Leaves;
    std::uint8_t CellSlot;
    std::uint8_t FirstLeaf;
    std::uint8_t LastLeaf;
  };
  std::vector<LeafRun> LeafRuns;
  /// The runs of leaf l of a cell are LeafRuns[RunsBegin[l]] to LeafRuns[RunsBegin[l + 1] - 1].
  std::array<std::uint32_t, ProcessingOctree::LeavesPerCell + 1> RunsBegin{};
  std::vector<ThreadScratch> Scratch;
  /// The squared reach around a leaf's box within which its points' neighbours lie: r, and a
  /// margin for the rounding of the point-to-leaf assignment and of the box's corners.
  double LeafBoxReachSquared;
  std::atomic<bool> Aborted{ false };
  std::atomic<std::size_t> PointsDone{ 0 };
  std::size_t PointsProcessed = 0;
  std::uint64_t NeighbourEvaluations = 0;
};

} // namespace pcbilateral

#endif
