// Bit operations of the core: counting for the leaf masks, with the compiler's instruction where
// it has one and portable standard C++ elsewhere (C++17 has no std::countr_zero or
// std::popcount), and mixing for hashes.
#ifndef pcbilateral_BitOperations_h
#define pcbilateral_BitOperations_h

#include <cstdint>

namespace pcbilateral
{

/// The index of the lowest set bit of a non-zero mask.
inline int CountTrailingZeros(std::uint64_t mask)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctzll(mask);
#else
  int count = 0;
  for (; (mask & 1u) == 0; mask >>= 1)
  {
    ++count;
  }
  return count;
#endif
}

/// The number of zero bits above the highest set bit (64 for 0).
inline int CountLeadingZeros(std::uint64_t value)
{
#if defined(__GNUC__) || defined(__clang__)
  return value == 0 ? 64 : __builtin_clzll(value);
#else
  int count = 64;
  for (; value != 0; value >>= 1)
  {
    --count;
  }
  return count;
#endif
}

/// The number of set bits.
inline int PopCount(std::uint32_t mask)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_popcount(mask);
#else
  int count = 0;
  for (; mask != 0; mask &= mask - 1)
  {
    ++count;
  }
  return count;
#endif
}

/// SplitMix64's finaliser: every input bit changes about half the output bits, so that keys
/// made from coordinates spread evenly (the measurement's pseudo-random keys, the grid's
/// buckets).
inline std::uint64_t MixBits(std::uint64_t x)
{
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// A key for the cell of integer coordinates (x, y, z) of a hashed set of cells. Two cells may
/// share a key: users make that cost only time (a far cell counted as near), never a result.
inline std::uint64_t CellHashKey(std::int64_t x, std::int64_t y, std::int64_t z)
{
  return MixBits(MixBits(MixBits(static_cast<std::uint64_t>(x)) ^ static_cast<std::uint64_t>(y)) ^
                 static_cast<std::uint64_t>(z));
}

} // namespace pcbilateral

#endif
