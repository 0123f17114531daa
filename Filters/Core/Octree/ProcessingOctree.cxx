#include "ProcessingOctree.h"

#include "BilateralKernel.h"
#include "HugePages.h"
#include "Threads.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <type_traits>

namespace pcbilateral
{

namespace
{
/// Cells are at least this many radii wide, so that a point moved by less than r (the
/// filter's guarantee) from one cell cannot reach a leaf reachable from a cell of the same
/// colour (the paper's d = 2.1 r).
constexpr double CellSizeInRadii = 2.1;
/// Compact's parallel passes take this many cells at a time, and ask at the first of each.
constexpr std::int64_t CellsPerAsk = 4096;

/// The order of the points in a leaf: by coordinates, so that it depends on geometry alone and
/// not on the point ids (a distributed run numbers its points differently). Points equal in all
/// three coordinates are ordered by their bits, then by id: exact duplicates contribute the
/// same terms to every sum, so their order among themselves changes no result.
struct LeafOrder
{
  const double* X;
  const double* Y;
  const double* Z;
  const std::uint32_t* Ids;

  bool operator()(std::uint32_t a, std::uint32_t b) const
  {
    const double ca[3] = { this->X[a], this->Y[a], this->Z[a] };
    const double cb[3] = { this->X[b], this->Y[b], this->Z[b] };
    for (int axis = 0; axis < 3; ++axis)
    {
      if (ca[axis] != cb[axis])
      {
        return ca[axis] < cb[axis];
      }
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      std::uint64_t bitsA, bitsB;
      std::memcpy(&bitsA, ca + axis, sizeof(bitsA));
      std::memcpy(&bitsB, cb + axis, sizeof(bitsB));
      if (bitsA != bitsB)
      {
        return bitsA < bitsB;
      }
    }
    return this->Ids[a] < this->Ids[b];
  }
};

/// The order of the cells in a layout: by lattice coordinates (z, then y, then x), so that it
/// does not depend on the order in which cells were created. Cells are distinct, so the order is
/// total.
struct LatticeOrder
{
  const LatticeCoord* Coords;

  bool operator()(std::int32_t a, std::int32_t b) const
  {
    const LatticeCoord& ca = this->Coords[a];
    const LatticeCoord& cb = this->Coords[b];
    if (ca.Z != cb.Z)
    {
      return ca.Z < cb.Z;
    }
    if (ca.Y != cb.Y)
    {
      return ca.Y < cb.Y;
    }
    return ca.X < cb.X;
  }
};

/**
 * Puts a cell's points in the layout's order: by leaf, then by LeafOrder within each leaf.
 * `points` lists them, in any order, as indices into the arrays that `leafOf` and `order` read;
 * `sorted` receives them in layout order, and the ends of the cell's occupied leaves (counted from
 * cellBegin) go to leafEnds.
 */
template<typename LeafOfPoint>
void OrderCellPoints(const std::uint32_t* points,
  std::size_t count,
  LeafOfPoint leafOf,
  const LeafOrder& order,
  std::uint32_t cellBegin,
  std::vector<std::uint32_t>& sorted,
  std::uint32_t* leafEnds)
{
  constexpr int leaves = ProcessingOctree::LeavesPerCell;
  std::uint32_t leafStarts[leaves + 1] = {};
  for (std::size_t k = 0; k < count; ++k)
  {
    ++leafStarts[leafOf(points[k]) + 1];
  }
  for (int leaf = 0; leaf < leaves; ++leaf)
  {
    leafStarts[leaf + 1] += leafStarts[leaf];
  }
  sorted.resize(count);
  std::uint32_t fill[leaves];
  std::copy(leafStarts, leafStarts + leaves, fill);
  for (std::size_t k = 0; k < count; ++k)
  {
    sorted[fill[leafOf(points[k])]++] = points[k];
  }
  for (int leaf = 0; leaf < leaves; ++leaf)
  {
    if (leafStarts[leaf] == leafStarts[leaf + 1])
    {
      continue;
    }
    std::sort(sorted.begin() + leafStarts[leaf], sorted.begin() + leafStarts[leaf + 1], order);
    *leafEnds++ = cellBegin + leafStarts[leaf + 1];
  }
}

} // namespace

ProcessingOctree::ProcessingOctree(const double boundsMin[3],
  const double boundsMax[3],
  double radius)
{
  double extent = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    extent = std::max(extent, boundsMax[axis] - boundsMin[axis]);
  }
  // The root is at least two processing cells wide, so that depth 1 already satisfies the
  // cell size bound even for a radius as large as the cloud.
  const double minimumCellSize = CellSizeInRadii * radius;
  this->RootSize = std::max(extent, 2.0 * minimumCellSize);
  for (int axis = 0; axis < 3; ++axis)
  {
    this->RootOrigin[axis] = 0.5 * (boundsMin[axis] + boundsMax[axis]) - 0.5 * this->RootSize;
  }
  // Smallest cells whose size is at least 2.1 r, at least one level below the root.
  this->ProcessingDepth = 1;
  while (std::ldexp(this->RootSize, -(this->ProcessingDepth + 1)) >= minimumCellSize)
  {
    ++this->ProcessingDepth;
  }
  this->CellSize = std::ldexp(this->RootSize, -this->ProcessingDepth);
  this->LeafSize = this->CellSize / LeavesPerAxis;
}

bool ProcessingOctree::Load(const double* positions,
  std::size_t count,
  int numberOfThreads,
  const std::function<bool()>& shouldStop)
{
  LoadStop stop;
  stop.Ask = shouldStop ? &shouldStop : nullptr;
  this->Stop = &stop;
  this->Reset(count);
  for (std::size_t id = 0; id < count; ++id)
  {
    // (This pass is serial: asked every million points too, 0.1 s or so.)
    if ((id & 0xFFFFF) == 0xFFFFF && this->EndIfStopped())
    {
      return false;
    }
    if (IsFinitePoint(positions + 3 * id))
    {
      this->Ids.push_back(static_cast<std::uint32_t>(id));
    }
  }
  if (this->EndIfStopped())
  {
    return false;
  }
  this->AssignCellsAndLeaves(positions, numberOfThreads);
  if (this->EndIfStopped())
  {
    return false;
  }

  // The first layout, built here rather than by Compact (which would copy every position and
  // id a second time, beside the input: that copy was the peak memory of sparse clouds): the
  // cells in lattice order, each cell's points in layout order.
  const std::size_t n = this->Ids.size();
  const std::size_t cells = this->CellCoords.size();
  std::vector<std::int32_t> kept(cells);
  std::iota(kept.begin(), kept.end(), 0);
  this->SortCells(kept, numberOfThreads);
  std::vector<std::uint32_t> cellCounts(cells, 0);
  std::vector<std::uint64_t> cellMasks(cells, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    if ((i & 0xFFFFF) == 0 && this->EndIfStopped()) // (as the first pass)
    {
      return false;
    }
    ++cellCounts[static_cast<std::size_t>(this->NextLink[i])];
    cellMasks[static_cast<std::size_t>(this->NextLink[i])] |= std::uint64_t{ 1 }
                                                              << this->NextLeaf[i];
  }
  this->SetUpCells(kept, cellCounts, cellMasks);
  cellCounts = std::vector<std::uint32_t>();
  cellMasks = std::vector<std::uint64_t>();
  if (this->EndIfStopped())
  {
    return false;
  }

  // The points reach their places in two passes, each writing to few places at a time. A cloud
  // whose points are not in spatial order (random, or shuffled by a previous tool) made a single
  // pass write each point to its own cell, one of hundreds of thousands: a cache and TLB miss
  // per array per point, 5.9 s of the 28 s that lidar20M took on one thread. First, each point
  // goes to its bucket, a run of consecutive cells of about n / 1024 points; then each bucket is
  // ordered in cache.
  const LoadBuckets buckets = this->PlanBuckets(kept);
  PointArray<std::uint32_t> codes(n);
  this->ScatterToBuckets(positions, buckets, codes, numberOfThreads);
  if (this->EndIfStopped())
  {
    return false;
  }
  this->OrderBuckets(buckets, codes, numberOfThreads);
  if (this->EndIfStopped())
  {
    return false;
  }
  this->FinishCells(kept, n, numberOfThreads);
  const bool stopped = this->EndIfStopped(); // (FinishCells asks too)
  this->Stop = nullptr;
  return !stopped;
}

bool ProcessingOctree::EndIfStopped()
{
  if (!this->StopAsked())
  {
    return false;
  }
  this->Stop = nullptr;
  this->Reset(0);
  return true;
}

bool ProcessingOctree::StopSeen(std::int64_t cell) const
{
  return cell % CellsPerAsk == 0
           ? this->StopAsked()
           : this->Stop != nullptr && this->Stop->Stopped.load(std::memory_order_relaxed);
}

bool ProcessingOctree::StopAsked() const
{
  if (!this->Stop)
  {
    return false;
  }
  if (this->Stop->Stopped.load(std::memory_order_relaxed))
  {
    return true;
  }
  if (this->Stop->Ask && CurrentThreadIndex() == 0 && (*this->Stop->Ask)())
  {
    this->Stop->Stopped.store(true, std::memory_order_relaxed);
    return true;
  }
  return false;
}

void ProcessingOctree::Reset(std::size_t count)
{
  this->CellCoords.clear();
  this->CellIndex.Clear(count / 64);
  this->NumberOfProcessingCells = 0;
  this->NextHead.clear();
  this->LeafMasks.clear();
  this->CellBegins.assign(1, 0);
  this->LeafSlots.clear();
  this->LeafEnds.clear();
  this->Ids.clear();
  this->MovedX.clear();
  this->MovedY.clear();
  this->MovedZ.clear();
  ReserveWithHugePages(count, this->Ids, this->CompactedIds, this->X, this->Y, this->Z);
  ReserveWithHugePages(count, this->MovedX, this->MovedY, this->MovedZ);
  ReserveWithHugePages(count, this->NextLink, this->NextLeaf);
}

void ProcessingOctree::AssignCellsAndLeaves(const double* positions, int numberOfThreads)
{
  // Each point's cell (held in NextLink until the layout is made) and leaf, in parallel: the
  // map is filled from a sample of the points first (cells hold tens of points, so the sample
  // finds nearly all of them), then read by all threads; the few cells the sample missed are
  // created after, serially. Cells are numbered in no meaningful order until sorted.
  const std::size_t n = this->Ids.size();
  this->NextLink.resize(n);
  this->NextLeaf.resize(n);
  auto positionOf = [this, positions](std::size_t i)
  { return positions + 3 * static_cast<std::size_t>(this->Ids[i]); };
  constexpr std::size_t SampleStep = 16;
  for (std::size_t i = 0; i < n; i += SampleStep)
  {
    if (i % (SampleStep << 16) == 0 && this->StopAsked())
    {
      return; // Load sees it
    }
    this->FindOrCreateCell(CellOfLeaf(this->LeafOf(positionOf(i))));
  }
  // In blocks, so that a stop asked of the load is seen within one; taken one at a time, so
  // that the calling thread, which asks, never waits long for the others at the loop's end.
  constexpr std::size_t Block = std::size_t(1) << 16;
  const auto blocks = static_cast<std::int64_t>((n + Block - 1) / Block);
#pragma omp parallel for schedule(dynamic, 1) num_threads(numberOfThreads)
  for (std::int64_t block = 0; block < blocks; ++block)
  {
    if (this->StopAsked())
    {
      continue;
    }
    const std::size_t end = std::min(n, static_cast<std::size_t>(block + 1) * Block);
    for (std::size_t i = static_cast<std::size_t>(block) * Block; i < end; ++i)
    {
      const LatticeCoord leaf = this->LeafOf(positionOf(i));
      this->NextLink[i] = this->FindCell(CellOfLeaf(leaf));
      this->NextLeaf[i] = static_cast<std::uint8_t>(LocalLeafIndex(leaf));
    }
  }
  if (this->StopAsked())
  {
    return; // Load sees it
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if ((i & 0xFFFFF) == 0xFFFFF && this->StopAsked()) // (serial: asked every million points)
    {
      return; // Load sees it
    }
    if (this->NextLink[i] == NoCell)
    {
      this->NextLink[i] = this->FindOrCreateCell(CellOfLeaf(this->LeafOf(positionOf(i))));
    }
  }
}

ProcessingOctree::LoadBuckets ProcessingOctree::PlanBuckets(
  const std::vector<std::int32_t>& kept) const
{
  // Buckets are runs of consecutive cells (in the new order) of about n / 1024 points, at least
  // 4096.
  const std::size_t n = this->Ids.size();
  const std::size_t cells = kept.size();
  const std::size_t bucketPoints = std::max<std::size_t>(4096, n / 1024);
  LoadBuckets buckets;
  buckets.BucketOfCell.resize(cells);
  buckets.CellCode.resize(cells);
  for (std::size_t cell = 0, inBucket = 0; cell < cells; ++cell)
  {
    // (Serial over every cell, up to one per two points: asked every 65,536 cells. Load sees a
    // stop before the buckets are used.)
    if ((cell & 0xFFFF) == 0xFFFF && this->StopAsked())
    {
      break;
    }
    if (cell == 0 || inBucket >= bucketPoints)
    {
      buckets.FirstCell.push_back(static_cast<std::uint32_t>(cell));
      inBucket = 0;
    }
    const auto old = static_cast<std::size_t>(kept[cell]);
    buckets.BucketOfCell[old] = static_cast<std::uint32_t>(buckets.FirstCell.size() - 1);
    buckets.CellCode[old] = static_cast<std::uint32_t>(cell - buckets.FirstCell.back()) << 6;
    inBucket += this->CellBegins[cell + 1] - this->CellBegins[cell];
  }
  static_assert(LeavesPerCell <= 64, "a leaf index takes 6 bits of a cell code");
  buckets.Count = buckets.FirstCell.size();
  buckets.FirstCell.push_back(static_cast<std::uint32_t>(cells));
  return buckets;
}

void ProcessingOctree::ScatterToBuckets(const double* positions,
  const LoadBuckets& buckets,
  PointArray<std::uint32_t>& codes,
  int numberOfThreads)
{
  // Fixed chunks of points each count their points per bucket, then write them where the
  // counts say (bucket by bucket, chunk by chunk), in parallel. Buckets fill in a fixed order,
  // but that order does not matter: OrderBuckets orders every cell's points by geometry alone.
  const std::size_t n = this->Ids.size();
  constexpr std::size_t Chunks = 64;
  if (this->StopAsked()) // (PlanBuckets asks too)
  {
    return; // Load sees it
  }
  std::vector<std::uint32_t> cursors(Chunks * buckets.Count, 0);
  auto chunkBegin = [n](std::size_t chunk) { return chunk * n / Chunks; };
  // A chunk is n / 64 points (300,000 of 20 million, each written to its bucket: a cache miss
  // and, the first time, a page fault; 0.7 s unasked on a busy machine): asked within it too.
  constexpr std::size_t AskEvery = (std::size_t(1) << 14) - 1;
  // Chunks taken one at a time (here and below): the calling thread, which asks whether to stop,
  // then never waits long for the others at the loop's end (seconds on a busy machine).
#pragma omp parallel for schedule(dynamic, 1) num_threads(numberOfThreads)
  for (std::int64_t chunk = 0; chunk < static_cast<std::int64_t>(Chunks); ++chunk)
  {
    if (this->StopAsked())
    {
      continue;
    }
    std::uint32_t* counts = cursors.data() + static_cast<std::size_t>(chunk) * buckets.Count;
    for (std::size_t i = chunkBegin(chunk); i < chunkBegin(chunk + 1); ++i)
    {
      if ((i & AskEvery) == 0 && this->StopAsked())
      {
        break;
      }
      ++counts[buckets.BucketOfCell[static_cast<std::size_t>(this->NextLink[i])]];
    }
  }
  if (this->StopAsked())
  {
    return; // Load sees it
  }
  for (std::size_t bucket = 0, at = 0; bucket < buckets.Count; ++bucket)
  {
    for (std::size_t chunk = 0; chunk < Chunks; ++chunk)
    {
      std::uint32_t& cursor = cursors[chunk * buckets.Count + bucket];
      const std::uint32_t count = cursor;
      cursor = static_cast<std::uint32_t>(at);
      at += count;
    }
  }
  if (!this->TouchLayout(codes, numberOfThreads))
  {
    return; // Load sees it
  }
#pragma omp parallel for schedule(dynamic, 1) num_threads(numberOfThreads)
  for (std::int64_t chunk = 0; chunk < static_cast<std::int64_t>(Chunks); ++chunk)
  {
    if (this->StopAsked())
    {
      continue;
    }
    std::uint32_t* cursor = cursors.data() + static_cast<std::size_t>(chunk) * buckets.Count;
    for (std::size_t i = chunkBegin(chunk); i < chunkBegin(chunk + 1); ++i)
    {
      if ((i & AskEvery) == 0 && this->StopAsked())
      {
        break;
      }
      const auto cell = static_cast<std::size_t>(this->NextLink[i]);
      const std::uint32_t to = cursor[buckets.BucketOfCell[cell]]++;
      const double* p = positions + 3 * static_cast<std::size_t>(this->Ids[i]);
      this->X[to] = p[0];
      this->Y[to] = p[1];
      this->Z[to] = p[2];
      this->CompactedIds[to] = this->Ids[i];
      codes[to] = buckets.CellCode[cell] | this->NextLeaf[i];
    }
  }
  this->Ids.swap(this->CompactedIds);
  // The ids of the finite points in input order are not needed again; Compact makes its own.
  PointArray<std::uint32_t>().swap(this->CompactedIds);
}

bool ProcessingOctree::TouchLayout(PointArray<std::uint32_t>& codes, int numberOfThreads)
{
  const std::size_t n = this->Ids.size();
  this->CompactedIds.resize(n);
  this->X.resize(n);
  this->Y.resize(n);
  this->Z.resize(n);
  const auto stopSeen = [this]() { return this->StopAsked(); };
  TouchPages(codes.data(), n, numberOfThreads, stopSeen);
  TouchPages(this->CompactedIds.data(), n, numberOfThreads, stopSeen);
  for (PointArray<double>* axis : { &this->X, &this->Y, &this->Z })
  {
    TouchPages(axis->data(), n, numberOfThreads, stopSeen);
  }
  return !this->StopAsked();
}

void ProcessingOctree::OrderBuckets(const LoadBuckets& buckets,
  const PointArray<std::uint32_t>& codes,
  int numberOfThreads)
{
  // Each bucket's points, copied aside, sorted by cell and written back in layout order.
  const auto signedBuckets = static_cast<std::int64_t>(buckets.Count);
#pragma omp parallel num_threads(numberOfThreads)
  {
    BucketScratch scratch;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t bucket = 0; bucket < signedBuckets; ++bucket)
    {
      if (!this->StopAsked())
      {
        this->OrderBucket(buckets.FirstCell[bucket], buckets.FirstCell[bucket + 1], codes, scratch);
      }
    }
  }
}

void ProcessingOctree::OrderBucket(std::uint32_t firstCell,
  std::uint32_t endCell,
  const PointArray<std::uint32_t>& codes,
  BucketScratch& scratch)
{
  const std::uint32_t begin = this->CellBegins[firstCell];
  const std::uint32_t end = this->CellBegins[endCell];
  scratch.X.assign(this->X.begin() + begin, this->X.begin() + end);
  scratch.Y.assign(this->Y.begin() + begin, this->Y.begin() + end);
  scratch.Z.assign(this->Z.begin() + begin, this->Z.begin() + end);
  scratch.Ids.assign(this->Ids.begin() + begin, this->Ids.begin() + end);
  scratch.Codes.assign(codes.begin() + begin, codes.begin() + end);
  const std::vector<std::uint32_t>& bucketCodes = scratch.Codes;
  // The copies' indices, grouped by cell.
  std::vector<std::uint32_t>& cellStarts = scratch.CellStarts;
  cellStarts.assign(endCell - firstCell + 1, 0);
  for (const std::uint32_t code : bucketCodes)
  {
    ++cellStarts[(code >> 6) + 1];
  }
  for (std::size_t cell = 0; cell + 1 < cellStarts.size(); ++cell)
  {
    cellStarts[cell + 1] += cellStarts[cell];
  }
  scratch.ByCell.resize(bucketCodes.size());
  for (std::uint32_t k = 0; k < bucketCodes.size(); ++k)
  {
    scratch.ByCell[cellStarts[bucketCodes[k] >> 6]++] = k;
  }
  const LeafOrder order{ scratch.X.data(), scratch.Y.data(), scratch.Z.data(), scratch.Ids.data() };
  std::vector<std::uint32_t>& sorted = scratch.Sorted;
  std::uint32_t listed = 0;
  for (std::uint32_t cell = firstCell; cell < endCell; ++cell)
  {
    const std::uint32_t cellBegin = this->CellBegins[cell];
    const std::uint32_t count = this->CellBegins[cell + 1] - cellBegin;
    OrderCellPoints(
      scratch.ByCell.data() + listed,
      count,
      [&bucketCodes](std::uint32_t k) { return bucketCodes[k] & 63u; },
      order,
      cellBegin,
      sorted,
      this->LeafEnds.data() + this->LeafSlots[cell]);
    listed += count;
    for (std::uint32_t k = 0; k < count; ++k)
    {
      this->X[cellBegin + k] = scratch.X[sorted[k]];
      this->Y[cellBegin + k] = scratch.Y[sorted[k]];
      this->Z[cellBegin + k] = scratch.Z[sorted[k]];
      this->Ids[cellBegin + k] = scratch.Ids[sorted[k]];
    }
  }
}

std::int32_t ProcessingOctree::FindCell(const LatticeCoord& cell) const
{
  static_assert(CellIndexMap::Missing == NoCell, "a cell not found is NoCell");
  return this->CellIndex.Find(cell, this->CellCoords.data());
}

std::int32_t ProcessingOctree::FindOrCreateCell(const LatticeCoord& cell)
{
  const auto created = static_cast<std::int32_t>(this->CellCoords.size());
  const std::int32_t index = this->CellIndex.Insert(cell, created, this->CellCoords.data());
  if (index != created)
  {
    return index;
  }
  this->CellCoords.push_back(cell);
  this->NextHead.push_back(-1);
  return index;
}

void ProcessingOctree::PlaceSerially(std::uint32_t index)
{
  const double moved[3] = { this->MovedX[index], this->MovedY[index], this->MovedZ[index] };
  const LatticeCoord leaf = this->LeafOf(moved);
  this->Place(index, this->FindOrCreateCell(CellOfLeaf(leaf)), LocalLeafIndex(leaf));
}

void ProcessingOctree::SortCells(std::vector<std::int32_t>& kept, int numberOfThreads) const
{
  // The cells of the last layout come first and are in that order already; only the cells
  // created since (all of them at Load, few after an iteration) are sorted, in two halves in
  // parallel, then merged in. This part is serial, and a sort of all cells cost sparse clouds
  // (up to one cell per two points) a good share of their 2-thread speed-up. The order is total,
  // so the result is the same whatever the way it is reached.
  const LatticeOrder latticeOrder{ this->CellCoords.data() };
  const auto firstNew = static_cast<std::size_t>(
    std::lower_bound(
      kept.begin(), kept.end(), static_cast<std::int32_t>(this->NumberOfProcessingCells)) -
    kept.begin());
  const std::size_t newCells = kept.size() - firstNew;
  const auto newBegin = kept.begin() + static_cast<std::ptrdiff_t>(firstNew);
  const auto newMiddle = newBegin + static_cast<std::ptrdiff_t>(newCells / 2);
  if (numberOfThreads > 1 && newCells > 65536)
  {
#pragma omp parallel sections num_threads(2)
    {
#pragma omp section
      std::sort(newBegin, newMiddle, latticeOrder);
#pragma omp section
      std::sort(newMiddle, kept.end(), latticeOrder);
    }
    std::inplace_merge(newBegin, newMiddle, kept.end(), latticeOrder);
  }
  else
  {
    std::sort(newBegin, kept.end(), latticeOrder);
  }
  std::inplace_merge(kept.begin(), newBegin, kept.end(), latticeOrder);
}

void ProcessingOctree::SetUpCells(const std::vector<std::int32_t>& kept,
  const std::vector<std::uint32_t>& cellCounts,
  const std::vector<std::uint64_t>& cellMasks)
{
  const std::size_t newCellCount = kept.size();
  this->LeafMasks.resize(newCellCount);
  this->CellBegins.resize(newCellCount + 1);
  this->LeafSlots.resize(newCellCount);
  this->CellBegins[0] = 0;
  std::uint32_t slots = 0;
  for (std::size_t cell = 0; cell < newCellCount; ++cell)
  {
    this->LeafMasks[cell] = cellMasks[kept[cell]];
    this->CellBegins[cell + 1] = this->CellBegins[cell] + cellCounts[kept[cell]];
    this->LeafSlots[cell] = slots;
    slots += static_cast<std::uint32_t>(Popcount(this->LeafMasks[cell]));
  }
  this->LeafEnds.resize(slots);
}

void ProcessingOctree::FinishCells(const std::vector<std::int32_t>& kept,
  std::size_t pointCount,
  int numberOfThreads)
{
  // The cells' coordinates in their new order, and the map to their new numbers, in parallel
  // (serially, the map took a tenth of a sparse cloud's iteration on one thread, which weighed
  // on its 2-thread speed-up).
  const std::size_t newCellCount = kept.size();
  const auto signedNewCellCount = static_cast<std::int64_t>(newCellCount);
  // Room for the cells an iteration creates (points that land in a cell not stored yet), so
  // that creating one does not copy all of them into a new array of twice the size: on sparse
  // clouds (up to a cell per two points) that copy, beside the old array, was the iteration's
  // peak memory. Room never written costs no memory.
  const std::size_t room = newCellCount + newCellCount / 8 + 64;
  std::vector<LatticeCoord> newCoords;
  newCoords.reserve(room);
  newCoords.resize(newCellCount);
#pragma omp parallel for schedule(static) num_threads(numberOfThreads)
  for (std::int64_t cell = 0; cell < signedNewCellCount; ++cell)
  {
    newCoords[static_cast<std::size_t>(cell)] = this->CellCoords[kept[cell]];
  }
  this->CellIndex.InsertDistinct(newCoords.data(), newCellCount, numberOfThreads);
  this->CellCoords = std::move(newCoords);
  this->NumberOfProcessingCells = newCellCount;
  this->NextHead.clear();
  this->NextHead.reserve(room);
  this->NextHead.resize(newCellCount, -1);
  // (Asked between these: each is a first touch of up to 160 MB, seconds on a busy machine.)
  if (this->StopAsked())
  {
    return;
  }
  this->NextLink.assign(pointCount, -1);
  this->NextLeaf.assign(pointCount, 0);
  for (PointArray<double>* moved : { &this->MovedX, &this->MovedY, &this->MovedZ })
  {
    if (this->StopAsked())
    {
      return;
    }
    moved->resize(pointCount);
  }
}

bool ProcessingOctree::Compact(int numberOfThreads, const std::function<bool()>& shouldStop)
{
  LoadStop stop;
  stop.Ask = shouldStop ? &shouldStop : nullptr;
  this->Stop = &stop;
  // (Both parallel passes over the cells take them in blocks, so that the calling thread, which
  // asks whether to stop, does not wait for the others' halves: a whole cloud's Compact between
  // two iterations was unasked.)
  std::vector<std::uint32_t> cellCounts;
  std::vector<std::uint64_t> cellMasks;
  this->CountPlacedPoints(cellCounts, cellMasks, numberOfThreads);
  if (this->EndIfStopped())
  {
    return false;
  }
  // Non-empty cells in lattice order.
  std::vector<std::int32_t> kept;
  for (std::size_t cell = 0; cell < cellCounts.size(); ++cell)
  {
    if (cellCounts[cell] > 0)
    {
      kept.push_back(static_cast<std::int32_t>(cell));
    }
  }
  this->SortCells(kept, numberOfThreads);
  this->SetUpCells(kept, cellCounts, cellMasks);
  cellCounts = std::vector<std::uint32_t>();
  cellMasks = std::vector<std::uint64_t>();
  if (this->EndIfStopped())
  {
    return false;
  }
  const std::size_t pointCount = this->CellBegins.back();
  this->LayOutPlacedPoints(kept, numberOfThreads);
  if (this->EndIfStopped())
  {
    return false;
  }
  this->FinishCells(kept, pointCount, numberOfThreads);
  const bool stopped = this->EndIfStopped(); // (FinishCells asks too)
  this->Stop = nullptr;
  return !stopped;
}

void ProcessingOctree::CountPlacedPoints(std::vector<std::uint32_t>& cellCounts,
  std::vector<std::uint64_t>& cellMasks,
  int numberOfThreads)
{
  // Each cell's points and occupied leaves.
  const auto oldCellCount = static_cast<std::int64_t>(this->CellCoords.size());
  cellCounts.assign(this->CellCoords.size(), 0);
  cellMasks.assign(this->CellCoords.size(), 0);
#pragma omp parallel for schedule(dynamic, CellsPerAsk) num_threads(numberOfThreads)
  for (std::int64_t cell = 0; cell < oldCellCount; ++cell)
  {
    if (this->StopSeen(cell))
    {
      continue;
    }
    std::uint32_t count = 0;
    std::uint64_t mask = 0;
    for (std::int32_t index = this->NextHead[cell]; index >= 0; index = this->NextLink[index])
    {
      ++count;
      mask |= std::uint64_t{ 1 } << this->NextLeaf[index];
    }
    cellCounts[cell] = count;
    cellMasks[cell] = mask;
  }
}

void ProcessingOctree::LayOutPlacedPoints(const std::vector<std::int32_t>& kept,
  int numberOfThreads)
{
  // The new layout from the placed points: their ids and moved positions, by leaf, each leaf
  // sorted. The coordinate arrays of the last iteration are free to take it.
  const std::size_t pointCount = this->CellBegins.back();
  ReserveWithHugePages(pointCount, this->CompactedIds);
  this->CompactedIds.resize(pointCount);
  this->X.resize(pointCount);
  this->Y.resize(pointCount);
  this->Z.resize(pointCount);
  const LeafOrder order{
    this->MovedX.data(), this->MovedY.data(), this->MovedZ.data(), this->Ids.data()
  };
  const auto signedNewCellCount = static_cast<std::int64_t>(kept.size());
#pragma omp parallel num_threads(numberOfThreads)
  {
    std::vector<std::uint32_t> listed, sorted;
#pragma omp for schedule(dynamic, CellsPerAsk)
    for (std::int64_t cell = 0; cell < signedNewCellCount; ++cell)
    {
      if (this->StopSeen(cell))
      {
        continue;
      }
      listed.clear();
      for (std::int32_t index = this->NextHead[kept[cell]]; index >= 0;
           index = this->NextLink[index])
      {
        listed.push_back(static_cast<std::uint32_t>(index));
      }
      const std::uint32_t cellBegin = this->CellBegins[cell];
      OrderCellPoints(
        listed.data(),
        listed.size(),
        [this](std::uint32_t i) { return this->NextLeaf[i]; },
        order,
        cellBegin,
        sorted,
        this->LeafEnds.data() + this->LeafSlots[cell]);
      std::uint32_t to = cellBegin;
      for (const std::uint32_t from : sorted)
      {
        this->CompactedIds[to] = this->Ids[from];
        this->X[to] = this->MovedX[from];
        this->Y[to] = this->MovedY[from];
        this->Z[to] = this->MovedZ[from];
        ++to;
      }
    }
  }
  this->Ids.swap(this->CompactedIds);
}

void ProcessingOctree::ReleaseAllButMoves()
{
  auto release = [](auto& vector) { std::decay_t<decltype(vector)>().swap(vector); };
  release(this->X);
  release(this->Y);
  release(this->Z);
  release(this->CompactedIds);
  release(this->NextHead);
  release(this->NextLink);
  release(this->NextLeaf);
  release(this->LeafMasks);
  release(this->CellBegins);
  release(this->LeafSlots);
  release(this->LeafEnds);
  release(this->CellCoords);
  this->CellIndex = CellIndexMap();
  this->CellIndex.Clear(0);
  this->NumberOfProcessingCells = 0;
}

void ProcessingOctree::GetNeighbourCells(std::size_t cell, std::int32_t neighbours[27]) const
{
  const LatticeCoord& c = this->CellCoords[cell];
  const auto stored = static_cast<std::int64_t>(this->CellCoords.size());
  // Whether the cell numbered `guess` (perhaps none) is the one at `at`.
  auto isAt = [this, stored](std::int64_t guess, const LatticeCoord& at)
  { return guess >= 0 && guess < stored && this->CellCoords[guess] == at; };
  for (int dz = -1; dz <= 1; ++dz)
  {
    for (int dy = -1; dy <= 1; ++dy)
    {
      // A layout numbers the cells in lattice order, so the cells of a row (one y and z) that
      // exist are numbered one after the other: found the first, the next is checked beside
      // it rather than looked up (a hash lookup is a cache miss or two). In the cell's own row
      // its own number is known.
      const bool ownRow = dy == 0 && dz == 0;
      std::int64_t previous = ownRow ? static_cast<std::int64_t>(cell) - 2 : -2;
      for (int dx = -1; dx <= 1; ++dx)
      {
        const LatticeCoord at{ c.X + dx, c.Y + dy, c.Z + dz };
        std::int32_t found;
        if (ownRow && dx == 0)
        {
          found = static_cast<std::int32_t>(cell);
        }
        else if (isAt(previous + 1, at))
        {
          found = static_cast<std::int32_t>(previous + 1);
        }
        else
        {
          found = this->FindCell(at);
        }
        neighbours[NeighbourSlot(dx, dy, dz)] = found;
        previous = found == NoCell ? -2 : found;
      }
    }
  }
}

} // namespace pcbilateral
