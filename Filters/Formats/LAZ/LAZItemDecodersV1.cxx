// Version 1 of the items of point formats 0 to 5 (LASzip 1.x).
#include "LAZItemDecoders.h"

namespace pcbilateral
{
namespace laz
{

std::unique_ptr<ItemDecoder> MakeItemDecoderV1(const LAZItem&)
{
  return nullptr;
}

} // namespace laz
} // namespace pcbilateral
