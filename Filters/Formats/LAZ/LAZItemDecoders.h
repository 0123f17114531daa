// The decoders of the items of LAZ point records, one per item of the LASzip record: each
// predicts its fields from the previous point's and decodes the corrections. A chunk's first
// point is stored raw and starts the predictions. Private to the LAZ codec.
#ifndef pcbilateral_LAZItemDecoders_h
#define pcbilateral_LAZItemDecoders_h

#include "LAZEntropyDecoder.h"
#include "LAZFormat.h"

#include <cstdint>
#include <memory>

namespace pcbilateral
{
namespace laz
{

/// Decodes one item of each point record of a chunk, in the pointwise (not layered) scheme.
class ItemDecoder
{
public:
  virtual ~ItemDecoder() = default;
  /// The chunk's first point's item, stored raw.
  virtual void Start(const std::uint8_t* item) = 0;
  /// Decodes the next point's item into `item`.
  virtual void Decode(ArithmeticDecoder& decoder, std::uint8_t* item) = 0;
};

/// A fresh decoder of `item` (one of the pointwise items, version 2), or null.
std::unique_ptr<ItemDecoder> MakeItemDecoder(const LAZItem& item);

/// The byte `value` wrapped into 0..255, as the predictions of bytes do.
inline std::uint8_t FoldByte(std::int32_t value)
{
  return static_cast<std::uint8_t>(value);
}

inline std::int32_t ClampByte(std::int32_t value)
{
  return value < 0 ? 0 : (value > 255 ? 255 : value);
}

} // namespace laz
} // namespace pcbilateral

#endif
