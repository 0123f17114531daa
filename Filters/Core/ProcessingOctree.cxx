#include "ProcessingOctree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

namespace pcbilateral
{

namespace
{
/// Cells are at least this many radii wide, so that a point moved by less than r (the
/// filter's guarantee) from one cell cannot reach a leaf reachable from a cell of the same
/// colour (the paper's d = 2.1 r).
constexpr double CellSizeInRadii = 2.1;

/// The order of the points in a leaf: by coordinates, so that it depends on geometry alone and
/// not on the point ids (a distributed run numbers its points differently). Points equal in all
/// three coordinates are ordered by their bits, then by id: exact duplicates contribute the
/// same terms to every sum, so their order among themselves changes no result.
bool PrecedesInLeaf(const double* a, std::uint32_t idA, const double* b, std::uint32_t idB)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    if (a[axis] != b[axis])
    {
      return a[axis] < b[axis];
    }
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    std::uint64_t bitsA, bitsB;
    std::memcpy(&bitsA, a + axis, sizeof(bitsA));
    std::memcpy(&bitsB, b + axis, sizeof(bitsB));
    if (bitsA != bitsB)
    {
      return bitsA < bitsB;
    }
  }
  return idA < idB;
}

std::int64_t FloorDivide(std::int64_t value, std::int64_t divisor)
{
  const std::int64_t quotient = value / divisor;
  return (value % divisor < 0) ? quotient - 1 : quotient;
}
} // namespace

std::size_t LatticeCoordHash::operator()(const LatticeCoord& c) const
{
  // SplitMix64 finaliser over a mix of the three coordinates.
  std::uint64_t h = static_cast<std::uint64_t>(c.X) * 0x9E3779B97F4A7C15ULL;
  h ^= static_cast<std::uint64_t>(c.Y) + 0xBF58476D1CE4E5B9ULL + (h << 6) + (h >> 2);
  h ^= static_cast<std::uint64_t>(c.Z) + 0x94D049BB133111EBULL + (h << 6) + (h >> 2);
  h ^= h >> 30;
  h *= 0xBF58476D1CE4E5B9ULL;
  h ^= h >> 27;
  h *= 0x94D049BB133111EBULL;
  h ^= h >> 31;
  return static_cast<std::size_t>(h);
}

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

LatticeCoord ProcessingOctree::LeafOf(const double p[3]) const
{
  LatticeCoord leaf;
  leaf.X = static_cast<std::int64_t>(std::floor((p[0] - this->RootOrigin[0]) / this->LeafSize));
  leaf.Y = static_cast<std::int64_t>(std::floor((p[1] - this->RootOrigin[1]) / this->LeafSize));
  leaf.Z = static_cast<std::int64_t>(std::floor((p[2] - this->RootOrigin[2]) / this->LeafSize));
  return leaf;
}

LatticeCoord ProcessingOctree::CellOfLeaf(const LatticeCoord& leaf)
{
  LatticeCoord cell;
  cell.X = FloorDivide(leaf.X, LeavesPerAxis);
  cell.Y = FloorDivide(leaf.Y, LeavesPerAxis);
  cell.Z = FloorDivide(leaf.Z, LeavesPerAxis);
  return cell;
}

int ProcessingOctree::LocalLeafIndex(const LatticeCoord& leaf)
{
  const LatticeCoord cell = CellOfLeaf(leaf);
  const auto x = static_cast<int>(leaf.X - LeavesPerAxis * cell.X);
  const auto y = static_cast<int>(leaf.Y - LeavesPerAxis * cell.Y);
  const auto z = static_cast<int>(leaf.Z - LeavesPerAxis * cell.Z);
  return x + LeavesPerAxis * (y + LeavesPerAxis * z);
}

void ProcessingOctree::Clear(std::size_t numberOfPoints)
{
  this->CellCoords.clear();
  this->CellIndex.clear();
  this->NeighbourTable.clear();
  this->NumberOfProcessingCells = 0;
  this->NextHead.clear();
  this->NextLink.assign(numberOfPoints, -1);
  this->LeafOffsets.assign(1, 0);
  this->SortedIds.clear();
  this->SortedX.clear();
  this->SortedY.clear();
  this->SortedZ.clear();
}

std::int32_t ProcessingOctree::FindCell(const LatticeCoord& cell) const
{
  const auto found = this->CellIndex.find(cell);
  return found == this->CellIndex.end() ? NoCell : found->second;
}

std::int32_t ProcessingOctree::FindOrCreateCell(const LatticeCoord& cell)
{
  const auto inserted =
    this->CellIndex.emplace(cell, static_cast<std::int32_t>(this->CellCoords.size()));
  const std::int32_t index = inserted.first->second;
  if (!inserted.second)
  {
    return index;
  }
  this->CellCoords.push_back(cell);
  this->NextHead.resize(this->NextHead.size() + LeavesPerCell, -1);
  // Processing cells next to the new one must see it, to place points into it.
  for (int dz = -1; dz <= 1; ++dz)
  {
    for (int dy = -1; dy <= 1; ++dy)
    {
      for (int dx = -1; dx <= 1; ++dx)
      {
        const std::int32_t neighbour =
          this->FindCell(LatticeCoord{ cell.X + dx, cell.Y + dy, cell.Z + dz });
        if (neighbour != NoCell &&
            static_cast<std::size_t>(neighbour) < this->NumberOfProcessingCells)
        {
          this->NeighbourTable[27 * neighbour + NeighbourSlot(-dx, -dy, -dz)] = index;
        }
      }
    }
  }
  return index;
}

void ProcessingOctree::PlaceSerially(std::uint32_t pointId, const LatticeCoord& leaf)
{
  this->Place(pointId, this->FindOrCreateCell(CellOfLeaf(leaf)), LocalLeafIndex(leaf));
}

void ProcessingOctree::Compact(const double* positions, int numberOfThreads)
{
  const auto oldCellCount = static_cast<std::int64_t>(this->CellCoords.size());
  std::vector<std::uint32_t> leafCounts(this->NextHead.size(), 0);
  std::vector<std::uint32_t> cellCounts(this->CellCoords.size(), 0);
#pragma omp parallel for schedule(static) num_threads(numberOfThreads)
  for (std::int64_t cell = 0; cell < oldCellCount; ++cell)
  {
    std::uint32_t cellCount = 0;
    for (int leaf = 0; leaf < LeavesPerCell; ++leaf)
    {
      std::uint32_t count = 0;
      for (std::int32_t id = this->NextHead[cell * LeavesPerCell + leaf]; id >= 0;
           id = this->NextLink[id])
      {
        ++count;
      }
      leafCounts[cell * LeavesPerCell + leaf] = count;
      cellCount += count;
    }
    cellCounts[cell] = cellCount;
  }

  // Non-empty cells in lattice order (z, then y, then x), so that the layout does not depend
  // on the order in which cells were created.
  std::vector<std::int32_t> kept;
  for (std::int32_t cell = 0; cell < oldCellCount; ++cell)
  {
    if (cellCounts[cell] > 0)
    {
      kept.push_back(cell);
    }
  }
  std::sort(kept.begin(),
    kept.end(),
    [this](std::int32_t a, std::int32_t b)
    {
      const LatticeCoord& ca = this->CellCoords[a];
      const LatticeCoord& cb = this->CellCoords[b];
      if (ca.Z != cb.Z)
      {
        return ca.Z < cb.Z;
      }
      if (ca.Y != cb.Y)
      {
        return ca.Y < cb.Y;
      }
      return ca.X < cb.X;
    });

  const std::size_t newCellCount = kept.size();
  std::vector<std::uint32_t> offsets(newCellCount * LeavesPerCell + 1, 0);
  for (std::size_t cell = 0; cell < newCellCount; ++cell)
  {
    for (int leaf = 0; leaf < LeavesPerCell; ++leaf)
    {
      const std::size_t slot = cell * LeavesPerCell + leaf;
      offsets[slot + 1] = offsets[slot] + leafCounts[kept[cell] * LeavesPerCell + leaf];
    }
  }
  const std::size_t pointCount = offsets.back();
  this->SortedIds.resize(pointCount);
  this->SortedX.resize(pointCount);
  this->SortedY.resize(pointCount);
  this->SortedZ.resize(pointCount);
  const auto signedNewCellCount = static_cast<std::int64_t>(newCellCount);
#pragma omp parallel for schedule(static) num_threads(numberOfThreads)
  for (std::int64_t cell = 0; cell < signedNewCellCount; ++cell)
  {
    for (int leaf = 0; leaf < LeavesPerCell; ++leaf)
    {
      const std::size_t begin = offsets[cell * LeavesPerCell + leaf];
      std::size_t end = begin;
      for (std::int32_t id = this->NextHead[kept[cell] * LeavesPerCell + leaf]; id >= 0;
           id = this->NextLink[id])
      {
        this->SortedIds[end++] = static_cast<std::uint32_t>(id);
      }
      std::sort(this->SortedIds.begin() + begin,
        this->SortedIds.begin() + end,
        [positions](std::uint32_t a, std::uint32_t b)
        {
          return PrecedesInLeaf(
            positions + 3 * std::size_t{ a }, a, positions + 3 * std::size_t{ b }, b);
        });
      for (std::size_t i = begin; i < end; ++i)
      {
        const double* p = positions + 3 * static_cast<std::size_t>(this->SortedIds[i]);
        this->SortedX[i] = p[0];
        this->SortedY[i] = p[1];
        this->SortedZ[i] = p[2];
      }
    }
  }
  this->LeafOffsets = std::move(offsets);

  std::vector<LatticeCoord> newCoords(newCellCount);
  this->CellIndex.clear();
  this->CellIndex.reserve(newCellCount);
  for (std::size_t cell = 0; cell < newCellCount; ++cell)
  {
    newCoords[cell] = this->CellCoords[kept[cell]];
    this->CellIndex.emplace(newCoords[cell], static_cast<std::int32_t>(cell));
  }
  this->CellCoords = std::move(newCoords);
  this->NumberOfProcessingCells = newCellCount;
  this->NextHead.assign(newCellCount * LeavesPerCell, -1);
  std::fill(this->NextLink.begin(), this->NextLink.end(), -1);
  this->RebuildNeighbourTable(numberOfThreads);
}

void ProcessingOctree::RebuildNeighbourTable(int numberOfThreads)
{
  const auto cellCount = static_cast<std::int64_t>(this->CellCoords.size());
  this->NeighbourTable.assign(27 * this->CellCoords.size(), NoCell);
#pragma omp parallel for schedule(static) num_threads(numberOfThreads)
  for (std::int64_t cell = 0; cell < cellCount; ++cell)
  {
    const LatticeCoord& c = this->CellCoords[cell];
    for (int dz = -1; dz <= 1; ++dz)
    {
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          this->NeighbourTable[27 * cell + NeighbourSlot(dx, dy, dz)] =
            this->FindCell(LatticeCoord{ c.X + dx, c.Y + dy, c.Z + dz });
        }
      }
    }
  }
}

} // namespace pcbilateral
