// The encoders of the items of point formats 0 to 3 (version 2), the mirrors of
// LAZItemDecoders.h: each predicts a point's fields from the previous point's and codes the
// corrections. Private to the LAZ codec.
#ifndef pcbilateral_LAZItemEncoders_h
#define pcbilateral_LAZItemEncoders_h

#include "LAZEntropyEncoder.h"
#include "LAZFormat.h"

#include <cstdint>
#include <memory>

namespace pcbilateral
{
namespace laz
{

class ItemEncoder
{
public:
  virtual ~ItemEncoder() = default;
  /// The chunk's first point's item, which is stored raw.
  virtual void Start(const std::uint8_t* item) = 0;
  virtual void Encode(ArithmeticEncoder& encoder, const std::uint8_t* item) = 0;
};

/// A fresh encoder of `item` (point10, gpstime11, rgb12 or byte, version 2), or null.
std::unique_ptr<ItemEncoder> MakeItemEncoder(const LAZItem& item);

} // namespace laz
} // namespace pcbilateral

#endif
