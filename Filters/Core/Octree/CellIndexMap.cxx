// The octree's map from a cell's lattice coordinates to its number (ProcessingOctree.h).
#include "ProcessingOctree.h"

#include <algorithm>
#include <cstring>

namespace pcbilateral
{

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

void CellIndexMap::Clear(std::size_t expectedCells)
{
  std::size_t capacity = 16;
  while (capacity < 2 * expectedCells)
  {
    capacity *= 2;
  }
  this->Slots.assign(capacity, Slot());
  this->Count = 0;
}

namespace
{
/// The slot's tag: the hash's high 32 bits (the low ones pick the slot).
std::uint32_t TagOf(std::uint64_t hash)
{
  return static_cast<std::uint32_t>(hash >> 32);
}
} // namespace

std::int32_t CellIndexMap::Find(const LatticeCoord& cell, const LatticeCoord* coords) const
{
  const std::uint64_t hash = LatticeCoordHash()(cell);
  const std::uint32_t tag = TagOf(hash);
  const std::size_t mask = this->Slots.size() - 1;
  for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask)
  {
    const Slot& entry = this->Slots[slot];
    if (entry.Index == Missing || (entry.Tag == tag && coords[entry.Index] == cell))
    {
      return entry.Index;
    }
  }
}

std::int32_t CellIndexMap::Insert(const LatticeCoord& cell,
  std::int32_t index,
  const LatticeCoord* coords)
{
  if (2 * (this->Count + 1) > this->Slots.size())
  {
    this->Grow(coords);
  }
  const std::uint64_t hash = LatticeCoordHash()(cell);
  const std::uint32_t tag = TagOf(hash);
  const std::size_t mask = this->Slots.size() - 1;
  for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask)
  {
    Slot& entry = this->Slots[slot];
    if (entry.Index == Missing)
    {
      entry.Tag = tag;
      entry.Index = index;
      ++this->Count;
      return index;
    }
    if (entry.Tag == tag && coords[entry.Index] == cell)
    {
      return entry.Index;
    }
  }
}

void CellIndexMap::InsertDistinct(const LatticeCoord* coords,
  std::size_t count,
  int numberOfThreads)
{
  this->Clear(count);
  const std::size_t mask = this->Slots.size() - 1;
  const auto signedCount = static_cast<std::int64_t>(count);
#if defined(__GNUC__)
  // In parallel: a slot is claimed with a compare-and-swap of its 8 bytes from empty. The cells
  // are distinct, so a taken slot is always another cell's, and the probe goes on.
  static_assert(sizeof(Slot) == sizeof(std::uint64_t), "a slot is claimed in one 8-byte swap");
  const Slot emptySlot;
  std::uint64_t empty;
  std::memcpy(&empty, &emptySlot, sizeof(empty));
  std::uint64_t* slots = reinterpret_cast<std::uint64_t*>(this->Slots.data());
#pragma omp parallel for schedule(static) num_threads(numberOfThreads)
  for (std::int64_t index = 0; index < signedCount; ++index)
  {
    const std::uint64_t hash = LatticeCoordHash()(coords[index]);
    Slot claimed;
    claimed.Tag = TagOf(hash);
    claimed.Index = static_cast<std::int32_t>(index);
    std::uint64_t value;
    std::memcpy(&value, &claimed, sizeof(value));
    for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask)
    {
      std::uint64_t expected = empty;
      if (__atomic_compare_exchange_n(
            slots + slot, &expected, value, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
      {
        break;
      }
    }
  }
  this->Count = count;
#else
  (void)numberOfThreads;
  (void)mask;
  for (std::int64_t index = 0; index < signedCount; ++index)
  {
    this->Insert(coords[index], static_cast<std::int32_t>(index), coords);
  }
#endif
}

void CellIndexMap::Grow(const LatticeCoord* coords)
{
  std::vector<Slot> old;
  old.swap(this->Slots);
  this->Clear(std::max<std::size_t>(8, old.size()));
  for (const Slot& entry : old)
  {
    if (entry.Index != Missing)
    {
      this->Insert(coords[entry.Index], entry.Index, coords);
    }
  }
}

} // namespace pcbilateral
