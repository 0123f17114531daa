// Bit counting for the core's leaf masks, with the compiler's instruction where it has one and
// portable standard C++ elsewhere (C++17 has no std::countr_zero or std::popcount).
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

} // namespace pcbilateral

#endif
