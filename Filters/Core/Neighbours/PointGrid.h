// The core's neighbour search for everything but the paper's scheduler: a uniform grid whose
// points are sorted by cell, then by coordinates. Plain C++17, no VTK types.
//
// Why two neighbour structures, this one and Octree/ProcessingOctree: the scheduler's octree is
// tied to one radius (cells of at least 2.1 r, leaves a quarter of that, colour classes for
// lock-free parallel writes) and keeps its points placed from one iteration to the next: each
// filtered point is put into its next leaf while its cell is processed, so no iteration sorts
// the cloud again. This grid serves what the octree cannot: balls of any radius (the
// measurement's fits, a radius per point), cell sizes chosen by the caller, and searches
// whose visiting order must follow the coordinates (the edge-aware mode). Built for one
// iteration, it costs a sort of the cloud. Measured on a noisy sphere of 1M points at the
// paper's radius, 2 threads: Build 0.28-0.31 s and the 27-cell neighbour runs 0.67-0.74 s,
// against 0.14 s for the octree's own re-layout between iterations (Compact), of 1.2 s for a
// whole iteration: in place of the octree, the grid would add most of an iteration's time.
#ifndef pcbilateral_PointGrid_h
#define pcbilateral_PointGrid_h

#include "PointArray.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{

/**
 * Points grouped into cubic cells of one size anchored at an origin, in one of two layouts:
 * - PointOrder::ByCoordinates: cells sorted by their integer coordinates (x, then y, then z),
 *   each cell's points by coordinates. A search visits cells in that order and each cell's
 *   points in it, so it meets the points in an order that depends on their coordinates alone,
 *   never on their ids or on the number of threads (the edge-aware mode's sums need this).
 *   Points with equal coordinates are interchangeable (every result computed from them is
 *   equal too).
 * - PointOrder::Any: cells sorted as above, each cell's points in no particular order, and the
 *   (x, y) columns of cells found by hashing. The cells are sorted by a radix sort of their
 *   coordinates packed into one integer, so the layout costs a few passes over the points
 *   instead of a comparison sort; a search makes one hash probe per column instead of a binary
 *   search (the measurement, which sorts what it gathers itself, or only counts). When the
 *   packed coordinates would not fit 64 bits, the points are laid out ByCoordinates instead
 *   (still a valid Any layout).
 */
class PointGrid
{
public:
  enum class PointOrder
  {
    Any,
    ByCoordinates
  };

  /// Groups the points `ids` (indices of finite points of `positions`, interleaved x y z) into
  /// cells of `cellSize` from `origin`. Returns false, and holds nothing, when a cell's integer
  /// coordinates would be beyond 1e15 or not finite, for a cell size or coordinates beyond what
  /// the lattice can index.
  bool Build(const double* positions,
    const std::vector<std::uint32_t>& ids,
    const double origin[3],
    double cellSize,
    PointOrder order);

  /// The grid's points: their ids and coordinates, by index in the layout.
  std::size_t Size() const { return this->Ids.size(); }
  const std::uint32_t* GetIds() const { return this->Ids.data(); }
  const double* GetX() const { return this->X.data(); }
  const double* GetY() const { return this->Y.data(); }
  const double* GetZ() const { return this->Z.data(); }
  double GetCellSize() const { return this->CellSize; }
  /// The cell of point i of the layout, an index into the cells (0 to the number of cells - 1);
  /// ByCoordinates layout only.
  std::uint32_t GetCellOfPoint(std::size_t i) const { return this->CellOfPoint[i]; }
  /// The number of cells holding points, and the integer coordinates (3) of one of them.
  std::size_t GetNumberOfCells() const { return this->CellKey.size() / 3; }
  const std::int64_t* GetCellCoordinates(std::uint32_t cell) const
  {
    return &this->CellKey[3 * static_cast<std::size_t>(cell)];
  }

  /**
   * In the ByCoordinates layout, for cells at least as wide as the search radius: the points of
   * each cell's 27 neighbour cells, as 9 runs of consecutive indices (begin, end) per cell, one
   * per (dx, dy) column (cells are sorted by z last, so (x, y, z - 1), (x, y, z) and
   * (x, y, z + 1) are consecutive). Computed in parallel; read with GetNeighbourRuns.
   */
  void ComputeNeighbourRuns(int threads);
  /// The 18 numbers (9 runs) of ComputeNeighbourRuns for a cell.
  const std::uint32_t* GetNeighbourRuns(std::uint32_t cell) const
  {
    return &this->NeighbourRuns[18 * static_cast<std::size_t>(cell)];
  }

  /// Calls visit(index in the layout, |q - centre|^2) for each point q with
  /// |q - centre|^2 <= radius^2, cell by cell in the layout's order. A ball that spans more cells
  /// than there are points is answered by looking at every point.
  template<typename Visit>
  void ForEachInBall(const double centre[3], double radius, Visit&& visit) const;

  /// Calls visitRun(begin, end) for runs of consecutive layout indices that hold every point of
  /// the ball and others near it (the cells its bounding box spans, or every point), in the
  /// order ForEachInBall visits them: for loops that test the distance themselves, without a
  /// branch per point.
  template<typename VisitRun>
  void ForEachRunAroundBall(const double centre[3], double radius, VisitRun&& visitRun) const;

private:
  /// The ByCoordinates layout: every point sorted by cell, then by coordinates.
  void LayOutByCoordinates(const double* positions,
    const std::vector<std::uint32_t>& ids,
    const PointArray<std::int64_t>& keys);
  /// The Any layout: the points radix-sorted by their packed cell coordinates, then the
  /// columns' hash table. False when the packed coordinates would not fit 64 bits.
  bool LayOutInColumns(const double* positions,
    const std::vector<std::uint32_t>& ids,
    const PointArray<std::int64_t>& keys);
  /// The column (x, y) packed into one integer (PackedColumn), or false when no cell has
  /// these coordinates' range.
  bool PackColumn(std::int64_t x, std::int64_t y, std::uint64_t& packed) const;
  /// The first cell of column (x, y) in the Any layout, or -1.
  std::int64_t FindColumn(std::int64_t x, std::int64_t y) const;
  /// Cell coordinates packed into one integer, in the order of the coordinates (Any layout).
  std::uint64_t Pack(const std::int64_t key[3]) const;
  /// Fills the columns' hash table from the sorted cells.
  void HashColumns();
  static constexpr std::uint64_t EmptyColumn = ~std::uint64_t(0);
  /// Puts point `id` (at p, in cell `key`) at index `at` of the layout, the next one, starting
  /// a new cell when the key differs from the last cell's.
  void Place(std::size_t at, std::uint32_t id, const double p[3], const std::int64_t key[3]);
  /// The first cell whose coordinates are at least `key`, or the number of cells (ByCoordinates).
  std::size_t LowerBound(const std::int64_t key[3]) const;
  /// The cell with these coordinates, or -1 (either layout).
  std::int64_t FindCell(const std::int64_t key[3]) const;
  /// The range of cells a ball spans along each axis; false when it is beyond the lattice.
  bool CellRange(const double centre[3],
    double radius,
    std::int64_t low[3],
    std::int64_t high[3]) const;

  PointArray<std::uint32_t> Ids;
  PointArray<double> X, Y, Z;
  PointArray<std::uint32_t> CellOfPoint;
  /// Per cell: its integer coordinates (3), and where its points begin (one more entry than
  /// cells).
  std::vector<std::int64_t> CellKey;
  std::vector<std::uint32_t> CellBegin;
  std::vector<std::uint32_t> NeighbourRuns;
  /// The Any layout's columns: cell coordinates less KeyMin, packed as x << (YBits + ZBits) |
  /// y << ZBits | z; an open-addressing hash table (a power of two of slots, an empty slot's
  /// key is EmptyColumn) from a column's packed (x, y) to its first cell.
  std::int64_t KeyMin[3] = { 0, 0, 0 };
  std::int64_t KeyMax[3] = { -1, -1, -1 };
  int YBits = 0, ZBits = 0;
  std::vector<std::uint64_t> ColumnKey;
  std::vector<std::uint32_t> ColumnFirstCell;
  PointOrder Order = PointOrder::ByCoordinates;
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double CellSize = 1.0;
};

template<typename Visit>
void PointGrid::ForEachInBall(const double centre[3], double radius, Visit&& visit) const
{
  const double radiusSquared = radius * radius;
  this->ForEachRunAroundBall(centre,
    radius,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t i = begin; i < end; ++i)
      {
        const double dx = this->X[i] - centre[0], dy = this->Y[i] - centre[1],
                     dz = this->Z[i] - centre[2];
        const double distanceSquared = dx * dx + dy * dy + dz * dz;
        if (distanceSquared <= radiusSquared)
        {
          visit(i, distanceSquared);
        }
      }
    });
}

template<typename VisitRun>
void PointGrid::ForEachRunAroundBall(const double centre[3],
  double radius,
  VisitRun&& visitRun) const
{
  std::int64_t low[3], high[3];
  if (this->Ids.empty() || !this->CellRange(centre, radius, low, high))
  {
    return;
  }
  double cellsInRange = 1.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    cellsInRange *= static_cast<double>(high[axis] - low[axis] + 1);
  }
  if (cellsInRange > static_cast<double>(this->Ids.size()))
  {
    visitRun(0, this->Ids.size());
    return;
  }
  const std::size_t cells = this->CellBegin.size() - 1;
  for (std::int64_t x = low[0]; x <= high[0]; ++x)
  {
    for (std::int64_t y = low[1]; y <= high[1]; ++y)
    {
      // The cells (x, y, low z) to (x, y, high z) that exist are consecutive.
      std::size_t cell;
      if (this->Order == PointOrder::Any)
      {
        const std::int64_t column = this->FindColumn(x, y);
        if (column < 0)
        {
          continue;
        }
        cell = static_cast<std::size_t>(column);
        while (cell < cells && this->CellKey[3 * cell] == x && this->CellKey[3 * cell + 1] == y &&
               this->CellKey[3 * cell + 2] < low[2])
        {
          ++cell;
        }
      }
      else
      {
        const std::int64_t first[3] = { x, y, low[2] };
        cell = this->LowerBound(first);
      }
      std::size_t last = cell;
      while (last < cells && this->CellKey[3 * last] == x && this->CellKey[3 * last + 1] == y &&
             this->CellKey[3 * last + 2] <= high[2])
      {
        ++last;
      }
      if (last > cell)
      {
        visitRun(this->CellBegin[cell], this->CellBegin[last]);
      }
    }
  }
}

} // namespace pcbilateral

#endif
