#include "LAZLayeredDecoder.h"

namespace pcbilateral
{
namespace laz
{

std::string DecodeLayeredChunk(const std::uint8_t*,
  const std::uint8_t*,
  const LAZParameters&,
  std::size_t,
  std::uint64_t,
  std::uint8_t*)
{
  return "the layered LAZ compressor (point formats 6 to 10) is not supported yet";
}

} // namespace laz
} // namespace pcbilateral
