// The fields packed in bits of one byte of the point records (return numbers, flags,
// classification of formats 0-5...), grouped by byte so that a pass over the records reads or
// writes each such byte once for all its fields. Private to the LAS codec.
#ifndef pcbilateral_LASBitFields_h
#define pcbilateral_LASBitFields_h

#include "LASHeader.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{
namespace las
{

/// A byte's value in each byte of a 64-bit word: eight points' bit fields are decoded and
/// encoded together, the eight bytes of a word (the host is little-endian, as checked when the
/// header is parsed; a field's mask keeps its bits within its byte).
constexpr std::uint64_t EveryByte = 0x0101010101010101ull;

/// A field packed in bits of a byte of the record.
struct BitField
{
  std::size_t Dimension;
  unsigned Mask;
  unsigned Shift;
};

/// The bit fields of one byte of the record, decoded or encoded together.
struct BitFieldByte
{
  std::size_t ByteOffset = 0;
  std::vector<BitField> Fields;
};

/// The bit fields of the dimensions that have a column, by byte.
std::vector<BitFieldByte> GroupBitFields(const LASFileInfo& info, const void* const* columns);

} // namespace las
} // namespace pcbilateral

#endif
