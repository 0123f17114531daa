#include "PointGrid.h"

#include <algorithm>
#include <cmath>

namespace pcbilateral
{

namespace
{
/// Cell coordinates are computed in double precision and must stay below this magnitude.
/// (Within 2^53 they would be exact; 1e15 leaves room for the range of a ball around them.)
constexpr double LargestCellCoordinate = 1e15;

/// A point with its cell, sorted by cell and then by coordinates.
struct GridEntry
{
  std::int64_t Key[3];
  double P[3];
  std::uint32_t Id;
};

bool EntryBefore(const GridEntry& a, const GridEntry& b)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    if (a.Key[axis] != b.Key[axis])
    {
      return a.Key[axis] < b.Key[axis];
    }
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (a.P[axis] != b.P[axis])
    {
      return a.P[axis] < b.P[axis];
    }
  }
  return false;
}

bool KeyLess(const std::int64_t* a, const std::int64_t* b)
{
  return a[0] != b[0] ? a[0] < b[0] : (a[1] != b[1] ? a[1] < b[1] : a[2] < b[2]);
}

/// floor((value - origin) / cellSize) when it is exact, else false.
bool CellCoordinate(double value, double origin, double cellSize, std::int64_t& key)
{
  const double cell = std::floor((value - origin) / cellSize);
  if (!(std::abs(cell) < LargestCellCoordinate))
  {
    return false;
  }
  key = static_cast<std::int64_t>(cell);
  return true;
}
} // namespace

bool PointGrid::Build(const double* positions,
  const std::vector<std::uint32_t>& ids,
  const double origin[3],
  double cellSize)
{
  *this = PointGrid();
  std::copy(origin, origin + 3, this->Origin);
  this->CellSize = cellSize;
  std::vector<GridEntry> entries(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    GridEntry& entry = entries[k];
    const double* p = positions + 3 * static_cast<std::size_t>(ids[k]);
    for (int axis = 0; axis < 3; ++axis)
    {
      if (!CellCoordinate(p[axis], origin[axis], cellSize, entry.Key[axis]))
      {
        *this = PointGrid();
        return false;
      }
      entry.P[axis] = p[axis];
    }
    entry.Id = ids[k];
  }
  std::sort(entries.begin(), entries.end(), EntryBefore);
  const std::size_t n = entries.size();
  this->Ids.resize(n);
  this->X.resize(n);
  this->Y.resize(n);
  this->Z.resize(n);
  this->CellOfPoint.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const GridEntry& entry = entries[i];
    this->Ids[i] = entry.Id;
    this->X[i] = entry.P[0];
    this->Y[i] = entry.P[1];
    this->Z[i] = entry.P[2];
    const std::size_t cells = this->CellBegin.size();
    if (cells == 0 || !std::equal(entry.Key, entry.Key + 3, &this->CellKey[3 * (cells - 1)]))
    {
      this->CellKey.insert(this->CellKey.end(), entry.Key, entry.Key + 3);
      this->CellBegin.push_back(static_cast<std::uint32_t>(i));
    }
    this->CellOfPoint[i] = static_cast<std::uint32_t>(this->CellBegin.size() - 1);
  }
  this->CellBegin.push_back(static_cast<std::uint32_t>(n));
  return true;
}

void PointGrid::ComputeNeighbourRuns(int threads)
{
  const std::size_t cells = this->CellBegin.empty() ? 0 : this->CellBegin.size() - 1;
  this->NeighbourRuns.assign(18 * cells, 0);
  const auto cellCount = static_cast<std::int64_t>(cells);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t cell = 0; cell < cellCount; ++cell)
  {
    const std::int64_t* key = &this->CellKey[3 * static_cast<std::size_t>(cell)];
    std::uint32_t* runs = &this->NeighbourRuns[18 * static_cast<std::size_t>(cell)];
    for (std::int64_t dx = -1; dx <= 1; ++dx)
    {
      for (std::int64_t dy = -1; dy <= 1; ++dy, runs += 2)
      {
        std::int64_t first = -1, last = -1;
        for (std::int64_t dz = -1; dz <= 1; ++dz)
        {
          const std::int64_t wanted[3] = { key[0] + dx, key[1] + dy, key[2] + dz };
          const std::int64_t found = this->FindCell(wanted);
          if (found >= 0)
          {
            first = first < 0 ? found : first;
            last = found;
          }
        }
        if (first >= 0)
        {
          runs[0] = this->CellBegin[static_cast<std::size_t>(first)];
          runs[1] = this->CellBegin[static_cast<std::size_t>(last) + 1];
        }
      }
    }
  }
}

std::size_t PointGrid::LowerBound(const std::int64_t key[3]) const
{
  std::size_t low = 0, high = this->CellBegin.size() - 1;
  while (low < high)
  {
    const std::size_t middle = (low + high) / 2;
    if (KeyLess(&this->CellKey[3 * middle], key))
    {
      low = middle + 1;
    }
    else
    {
      high = middle;
    }
  }
  return low;
}

std::int64_t PointGrid::FindCell(const std::int64_t key[3]) const
{
  const std::size_t cell = this->LowerBound(key);
  if (cell < this->CellBegin.size() - 1 && std::equal(key, key + 3, &this->CellKey[3 * cell]))
  {
    return static_cast<std::int64_t>(cell);
  }
  return -1;
}

bool PointGrid::CellRange(const double centre[3],
  double radius,
  std::int64_t low[3],
  std::int64_t high[3]) const
{
  // (A ball beyond what the lattice can index holds none of its points.)
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!CellCoordinate(centre[axis] - radius, this->Origin[axis], this->CellSize, low[axis]) ||
        !CellCoordinate(centre[axis] + radius, this->Origin[axis], this->CellSize, high[axis]))
    {
      return false;
    }
  }
  return true;
}

} // namespace pcbilateral
