// The octree that sorts the points for Algorithm 2 of Digne & de Franchis (IPOL 2017).
// Plain C++17, no VTK types.
#ifndef pcbilateral_ProcessingOctree_h
#define pcbilateral_ProcessingOctree_h

#include "PointArray.h"

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace pcbilateral
{

/// Integer coordinates of a cell or a leaf on the octree's lattice (may be negative: points
/// that drift out of the root cube keep their place on the same lattice). 32 bits each: the
/// filter refuses clouds more than 1e8 radii wide, about 2e8 leaves, and a point drifts by less
/// than 2 leaves per iteration. 12 bytes rather than 24 per stored cell: sparse clouds have up
/// to a cell per two points.
struct LatticeCoord
{
  std::int32_t X = 0, Y = 0, Z = 0;
  bool operator==(const LatticeCoord& other) const
  {
    return X == other.X && Y == other.Y && Z == other.Z;
  }
};

struct LatticeCoordHash
{
  std::size_t operator()(const LatticeCoord& c) const;
};

/**
 * The index of each stored cell by its lattice coordinates: open addressing with linear
 * probing in one flat array (no node per cell, usually one cache line per lookup), which
 * matters for clouds of millions of sparse cells: with it instead of std::unordered_map, the
 * whole run on a 1M-point noisy sphere at the automatic radius went from 1.67 s to 1.11 s.
 * A slot holds the cell's index and 32 bits of its hash, not its coordinates, which the caller
 * keeps by index (`coords`): 8 bytes instead of 32, so the map, two to four slots per cell,
 * costs sparse clouds (up to a cell per two points) some 40 bytes per point less at their peak;
 * the coordinates are read only when the hash bits agree.
 * Lookups may run in parallel; insertions may not.
 */
class CellIndexMap
{
public:
  static constexpr std::int32_t Missing = -1;
  void Clear(std::size_t expectedCells);
  /// The index of the cell, whose coordinates are coords[index], or Missing.
  std::int32_t Find(const LatticeCoord& cell, const LatticeCoord* coords) const;
  /// The index stored for the cell, or `index` if there was none (then stored); coords holds
  /// the coordinates of the cells stored so far, by index.
  std::int32_t Insert(const LatticeCoord& cell, std::int32_t index, const LatticeCoord* coords);
  /// Stores the `count` distinct cells coords[0] to coords[count - 1] as indices 0 to count - 1
  /// in a cleared map, with numberOfThreads threads. The map's layout may depend on the
  /// threads; what Find returns does not.
  void InsertDistinct(const LatticeCoord* coords, std::size_t count, int numberOfThreads);

private:
  // Eight bytes, aligned, so that InsertDistinct can claim a slot with one compare-and-swap.
  struct alignas(8) Slot
  {
    std::uint32_t Tag = 0;
    std::int32_t Index = Missing;
  };
  void Grow(const LatticeCoord* coords);
  std::vector<Slot> Slots; // a power of two, at most half full
  std::size_t Count = 0;
};

/**
 * An octree over a root cube around the points, kept only down to two levels:
 * - processing cells: the octree's cells at the processing depth, the smallest cells whose
 *   size is at least 2.1 r (and at least one level below the root). Their child index (the
 *   parities of their lattice coordinates) is their colour: two cells of one colour are at
 *   least one cell size apart, so their r-dilations share no leaf.
 * - leaves: each processing cell split LeavesPerAxis times per axis (two octree levels
 *   further down). A leaf holds its points sorted by coordinates, so that every traversal
 *   order is defined by geometry alone: a cloud gives the same sums however its points are
 *   numbered.
 *
 * Only non-empty cells are stored. Each iteration reads the points from a compact layout
 * (ids and coordinates contiguous per leaf, leaves contiguous per cell), writes their moved
 * positions in the same order, and places them into per-leaf lists for the next iteration, so
 * that the points stay sorted by place from one iteration to the next and are read and written
 * in order. A cell's list is written by one thread at a time without locks: the caller
 * guarantees it (the colouring invariant).
 */
class ProcessingOctree
{
public:
  static constexpr int LeavesPerAxis = 4;
  static constexpr int LeavesPerCell = LeavesPerAxis * LeavesPerAxis * LeavesPerAxis;
  /// Index of a cell's neighbour (dx, dy, dz in -1..1) in a cell's neighbour table.
  static int NeighbourSlot(int dx, int dy, int dz)
  {
    return (dx + 1) + 3 * ((dy + 1) + 3 * (dz + 1));
  }
  static constexpr int CentreSlot = 13;
  static constexpr std::int32_t NoCell = -1;

  /// Builds the geometry for points in [boundsMin, boundsMax] and radius r > 0.
  ProcessingOctree(const double boundsMin[3], const double boundsMax[3], double radius);

  ///@{
  /// Geometry of the lattice.
  const double* GetRootOrigin() const { return this->RootOrigin.data(); }
  double GetRootSize() const { return this->RootSize; }
  int GetProcessingDepth() const { return this->ProcessingDepth; }
  double GetCellSize() const { return this->CellSize; }
  double GetLeafSize() const { return this->LeafSize; }
  ///@}

  /// The leaf (global lattice coordinates) holding point p. Inline, as the two below: every
  /// point asks them once per iteration, and on a cloud of tens of millions of points the calls
  /// weighed.
  LatticeCoord LeafOf(const double p[3]) const
  {
    // Floor by truncation and a correction: lattice coordinates are far inside 32-bit integers
    // (see LatticeCoord).
    auto floorToInteger = [](double value)
    {
      const auto truncated = static_cast<std::int64_t>(value);
      return static_cast<std::int32_t>(
        truncated - (value < static_cast<double>(truncated) ? 1 : 0));
    };
    LatticeCoord leaf;
    leaf.X = floorToInteger((p[0] - this->RootOrigin[0]) / this->LeafSize);
    leaf.Y = floorToInteger((p[1] - this->RootOrigin[1]) / this->LeafSize);
    leaf.Z = floorToInteger((p[2] - this->RootOrigin[2]) / this->LeafSize);
    return leaf;
  }
  /// The processing cell holding a leaf, and the leaf's index inside that cell: the floor of
  /// the leaf's coordinates over 4, and their remainders, as shifts and masks (an arithmetic
  /// shift floors negative coordinates too).
  static LatticeCoord CellOfLeaf(const LatticeCoord& leaf)
  {
    static_assert(LeavesPerAxis == 4, "cells of 4 x 4 x 4 leaves: a shift by 2 and a mask of 3");
    return LatticeCoord{ leaf.X >> 2, leaf.Y >> 2, leaf.Z >> 2 };
  }
  static int LocalLeafIndex(const LatticeCoord& leaf)
  {
    return (leaf.X & 3) + LeavesPerAxis * ((leaf.Y & 3) + LeavesPerAxis * (leaf.Z & 3));
  }
  /// Colour of a processing cell: its child index in the octree, 0 to 7.
  static int ColourOf(const LatticeCoord& cell)
  {
    return static_cast<int>((cell.X & 1) | ((cell.Y & 1) << 1) | ((cell.Z & 1) << 2));
  }

  /**
   * Takes the points to filter: the finite ones among `count` interleaved xyz positions, which
   * keep their index as id, and lays them out for the first iteration with numberOfThreads
   * threads (as Compact lays out placed points). `shouldStop`, when given, is asked between
   * the passes over the points (each well under a second for 20 million points): when it says
   * stop, the octree is left empty and Load returns false (an aborted run).
   */
  bool Load(const double* positions,
    std::size_t count,
    int numberOfThreads = 1,
    const std::function<bool()>& shouldStop = nullptr);

  ///@{
  /// Placement of points into the next iteration's leaf lists. A point is named by its index
  /// in this iteration's layout (GetIds and the coordinate arrays); its place is that of its
  /// moved position (GetMovedX...). FindOrCreateCell and PlaceSerially may only be called
  /// while no thread places points.
  std::int32_t FindCell(const LatticeCoord& cell) const;
  std::int32_t FindOrCreateCell(const LatticeCoord& cell);
  void PlaceSerially(std::uint32_t index);
  /// Lock-free placement into an existing cell: no other thread may place into the same cell
  /// at the same time.
  void Place(std::uint32_t index, std::int32_t cell, int localLeaf)
  {
    std::int32_t& head = this->NextHead[cell];
    this->Link(index, localLeaf, head);
  }
  /// Puts point `index` (in leaf `localLeaf` of the cell it goes to) at the front of a list
  /// whose head the caller keeps; PlaceList then hands the whole list to its cell. Threads that
  /// place many points this way write the cells' shared heads once per list, not per point.
  void Link(std::uint32_t index, int localLeaf, std::int32_t& head)
  {
    this->NextLeaf[index] = static_cast<std::uint8_t>(localLeaf);
    this->NextLink[index] = head;
    head = static_cast<std::int32_t>(index);
  }
  /// Appends a list made with Link (first and last point) to an existing cell's list. Other
  /// threads may hand lists to the same cell at the same time: two cells of one colour share no
  /// leaf of their r-dilations, but the cells between them are in both, and a cell's leaves
  /// share its list head. So the head is swapped atomically; the order of the lists in it does
  /// not matter (Compact orders each leaf's points by coordinates).
  void PlaceList(std::int32_t cell, std::int32_t first, std::int32_t last)
  {
    std::int32_t& head = this->NextHead[cell];
    // (GCC's and clang's atomic builtins on a plain int32_t: C++17 has no std::atomic_ref, and
    // NextHead grows while no thread places points, which a vector of atomics could not.)
    std::int32_t old = __atomic_load_n(&head, __ATOMIC_RELAXED);
    do
    {
      this->NextLink[last] = old;
    } while (
      !__atomic_compare_exchange_n(&head, &old, first, true, __ATOMIC_RELEASE, __ATOMIC_RELAXED));
  }
  ///@}

  /**
   * After an iteration has placed its points: turns them into the layout read by the next
   * iteration: drops empty cells, sorts cells by lattice coordinates and each leaf's points by
   * coordinates, lays out their ids and moved positions in that order. `shouldStop`, when
   * given, is asked as Load asks it (between the steps, and every few thousand cells within
   * them): when it says stop, the octree is left empty and Compact returns false.
   */
  bool Compact(int numberOfThreads, const std::function<bool()>& shouldStop = nullptr);

  ///@{
  /// The layout of this iteration (valid after Load or Compact).
  /// Cells that held points at the last layout, numbered 0 to this count - 1. Cells created
  /// while placing come after them.
  std::size_t GetNumberOfProcessingCells() const { return this->NumberOfProcessingCells; }
  const LatticeCoord& GetCellCoord(std::size_t cell) const { return this->CellCoords[cell]; }
  /// The 27 cells around a cell (itself in CentreSlot), NoCell where none is stored. Looked up
  /// rather than stored: clouds of sparse cells would spend more on such tables than on points.
  void GetNeighbourCells(std::size_t cell, std::int32_t neighbours[27]) const;
  /// The end of a cell's points in the arrays below (they start at the previous cell's end).
  std::uint32_t GetCellEnd(std::size_t cell) const { return this->CellBegins[cell + 1]; }
  /// The leaves of a cell that hold points: bit l for leaf l.
  std::uint64_t GetLeafMask(std::size_t cell) const { return this->LeafMasks[cell]; }
  /// Points of leaves `first` to `last` of `cell`: indices [begin, end) in the arrays below
  /// (empty when the leaves hold none).
  void GetLeavesRange(std::size_t cell,
    int first,
    int last,
    std::uint32_t& begin,
    std::uint32_t& end) const
  {
    const std::uint64_t mask = this->LeafMasks[cell];
    const int before = Popcount(mask & ((std::uint64_t{ 1 } << first) - 1));
    const int upToLast = Popcount(mask & (~std::uint64_t{ 0 } >> (LeavesPerCell - 1 - last)));
    const std::uint32_t* ends = this->LeafEnds.data() + this->LeafSlots[cell];
    begin = before ? ends[before - 1] : this->CellBegins[cell];
    end = upToLast ? ends[upToLast - 1] : this->CellBegins[cell];
  }
  void GetLeafRange(std::size_t cell, int localLeaf, std::uint32_t& begin, std::uint32_t& end) const
  {
    this->GetLeavesRange(cell, localLeaf, localLeaf, begin, end);
  }
  const std::uint32_t* GetIds() const { return this->Ids.data(); }
  const double* GetX() const { return this->X.data(); }
  const double* GetY() const { return this->Y.data(); }
  const double* GetZ() const { return this->Z.data(); }
  std::size_t GetNumberOfPoints() const { return this->Ids.size(); }
  ///@}

  /// After the last iteration: frees all but GetIds and the moved positions (what is needed to
  /// write the moves back by id), so that the output can be allocated in their place. No
  /// iteration can follow.
  void ReleaseAllButMoves();

  ///@{
  /// Where the points of this iteration go, by index in its layout: written by the filter
  /// before it places them, read by the next Compact.
  double* GetMovedX() { return this->MovedX.data(); }
  double* GetMovedY() { return this->MovedY.data(); }
  double* GetMovedZ() { return this->MovedZ.data(); }
  ///@}

private:
  std::array<double, 3> RootOrigin;
  double RootSize;
  int ProcessingDepth;
  double CellSize;
  double LeafSize;

  // Cells: lattice coordinates and where to find them. Cells created while placing are
  // appended; Compact renumbers.
  std::vector<LatticeCoord> CellCoords;
  CellIndexMap CellIndex;
  std::size_t NumberOfProcessingCells = 0;

  /// Set bits, counted without the popcnt instruction, which x86-64's baseline lacks (the
  /// builtin would call a slower library function).
  static int Popcount(std::uint64_t bits)
  {
    bits = bits - ((bits >> 1) & 0x5555555555555555ULL);
    bits = (bits & 0x3333333333333333ULL) + ((bits >> 2) & 0x3333333333333333ULL);
    bits = (bits + (bits >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
    return static_cast<int>((bits * 0x0101010101010101ULL) >> 56);
  }

  /// Load's stop: its shouldStop, asked by the calling thread only (thread 0 of a parallel
  /// pass), and whether it said stop, seen by every thread, which then skip their remaining
  /// chunks (the octree is emptied after).
  struct LoadStop
  {
    const std::function<bool()>* Ask = nullptr;
    std::atomic<bool> Stopped{ false };
  };
  LoadStop* Stop = nullptr;
  bool StopAsked() const;
  /// In a pass over the cells: StopAsked at the first of each block of cells, else whether a
  /// stop was seen already (a relaxed load).
  bool StopSeen(std::int64_t cell) const;
  /// Whether the load was asked to stop; if so, the octree is emptied.
  bool EndIfStopped();

  /// Load's steps: empty tables with room for `count` points; each finite point's (Ids) cell
  /// in NextLink and leaf in NextLeaf.
  void Reset(std::size_t count);
  void AssignCellsAndLeaves(const double* positions, int numberOfThreads);
  /// Load places the points through buckets, runs of consecutive cells of the new layout:
  /// FirstCell[b] to FirstCell[b + 1] - 1 make bucket b; by old cell number, its bucket and its
  /// code, its number within the bucket shifted left by 6 with room for a leaf index.
  struct LoadBuckets
  {
    std::size_t Count = 0;
    std::vector<std::uint32_t> FirstCell;
    std::vector<std::uint32_t> BucketOfCell;
    std::vector<std::uint32_t> CellCode;
  };
  LoadBuckets PlanBuckets(const std::vector<std::int32_t>& kept) const;
  /// Sizes the layout's arrays for the points (and `codes`) and takes their page faults
  /// (TouchPages); false if asked to stop meanwhile.
  bool TouchLayout(PointArray<std::uint32_t>& codes, int numberOfThreads);
  /// Compact's steps: each cell's placed points and occupied leaves; the placed points' layout
  /// in the `kept` cells' new order.
  void CountPlacedPoints(std::vector<std::uint32_t>& cellCounts,
    std::vector<std::uint64_t>& cellMasks,
    int numberOfThreads);
  void LayOutPlacedPoints(const std::vector<std::int32_t>& kept, int numberOfThreads);
  /// Writes every point's position and id into its bucket's stretch of the layout, and its cell
  /// code with its leaf index into `codes`.
  void ScatterToBuckets(const double* positions,
    const LoadBuckets& buckets,
    PointArray<std::uint32_t>& codes,
    int numberOfThreads);
  /// One thread's copies of a bucket, kept from one bucket to the next.
  struct BucketScratch
  {
    std::vector<double> X, Y, Z;
    std::vector<std::uint32_t> Ids, Codes, ByCell, CellStarts, Sorted;
  };
  /// Orders every bucket's points into the layout (cell by cell, leaf by leaf, by coordinates).
  void OrderBuckets(const LoadBuckets& buckets,
    const PointArray<std::uint32_t>& codes,
    int numberOfThreads);
  void OrderBucket(std::uint32_t firstCell,
    std::uint32_t endCell,
    const PointArray<std::uint32_t>& codes,
    BucketScratch& scratch);
  /// Sorts `kept` (cell numbers) into lattice order; the cells of the last layout, numbered
  /// below NumberOfProcessingCells in that order already, must come first.
  void SortCells(std::vector<std::int32_t>& kept, int numberOfThreads) const;
  /// The layout's cell tables for the cells `kept` (old numbers, in their new order), given
  /// each old cell's number of points and leaf mask; LeafEnds is sized, not filled.
  void SetUpCells(const std::vector<std::int32_t>& kept,
    const std::vector<std::uint32_t>& cellCounts,
    const std::vector<std::uint64_t>& cellMasks);
  /// Renumbers the cells as `kept` orders them and readies the lists of the next iteration.
  void FinishCells(const std::vector<std::int32_t>& kept,
    std::size_t pointCount,
    int numberOfThreads);

  // Next iteration: per cell, the head of a list of indices linked through NextLink (-1 ends
  // it), and each index's leaf in its cell.
  std::vector<std::int32_t> NextHead;
  PointArray<std::int32_t> NextLink;
  PointArray<std::uint8_t> NextLeaf;

  // This iteration: ids and coordinates sorted by cell, leaf, then coordinates; the moved
  // positions by the same index. Only leaves that hold points are stored: a cell's points
  // start at CellBegins[cell]; its occupied leaves, in order, end at LeafEnds[LeafSlots[cell]]
  // and on.
  std::vector<std::uint64_t> LeafMasks;
  std::vector<std::uint32_t> CellBegins, LeafSlots, LeafEnds;
  PointArray<std::uint32_t> Ids, CompactedIds;
  PointArray<double> X, Y, Z;
  PointArray<double> MovedX, MovedY, MovedZ;
};

} // namespace pcbilateral

#endif
