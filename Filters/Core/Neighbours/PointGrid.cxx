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

/// A point's packed cell coordinates (PointGrid::Pack) and its id.
struct PackedPoint
{
  std::uint64_t Key;
  std::uint32_t Id;
};

/// The number of bits value needs (0 for 0).
int BitWidth(std::uint64_t value)
{
  int bits = 0;
  for (; value != 0; value >>= 1)
  {
    ++bits;
  }
  return bits;
}

/// Sorts points by the low `bits` bits of their keys, stably (equal keys keep their order), 11
/// bits a pass.
void RadixSort(PointArray<PackedPoint>& points, int bits)
{
  constexpr int DigitBits = 11;
  constexpr std::size_t Digits = std::size_t(1) << DigitBits;
  const int passes = (bits + DigitBits - 1) / DigitBits;
  // Every pass's digit counts in one reading of the keys.
  std::vector<std::uint32_t> start(passes * (Digits + 1), 0);
  for (const PackedPoint& point : points)
  {
    for (int pass = 0; pass < passes; ++pass)
    {
      ++start[pass * (Digits + 1) + ((point.Key >> (pass * DigitBits)) & (Digits - 1)) + 1];
    }
  }
  PointArray<PackedPoint> sorted(points.size());
  for (int pass = 0; pass < passes; ++pass)
  {
    std::uint32_t* next = &start[pass * (Digits + 1)];
    for (std::size_t digit = 0; digit < Digits; ++digit)
    {
      next[digit + 1] += next[digit];
    }
    for (const PackedPoint& point : points)
    {
      sorted[next[(point.Key >> (pass * DigitBits)) & (Digits - 1)]++] = point;
    }
    std::swap(points, sorted);
  }
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
  // (At most a cell per point; the first layout of a sparse cloud has nearly that many.)
  this->CellKey.reserve(3 * n);
  this->CellBegin.reserve(n + 1);
  if (order == PointOrder::ByCoordinates || !this->LayOutInColumns(positions, ids, keys))
  {
    this->Order = PointOrder::ByCoordinates;
    this->LayOutByCoordinates(positions, ids, keys);
  }
  this->CellBegin.push_back(static_cast<std::uint32_t>(n));
  return true;
}

void PointGrid::LayOutByCoordinates(const double* positions,
  const std::vector<std::uint32_t>& ids,
  const PointArray<std::int64_t>& keys)
{
  this->CellOfPoint.resize(ids.size());
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

bool PointGrid::LayOutInColumns(const double* positions,
  const std::vector<std::uint32_t>& ids,
  const PointArray<std::int64_t>& keys)
{
  const std::size_t n = ids.size();
  if (n == 0)
  {
    this->HashColumns();
    return true;
  }
  std::copy_n(&keys[0], 3, this->KeyMin);
  std::copy_n(&keys[0], 3, this->KeyMax);
  for (std::size_t k = 1; k < n; ++k)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      this->KeyMin[axis] = std::min(this->KeyMin[axis], keys[3 * k + axis]);
      this->KeyMax[axis] = std::max(this->KeyMax[axis], keys[3 * k + axis]);
    }
  }
  int bits[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    bits[axis] = BitWidth(static_cast<std::uint64_t>(this->KeyMax[axis] - this->KeyMin[axis]));
  }
  // (Below 64 bits, no column's packed key is EmptyColumn.)
  if (bits[0] + bits[1] + bits[2] > 63)
  {
    return false;
  }
  this->YBits = bits[1];
  this->ZBits = bits[2];
  PointArray<PackedPoint> packed(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    packed[k] = { this->Pack(&keys[3 * k]), ids[k] };
  }
  RadixSort(packed, bits[0] + bits[1] + bits[2]);
  const std::uint64_t zMask = (std::uint64_t(1) << this->ZBits) - 1;
  const std::uint64_t yMask = (std::uint64_t(1) << this->YBits) - 1;
  for (std::size_t at = 0; at < n; ++at)
  {
    // (The points are read in the cells' order, at random in memory: asking for them ahead
    // keeps several reads in flight.)
    constexpr std::size_t Ahead = 16;
    if (at + Ahead < n)
    {
      __builtin_prefetch(positions + 3 * static_cast<std::size_t>(packed[at + Ahead].Id));
    }
    // (Place's work, on the packed keys: a cell starts where its key differs from the last.)
    const std::uint64_t cell = packed[at].Key;
    if (at == 0 || cell != packed[at - 1].Key)
    {
      this->CellKey.push_back(
        this->KeyMin[0] + static_cast<std::int64_t>(cell >> (this->YBits + this->ZBits)));
      this->CellKey.push_back(
        this->KeyMin[1] + static_cast<std::int64_t>((cell >> this->ZBits) & yMask));
      this->CellKey.push_back(this->KeyMin[2] + static_cast<std::int64_t>(cell & zMask));
      this->CellBegin.push_back(static_cast<std::uint32_t>(at));
    }
    const std::uint32_t id = packed[at].Id;
    const double* p = positions + 3 * static_cast<std::size_t>(id);
    this->Ids[at] = id;
    this->X[at] = p[0];
    this->Y[at] = p[1];
    this->Z[at] = p[2];
  }
  this->HashColumns();
  return true;
}

std::uint64_t PointGrid::Pack(const std::int64_t key[3]) const
{
  return static_cast<std::uint64_t>(key[0] - this->KeyMin[0]) << (this->YBits + this->ZBits) |
         static_cast<std::uint64_t>(key[1] - this->KeyMin[1]) << this->ZBits |
         static_cast<std::uint64_t>(key[2] - this->KeyMin[2]);
}

void PointGrid::HashColumns()
{
  const std::size_t cells = this->CellBegin.size();
  std::size_t slots = 2;
  while (slots < 2 * cells)
  {
    slots *= 2;
  }
  this->ColumnKey.assign(slots, EmptyColumn);
  this->ColumnFirstCell.assign(slots, 0);
  std::uint64_t previous = EmptyColumn;
  for (std::size_t cell = 0; cell < cells; ++cell)
  {
    std::uint64_t column;
    this->PackColumn(this->CellKey[3 * cell], this->CellKey[3 * cell + 1], column);
    if (column == previous)
    {
      continue;
    }
    previous = column;
    std::size_t slot = MixBits(column) & (slots - 1);
    while (this->ColumnKey[slot] != EmptyColumn)
    {
      slot = (slot + 1) & (slots - 1);
    }
    this->ColumnKey[slot] = column;
    this->ColumnFirstCell[slot] = static_cast<std::uint32_t>(cell);
  }
}

bool PointGrid::PackColumn(std::int64_t x, std::int64_t y, std::uint64_t& packed) const
{
  if (x < this->KeyMin[0] || x > this->KeyMax[0] || y < this->KeyMin[1] || y > this->KeyMax[1])
  {
    return false;
  }
  packed = static_cast<std::uint64_t>(x - this->KeyMin[0]) << this->YBits |
           static_cast<std::uint64_t>(y - this->KeyMin[1]);
  return true;
}

std::int64_t PointGrid::FindColumn(std::int64_t x, std::int64_t y) const
{
  std::uint64_t column;
  if (!this->PackColumn(x, y, column))
  {
    return -1;
  }
  const std::size_t mask = this->ColumnKey.size() - 1;
  for (std::size_t slot = MixBits(column) & mask; this->ColumnKey[slot] != EmptyColumn;
       slot = (slot + 1) & mask)
  {
    if (this->ColumnKey[slot] == column)
    {
      return this->ColumnFirstCell[slot];
    }
  }
  return -1;
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
  if (this->Order == PointOrder::ByCoordinates)
  {
    this->CellOfPoint[at] = static_cast<std::uint32_t>(this->CellBegin.size() - 1);
  }
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
  std::size_t cell;
  if (this->Order == PointOrder::Any)
  {
    const std::int64_t column = this->FindColumn(key[0], key[1]);
    if (column < 0)
    {
      return -1;
    }
    cell = static_cast<std::size_t>(column);
    while (cell < this->CellBegin.size() - 1 && this->CellKey[3 * cell] == key[0] &&
           this->CellKey[3 * cell + 1] == key[1] && this->CellKey[3 * cell + 2] < key[2])
    {
      ++cell;
    }
  }
  else
  {
    cell = this->LowerBound(key);
  }
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
