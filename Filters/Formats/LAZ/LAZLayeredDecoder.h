// The layered chunks of point formats 6 to 10 (LASzip's compressor 3, items version 3): each
// field of the points after the first is coded in a layer of its own, with its byte count at the
// chunk's start. Private to the LAZ codec.
#ifndef pcbilateral_LAZLayeredDecoder_h
#define pcbilateral_LAZLayeredDecoder_h

#include "LAZFormat.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace pcbilateral
{
namespace laz
{

/// Decodes the `points` records of a layered chunk [begin, end) into `out`; returns an empty
/// string or what is wrong.
std::string DecodeLayeredChunk(const std::uint8_t* begin,
  const std::uint8_t* end,
  const LAZParameters& parameters,
  std::size_t recordLength,
  std::uint64_t points,
  std::uint8_t* out);

} // namespace laz
} // namespace pcbilateral

#endif
