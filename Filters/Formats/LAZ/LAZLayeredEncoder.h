// The layered chunks of point formats 6 to 8 (LASzip's compressor 3, items version 3), the
// mirror of LAZLayeredDecoder.h. Private to the LAZ codec.
#ifndef pcbilateral_LAZLayeredEncoder_h
#define pcbilateral_LAZLayeredEncoder_h

#include "LAZFormat.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{
namespace laz
{

/// One layered chunk of the `count` records: the first raw, the point count, each layer's byte
/// count, then the layers (a layer whose field never changes in the chunk is left empty).
std::vector<std::uint8_t> CompressLayeredChunk(const std::uint8_t* records,
  std::size_t count,
  std::size_t recordLength,
  const LAZParameters& parameters);

} // namespace laz
} // namespace pcbilateral

#endif
