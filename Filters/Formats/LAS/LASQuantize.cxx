#include "LASQuantize.h"

#include <algorithm>
#include <cmath>

namespace pcbilateral
{
namespace las
{

#if defined(PCB_X86_CLONES) && defined(__linux__) && defined(__GNUC__) && !defined(__clang__)
// The same IEEE operations, vectorised where the machine has AVX2 or AVX-512 (floor needs
// SSE4.1's rounding instruction to vectorise): the same integers on every machine. The clones
// are picked at load time through the dynamic linker's indirect functions (Linux). GCC
// vectorises the loop only when it may ignore floating-point exception flags, which nothing
// here reads (the values are the same).
#define PCB_LAS_VECTOR_CLONES                                                                      \
  __attribute__((target_clones("avx512f", "avx2", "default"), optimize("no-trapping-math")))
#elif defined(PCB_X86_CLONES) && defined(__linux__) && defined(__clang__)
#define PCB_LAS_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PCB_LAS_VECTOR_CLONES
#endif

namespace
{
// The interleaved values are taken 24 at a time (8 points), with the scales and offsets
// repeated to match, so that the loop vectorises without regrouping the coordinates by axis.
PCB_LAS_VECTOR_CLONES
bool Quantize(const double* __restrict xyz,
  std::size_t n,
  const double scale[3],
  const double offset[3],
  std::int32_t* __restrict stored,
  std::int32_t low[3],
  std::int32_t high[3])
{
  constexpr std::size_t Period = 24;
  double scales[Period], offsets[Period];
  std::int32_t lowest[Period], highest[Period];
  for (std::size_t k = 0; k < Period; ++k)
  {
    scales[k] = scale[k % 3];
    offsets[k] = offset[k % 3];
    lowest[k] = low[k % 3];
    highest[k] = high[k % 3];
  }
  std::int32_t outOfRange = 0;
  const std::size_t total = 3 * n;
  for (std::size_t start = 0; start < total; start += Period)
  {
    const std::size_t length = std::min(Period, total - start);
    for (std::size_t k = 0; k < length; ++k)
    {
      const double q = std::floor((xyz[start + k] - offsets[k]) / scales[k] + 0.5);
      // Also false for NaN; no branch, so that the loop vectorises.
      const std::int32_t fits = (q >= -2147483648.0) & (q <= 2147483647.0);
      outOfRange |= fits ^ 1;
      const std::int32_t value = static_cast<std::int32_t>(fits ? q : 0.0);
      stored[start + k] = value;
      lowest[k] = value < lowest[k] ? value : lowest[k];
      highest[k] = value > highest[k] ? value : highest[k];
    }
  }
  for (std::size_t k = 0; k < Period; ++k)
  {
    low[k % 3] = std::min(low[k % 3], lowest[k]);
    high[k % 3] = std::max(high[k % 3], highest[k]);
  }
  return outOfRange == 0;
}
} // namespace

// Calls the clones through a function of this file: clang gives a cloned function of external
// linkage a name of its own, which callers in other files would not find.
bool QuantizeCoordinates(const double* xyz,
  std::size_t n,
  const double scale[3],
  const double offset[3],
  std::int32_t* stored,
  std::int32_t low[3],
  std::int32_t high[3])
{
  return Quantize(xyz, n, scale, offset, stored, low, high);
}

} // namespace las
} // namespace pcbilateral
