// The points' coordinates as the 32-bit integers of the LAS records, vectorised where the
// machine allows. Private to the LAS codec.
#ifndef pcbilateral_LASQuantize_h
#define pcbilateral_LASQuantize_h

#include <cstddef>
#include <cstdint>

namespace pcbilateral
{
namespace las
{

/// The coordinates of n points (interleaved x y z) as the records' integers, floor((value -
/// offset) / scale + 0.5), into stored (interleaved too); their extremes widen low and high.
/// Returns false when one does not fit 32 bits or is not finite (it is stored as 0).
bool QuantizeCoordinates(const double* xyz,
  std::size_t n,
  const double scale[3],
  const double offset[3],
  std::int32_t* stored,
  std::int32_t low[3],
  std::int32_t high[3]);

} // namespace las
} // namespace pcbilateral

#endif
