#include "PointGrid.h"

#include "BitOperations.h"

#include <algorithm>
#include <cmath>

namespace pcbilateral
{

namespace
{
/// Cell coordinates are computed in double precision and must stay below this magnitude.
/// (Within 2^53 they would be exact; 1e15 leaves room for the range of a ball around them.)
constexpr double LargestCellCoordinate = 1e15;

/// A point with its cell, sorted by cell and then by coordinates (the ByCoordinates layout).
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
  double cellSize,
  PointOrder order)
{
  *this = PointGrid();
  std::copy(origin, origin + 3, this->Origin);
  this->CellSize = cellSize;
  this->Order = order;
  const std::size_t n = ids.size();
  PointArray<std::int64_t> keys(3 * n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const double* p = positions + 3 * static_cast<std::size_t>(ids[k]);
    for (int axis = 0; axis < 3; ++axis)
    {
      if (!CellCoordinate(p[axis], origin[axis], cellSize, keys[3 * k + axis]))
      {
        *this = PointGrid();
        return false;
      }
    }
  }
  this->Ids.resize(n);
  this->X.resize(n);
  this->Y.resize(n);
  this->Z.resize(n);
  this->CellOfPoint.resize(n);
  // (At most a cell per point; the first layout of a sparse cloud has nearly that many.)
  this->CellKey.reserve(3 * n);
  this->CellBegin.reserve(n + 1);
  if (order == PointOrder::ByCoordinates)
  {
    this->LayOutByCoordinates(positions, ids, keys);
  }
  else
  {
    this->LayOutInBuckets(positions, ids, keys);
  }
  this->CellBegin.push_back(static_cast<std::uint32_t>(n));
  return true;
}

void PointGrid::LayOutByCoordinates(const double* positions,
  const std::vector<std::uint32_t>& ids,
  const PointArray<std::int64_t>& keys)
{
  PointArray<GridEntry> entries(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    GridEntry& entry = entries[k];
    std::copy_n(&keys[3 * k], 3, entry.Key);
    std::copy_n(positions + 3 * static_cast<std::size_t>(ids[k]), 3, entry.P);
    entry.Id = ids[k];
  }
  std::sort(entries.begin(), entries.end(), EntryBefore);
  for (std::size_t at = 0; at < entries.size(); ++at)
  {
    this->Place(at, entries[at].Id, entries[at].P, entries[at].Key);
  }
}

void PointGrid::LayOutInBuckets(const double* positions,
  const std::vector<std::uint32_t>& ids,
  const PointArray<std::int64_t>& keys)
{
  const std::size_t n = ids.size();
  std::size_t buckets = 1;
  while (buckets < n)
  {
    buckets *= 2;
  }
  this->BucketFirstCell.assign(buckets + 1, 0);
  PointArray<std::uint32_t> bucketOf(n);
  std::vector<std::uint32_t> starts(buckets + 1, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    bucketOf[k] = static_cast<std::uint32_t>(this->BucketOf(&keys[3 * k]));
    ++starts[bucketOf[k] + 1];
  }
  for (std::size_t b = 0; b < buckets; ++b)
  {
    starts[b + 1] += starts[b];
  }
  PointArray<std::uint32_t> grouped(n);
  std::vector<std::uint32_t> next(starts.begin(), starts.end() - 1);
  for (std::size_t k = 0; k < n; ++k)
  {
    grouped[next[bucketOf[k]]++] = static_cast<std::uint32_t>(k);
  }
  for (std::size_t b = 0; b < buckets; ++b)
  {
    // The cells that share a bucket: its points grouped by cell.
    const auto first = grouped.begin() + starts[b], last = grouped.begin() + starts[b + 1];
    if (last - first > 1)
    {
      std::sort(first,
        last,
        [&](std::uint32_t a, std::uint32_t c) { return KeyLess(&keys[3 * a], &keys[3 * c]); });
    }
    this->BucketFirstCell[b] = static_cast<std::uint32_t>(this->CellBegin.size());
    for (std::uint32_t at = starts[b]; at < starts[b + 1]; ++at)
    {
      // (Equal keys share a bucket, so a bucket never continues the previous one's last cell.)
      const std::uint32_t k = grouped[at];
      this->Place(at, ids[k], positions + 3 * static_cast<std::size_t>(ids[k]), &keys[3 * k]);
    }
  }
  this->BucketFirstCell[buckets] = static_cast<std::uint32_t>(this->CellBegin.size());
}

void PointGrid::Place(std::size_t at,
  std::uint32_t id,
  const double p[3],
  const std::int64_t key[3])
{
  const std::size_t cells = this->CellBegin.size();
  if (cells == 0 || !std::equal(key, key + 3, &this->CellKey[3 * (cells - 1)]))
  {
    this->CellKey.push_back(key[0]);
    this->CellKey.push_back(key[1]);
    this->CellKey.push_back(key[2]);
    this->CellBegin.push_back(static_cast<std::uint32_t>(at));
  }
  this->Ids[at] = id;
  this->X[at] = p[0];
  this->Y[at] = p[1];
  this->Z[at] = p[2];
  this->CellOfPoint[at] = static_cast<std::uint32_t>(this->CellBegin.size() - 1);
}

std::size_t PointGrid::BucketOf(const std::int64_t key[3]) const
{
  const std::uint64_t hash = static_cast<std::uint64_t>(key[0]) * 73856093ull ^
                             static_cast<std::uint64_t>(key[1]) * 19349663ull ^
                             static_cast<std::uint64_t>(key[2]) * 83492791ull;
  return static_cast<std::size_t>(MixBits(hash) & (this->BucketFirstCell.size() - 2));
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
  if (this->Order == PointOrder::Any)
  {
    const std::size_t bucket = this->BucketOf(key);
    for (std::uint32_t cell = this->BucketFirstCell[bucket];
         cell < this->BucketFirstCell[bucket + 1];
         ++cell)
    {
      if (std::equal(key, key + 3, &this->CellKey[3 * static_cast<std::size_t>(cell)]))
      {
        return cell;
      }
    }
    return -1;
  }
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
