#include "CellColoringScheduler.h"

#include "BitOperations.h"
#include "Threads.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>

namespace pcbilateral
{

namespace
{
/// Report progress after this many points per thread, so the observer is called often
/// enough for a smooth bar without costing anything next to the kernel.
constexpr std::size_t PointsPerReport = 256;
/// ... or after this many neighbour evaluations (some milliseconds), whichever comes first: with
/// a radius as large as the cloud, 256 points are 256 times the whole cloud, which may take
/// seconds on a busy machine, and the calling thread's reports are also when a GUI that runs the
/// filter on its own thread (ParaView) repaints and sees its Abort button.
constexpr std::uint64_t EvaluationsPerReport = 1u << 20;
} // namespace

CellColoringScheduler::CellColoringScheduler(ProcessingOctree& octree,
  const KernelConstants& constants,
  double radius,
  bool removeIsolatedPoints,
  int numberOfThreads)
  : Octree(octree)
  , Constants(constants)
  , RemoveIsolatedPoints(removeIsolatedPoints)
  , NumberOfThreads(numberOfThreads)
  , Scratch(static_cast<std::size_t>(numberOfThreads))
{
  // A point of a leaf has its neighbours in the leaves whose boxes come closer than r to that
  // leaf's box. The slack covers rounding in the point-to-leaf assignment. Cells are at least
  // 2.1 r wide, so these leaves lie in the 27 cells around the leaf's own.
  const double leafSize = octree.GetLeafSize();
  // A point lies in its leaf's box up to the rounding of (p - origin) / leafSize and of the
  // box's corners, a few ulps of the coordinates' magnitude; 1e-12 of it is thousands of ulps.
  double magnitude = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    magnitude = std::max(magnitude, std::abs(octree.GetRootOrigin()[axis]) + octree.GetRootSize());
  }
  const double boxReach = radius * (1.0 + 1e-9) + 1e-12 * magnitude;
  this->LeafBoxReachSquared = boxReach * boxReach;
  const int reach = static_cast<int>(std::floor(radius / leafSize)) + 1;
  const double reachSquared = radius * radius * (1.0 + 1e-6);
  auto gap = [leafSize](int offset) { return std::max(0, std::abs(offset) - 1) * leafSize; };
  // For each leaf of a cell, those leaves in z, y, x order, as runs along x within one cell
  // (consecutive leaves of a cell are consecutive in the layout).
  constexpr int perAxis = ProcessingOctree::LeavesPerAxis;
  auto cellAndLeaf = [](int leaf, int& cell, int& local)
  {
    cell = leaf < 0 ? -1 : leaf / perAxis;
    local = leaf - perAxis * cell;
  };
  for (int localLeaf = 0; localLeaf < ProcessingOctree::LeavesPerCell; ++localLeaf)
  {
    this->RunsBegin[localLeaf] = static_cast<std::uint32_t>(this->LeafRuns.size());
    const int lx = localLeaf % perAxis;
    const int ly = (localLeaf / perAxis) % perAxis;
    const int lz = localLeaf / (perAxis * perAxis);
    for (int z = -reach; z <= reach; ++z)
    {
      for (int y = -reach; y <= reach; ++y)
      {
        for (int x = -reach; x <= reach; ++x)
        {
          if (!(gap(x) * gap(x) + gap(y) * gap(y) + gap(z) * gap(z) < reachSquared))
          {
            continue;
          }
          int cellX, cellY, cellZ, leafX, leafY, leafZ;
          cellAndLeaf(lx + x, cellX, leafX);
          cellAndLeaf(ly + y, cellY, leafY);
          cellAndLeaf(lz + z, cellZ, leafZ);
          const auto slot =
            static_cast<std::uint8_t>(ProcessingOctree::NeighbourSlot(cellX, cellY, cellZ));
          const auto leaf = static_cast<std::uint8_t>(leafX + perAxis * (leafY + perAxis * leafZ));
          LeafRun* last =
            this->LeafRuns.size() > this->RunsBegin[localLeaf] ? &this->LeafRuns.back() : nullptr;
          if (last && last->CellSlot == slot && last->LastLeaf + 1 == leaf && leafX > 0)
          {
            last->LastLeaf = leaf;
            last->Leaves |= std::uint64_t{ 1 } << leaf;
          }
          else
          {
            this->LeafRuns.push_back(LeafRun{ std::uint64_t{ 1 } << leaf, slot, leaf, leaf });
          }
        }
      }
    }
  }
  this->RunsBegin[ProcessingOctree::LeavesPerCell] =
    static_cast<std::uint32_t>(this->LeafRuns.size());
}

void CellColoringScheduler::GatherCandidates(std::size_t cell,
  const std::int32_t* neighbours,
  int localLeaf,
  std::size_t pointsToFilter,
  CandidateNeighbours& candidates) const
{
  // Of the leaves' points, only those near this leaf's box can be neighbours of its points
  // (about half of them on a surface with tens of neighbours per point): left out here once
  // rather than tested again for each point. The order of the others, and so every sum, is as
  // if all were gathered. It pays when the leaf has a few points to filter: for a point or two
  // (sparse clouds) the test per candidate costs about what it saves, and the runs are copied
  // whole.
  constexpr std::size_t PointsForTheCut = 4;
  const bool cut = pointsToFilter >= PointsForTheCut;
  const LatticeCoord& cellCoord = this->Octree.GetCellCoord(cell);
  const int leafIndex[3] = { localLeaf % ProcessingOctree::LeavesPerAxis,
    (localLeaf / ProcessingOctree::LeavesPerAxis) % ProcessingOctree::LeavesPerAxis,
    localLeaf / (ProcessingOctree::LeavesPerAxis * ProcessingOctree::LeavesPerAxis) };
  const std::int64_t cellIndex[3] = { cellCoord.X, cellCoord.Y, cellCoord.Z };
  double boxLow[3], boxHigh[3];
  for (int axis = 0; axis < 3 && cut; ++axis)
  {
    const double leaf =
      static_cast<double>(ProcessingOctree::LeavesPerAxis * cellIndex[axis] + leafIndex[axis]);
    const double origin = this->Octree.GetRootOrigin()[axis];
    boxLow[axis] = origin + leaf * this->Octree.GetLeafSize();
    boxHigh[axis] = origin + (leaf + 1.0) * this->Octree.GetLeafSize();
  }
  const double* x = this->Octree.GetX();
  const double* y = this->Octree.GetY();
  const double* z = this->Octree.GetZ();
  const std::size_t storedCells = this->Octree.GetNumberOfProcessingCells();
  candidates.Clear();
  for (std::uint32_t run = this->RunsBegin[localLeaf]; run < this->RunsBegin[localLeaf + 1]; ++run)
  {
    const LeafRun& leaves = this->LeafRuns[run];
    const std::int32_t around = neighbours[leaves.CellSlot];
    if (around == ProcessingOctree::NoCell || static_cast<std::size_t>(around) >= storedCells ||
        (this->Octree.GetLeafMask(around) & leaves.Leaves) == 0)
    {
      continue;
    }
    std::uint32_t begin, end;
    this->Octree.GetLeavesRange(around, leaves.FirstLeaf, leaves.LastLeaf, begin, end);
    if (end > begin && cut)
    {
      candidates.AppendNearBox(
        x + begin, y + begin, z + begin, end - begin, boxLow, boxHigh, this->LeafBoxReachSquared);
    }
    else if (end > begin)
    {
      candidates.Append(x + begin, y + begin, z + begin, end - begin);
    }
  }
}

namespace
{
/// Stores a point's estimated normal, turned to agree with its orientation normal if it has one
/// (the orientation of n does not change p + d n: only the reported normal flips).
void KeepNormal(PointState& state, std::uint32_t id, const double estimated[3])
{
  const std::size_t at = 3 * static_cast<std::size_t>(id);
  double sign = 1.0;
  if (state.OrientationNormals)
  {
    const double* reference = state.OrientationNormals + at;
    const double agreement =
      estimated[0] * reference[0] + estimated[1] * reference[1] + estimated[2] * reference[2];
    sign = agreement < 0.0 ? -1.0 : 1.0;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    state.Normals[at + axis] = sign * estimated[axis];
  }
}
} // namespace

bool CellColoringScheduler::StopRequested(bool isMaster)
{
  if (this->Aborted.load(std::memory_order_relaxed))
  {
    return true;
  }
  if (isMaster && this->ShouldAbort && this->ShouldAbort())
  {
    this->Aborted.store(true, std::memory_order_relaxed);
    return true;
  }
  return false;
}

void CellColoringScheduler::CountProgress(ThreadScratch& scratch, std::size_t points, bool isMaster)
{
  scratch.PointsSinceReport += points;
  if (scratch.PointsSinceReport >= PointsPerReport ||
      scratch.EvaluationsSinceReport >= EvaluationsPerReport)
  {
    this->PointsDone.fetch_add(scratch.PointsSinceReport, std::memory_order_relaxed);
    scratch.PointsSinceReport = 0;
    scratch.EvaluationsSinceReport = 0;
    if (isMaster && this->ReportPoints)
    {
      this->ReportPoints(this->PointsDone.load(std::memory_order_relaxed));
    }
  }
}

/// A cell's run: the octree's layout arrays it reads and writes, and the points it sends to each
/// of the 27 cells around it (ProcessingOctree's neighbour slots), listed while the cell runs and
/// handed over when it is done: the lists are linked through the octree without locks (the
/// colouring invariant).
struct CellColoringScheduler::CellPlacement
{
  CellPlacement(ProcessingOctree& octree, std::size_t cell)
    : Octree(octree)
    , Cell(octree.GetCellCoord(cell))
    , Ids(octree.GetIds())
    , X(octree.GetX())
    , Y(octree.GetY())
    , Z(octree.GetZ())
    , MovedX(octree.GetMovedX())
    , MovedY(octree.GetMovedY())
    , MovedZ(octree.GetMovedZ())
  {
    octree.GetNeighbourCells(cell, this->Neighbours);
    std::fill(this->First, this->First + 27, -1);
    std::fill(this->Last, this->Last + 27, -1);
  }

  void Place(std::uint32_t index, int slot, int localLeaf)
  {
    if (this->Last[slot] < 0)
    {
      this->Last[slot] = static_cast<std::int32_t>(index);
    }
    this->Octree.Link(index, localLeaf, this->First[slot]);
  }

  /// Places a moved point in its leaf if that lies in one of the 27 cells around and that cell
  /// is stored; false otherwise (the caller defers it).
  bool PlaceMoved(std::uint32_t index, const double moved[3])
  {
    const LatticeCoord leaf = this->Octree.LeafOf(moved);
    const LatticeCoord destination = ProcessingOctree::CellOfLeaf(leaf);
    const std::int64_t dx = destination.X - this->Cell.X;
    const std::int64_t dy = destination.Y - this->Cell.Y;
    const std::int64_t dz = destination.Z - this->Cell.Z;
    if (std::abs(dx) > 1 || std::abs(dy) > 1 || std::abs(dz) > 1)
    {
      return false;
    }
    const int slot = ProcessingOctree::NeighbourSlot(
      static_cast<int>(dx), static_cast<int>(dy), static_cast<int>(dz));
    if (this->Neighbours[slot] == ProcessingOctree::NoCell)
    {
      return false;
    }
    this->Place(index, slot, ProcessingOctree::LocalLeafIndex(leaf));
    return true;
  }

  void HandOver()
  {
    for (int slot = 0; slot < 27; ++slot)
    {
      if (this->First[slot] >= 0)
      {
        this->Octree.PlaceList(this->Neighbours[slot], this->First[slot], this->Last[slot]);
      }
    }
  }

  ProcessingOctree& Octree;
  const LatticeCoord& Cell;
  const std::uint32_t* const Ids;
  const double* const X;
  const double* const Y;
  const double* const Z;
  double* const MovedX;
  double* const MovedY;
  double* const MovedZ;
  std::int32_t Neighbours[27];
  std::int32_t First[27], Last[27];
};

void CellColoringScheduler::ProcessCell(std::size_t cell,
  PointState& state,
  ThreadScratch& scratch,
  bool isMaster)
{
  CellPlacement placement(this->Octree, cell);
  for (std::uint64_t leaves = this->Octree.GetLeafMask(cell); leaves != 0; leaves &= leaves - 1)
  {
    const int localLeaf = CountTrailingZeros(leaves);
    if (!this->ProcessLeaf(cell, localLeaf, placement, state, scratch, isMaster))
    {
      return;
    }
  }
  placement.HandOver();
}

bool CellColoringScheduler::ProcessLeaf(std::size_t cell,
  int localLeaf,
  CellPlacement& placement,
  PointState& state,
  ThreadScratch& scratch,
  bool isMaster)
{
  const std::uint32_t* ids = placement.Ids;
  const double* x = placement.X;
  const double* y = placement.Y;
  const double* z = placement.Z;
  std::uint32_t begin, end;
  this->Octree.GetLeafRange(cell, localLeaf, begin, end);
  this->GatherCandidates(cell, placement.Neighbours, localLeaf, end - begin, scratch.Candidates);
  // The leaf's points KernelLanes at a time: they share the candidates, and the kernel solves
  // their eigenvectors side by side.
  for (std::uint32_t next = begin; next < end;)
  {
    if (this->StopRequested(isMaster))
    {
      return false;
    }
    std::uint32_t batch[KernelLanes];
    double points[KernelLanes][3];
    std::size_t batchSize = 0;
    const std::uint32_t batchBegin = next;
    for (; next < end && batchSize < KernelLanes; ++next)
    {
      if (ids[next] >= state.FirstGhost)
      {
        // Ghosts are neighbours only: they stay where they are.
        placement.MovedX[next] = x[next];
        placement.MovedY[next] = y[next];
        placement.MovedZ[next] = z[next];
        placement.Place(next, ProcessingOctree::CentreSlot, localLeaf);
        continue;
      }
      batch[batchSize] = next;
      points[batchSize][0] = x[next];
      points[batchSize][1] = y[next];
      points[batchSize][2] = z[next];
      ++batchSize;
    }
    // Progress within the leaf: with a radius as large as the cloud, one leaf may hold every
    // point.
    this->CountProgress(scratch, next - batchBegin, isMaster);
    FilteredPoint filteredPoints[KernelLanes];
    FilterPoints(points, batchSize, scratch.Candidates, this->Constants, filteredPoints);
    scratch.EvaluationsSinceReport += batchSize * scratch.Candidates.Size();
    for (std::size_t k = 0; k < batchSize; ++k)
    {
      this->StoreFilteredPoint(batch[k], points[k], filteredPoints[k], placement, state, scratch);
    }
  }
  return true;
}

void CellColoringScheduler::StoreFilteredPoint(std::uint32_t index,
  const double p[3],
  const FilteredPoint& filtered,
  CellPlacement& placement,
  PointState& state,
  ThreadScratch& scratch)
{
  const std::uint32_t id = placement.Ids[index];
  scratch.NeighbourEvaluations += filtered.NeighbourCount;
  if (!state.Normals.empty())
  {
    KeepNormal(state, id, filtered.Normal);
  }
  if (!filtered.Filtered && this->RemoveIsolatedPoints)
  {
    state.Removed[id] = 1;
    if (state.Positions.empty())
    {
      scratch.Stopped.push_back(StoppedPoint{ id, { p[0], p[1], p[2] } });
    }
    else
    {
      std::copy(p, p + 3, state.Positions.data() + 3 * static_cast<std::size_t>(id));
    }
    return;
  }
  const double moved[3] = { p[0] + filtered.Displacement * filtered.Normal[0],
    p[1] + filtered.Displacement * filtered.Normal[1],
    p[2] + filtered.Displacement * filtered.Normal[2] };
  placement.MovedX[index] = moved[0];
  placement.MovedY[index] = moved[1];
  placement.MovedZ[index] = moved[2];
  if (!placement.PlaceMoved(index, moved))
  {
    scratch.Deferred.push_back(index);
  }
}

double CellColoringScheduler::EstimateNeighboursPerPoint(std::size_t samples)
{
  const std::size_t count = this->Octree.GetNumberOfPoints();
  samples = std::min(samples, count);
  if (samples == 0)
  {
    return 0.0;
  }
  CandidateNeighbours& candidates = this->Scratch[0].Candidates;
  std::uint64_t neighbours = 0;
  std::size_t cell = 0;
  for (std::size_t k = 0; k < samples; ++k)
  {
    const auto index = static_cast<std::uint32_t>(k * count / samples);
    while (this->Octree.GetCellEnd(cell) <= index)
    {
      ++cell;
    }
    int localLeaf = 0;
    for (std::uint64_t leaves = this->Octree.GetLeafMask(cell); leaves != 0; leaves &= leaves - 1)
    {
      std::uint32_t begin, end;
      localLeaf = CountTrailingZeros(leaves);
      this->Octree.GetLeafRange(cell, localLeaf, begin, end);
      if (index < end)
      {
        break;
      }
    }
    std::int32_t around[27];
    this->Octree.GetNeighbourCells(cell, around);
    this->GatherCandidates(cell, around, localLeaf, 1, candidates); // one point to filter
    const double p[3] = {
      this->Octree.GetX()[index], this->Octree.GetY()[index], this->Octree.GetZ()[index]
    };
    neighbours += FilterPoint(p, candidates, this->Constants).NeighbourCount;
  }
  return static_cast<double>(neighbours) / static_cast<double>(samples);
}

void CellColoringScheduler::PollObserver()
{
  if (this->ShouldAbort && this->ShouldAbort())
  {
    this->Aborted.store(true, std::memory_order_relaxed);
  }
  if (this->ReportPoints)
  {
    this->ReportPoints(this->PointsDone.load(std::memory_order_relaxed));
  }
}

bool CellColoringScheduler::RunIteration(PointState& state)
{
  this->Aborted.store(false);
  this->PointsDone.store(0);
  this->PointsProcessed = this->Octree.GetNumberOfPoints();

  // Cell numbers fit in 32 bits (the octree numbers them with std::int32_t).
  std::array<std::vector<std::uint32_t>, 8> classes;
  for (std::size_t cell = 0; cell < this->Octree.GetNumberOfProcessingCells(); ++cell)
  {
    classes[ProcessingOctree::ColourOf(this->Octree.GetCellCoord(cell))].push_back(
      static_cast<std::uint32_t>(cell));
  }

  this->PollObserver(); // (the set-up above and the caller's: Compact, the estimate)
  for (const auto& cells : classes)
  {
    if (this->Aborted.load())
    {
      return false;
    }
    const auto cellCount = static_cast<std::int64_t>(cells.size());
    std::atomic<std::int64_t> cellsDone{ 0 };
#pragma omp parallel num_threads(this->NumberOfThreads)
    {
      ThreadScratch& scratch = this->Scratch[CurrentThreadIndex()];
      const bool isMaster = CurrentThreadIndex() == 0;
#pragma omp for schedule(dynamic, 1) nowait
      for (std::int64_t k = 0; k < cellCount; ++k)
      {
        if (!this->Aborted.load(std::memory_order_relaxed))
        {
          this->ProcessCell(static_cast<std::size_t>(cells[k]), state, scratch, isMaster);
        }
        cellsDone.fetch_add(1, std::memory_order_release);
      }
      // The hooks belong to the calling thread: once out of cells it keeps polling them while
      // the other threads finish theirs (a class may hold a single, long cell).
      while (isMaster && cellsDone.load(std::memory_order_acquire) < cellCount)
      {
        this->PollObserver();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
    if (this->Aborted.load())
    {
      return false;
    }
    // Points that landed in a cell the octree did not hold yet: placed here, serially.
    for (auto& scratch : this->Scratch)
    {
      for (const std::uint32_t index : scratch.Deferred)
      {
        this->Octree.PlaceSerially(index);
      }
      scratch.Deferred.clear();
    }
  }
  this->NeighbourEvaluations = 0;
  for (auto& scratch : this->Scratch)
  {
    state.Stopped.insert(state.Stopped.end(), scratch.Stopped.begin(), scratch.Stopped.end());
    scratch.Stopped.clear();
    scratch.PointsSinceReport = 0;
    scratch.EvaluationsSinceReport = 0;
    this->NeighbourEvaluations += scratch.NeighbourEvaluations;
    scratch.NeighbourEvaluations = 0;
  }
  return true;
}

} // namespace pcbilateral
