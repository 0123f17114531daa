#include "LASPointEncoder.h"

#include "LASBinary.h"
#include "LASQuantize.h"
#include "LASScaledFields.h"

#include <cstdint>
#include <cstring>
#include <limits>

namespace pcbilateral
{
namespace las
{

namespace
{
template<std::size_t Bytes>
void Scatter(const std::uint8_t* from, std::uint8_t* to, std::size_t stride, std::size_t count)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    std::memcpy(to + i * stride, from + i * Bytes, Bytes);
  }
}

/// Copies whole values of `bytes` bytes from a packed column into records of `stride` bytes.
void ScatterBytes(const std::uint8_t* from,
  std::uint8_t* to,
  std::size_t stride,
  std::size_t bytes,
  std::size_t count)
{
  if (!WithFieldSize(
        bytes, [&](auto size) { Scatter<decltype(size)::value>(from, to, stride, count); }))
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      std::memcpy(to + i * stride, from + i * bytes, bytes);
    }
  }
}
} // namespace

BlockEncoder::BlockEncoder(const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns)
  : Info(info)
  , Count(count)
  , Positions(positions)
  , Columns(columns)
  , BitFields(GroupBitFields(info, columns))
{
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    if (info.Dimensions[d].Name == "ReturnNumber" && columns[d])
    {
      this->ReturnDimension = static_cast<int>(d);
    }
  }
}

BlockSummary BlockEncoder::Encode(std::size_t b, std::uint8_t* records) const
{
  const std::size_t first = b * PointsPerBlock;
  const std::size_t n = std::min(PointsPerBlock, this->Count - first);
  constexpr double Infinity = std::numeric_limits<double>::infinity();
  BlockSummary summary{
    { Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity }, {}, false
  };
  this->EncodeCoordinates(first, n, records, summary);
  this->EncodeColumns(first, n, records);
  this->EncodeBitFields(first, n, records);
  this->CountReturns(first, n, summary);
  return summary;
}

void BlockEncoder::EncodeCoordinates(std::size_t first,
  std::size_t n,
  std::uint8_t* records,
  BlockSummary& summary) const
{
  const LASHeader& h = this->Info.Header;
  // The stored integers of the coordinates and their extremes, from which the bounds are
  // computed once.
  std::int32_t low[3] = { INT32_MAX, INT32_MAX, INT32_MAX };
  std::int32_t high[3] = { INT32_MIN, INT32_MIN, INT32_MIN };
  std::int32_t stored[3 * PointsPerBlock];
  summary.OutOfRange =
    !QuantizeCoordinates(this->Positions + 3 * first, n, h.Scale, h.Offset, stored, low, high);
  Scatter<12>(reinterpret_cast<const std::uint8_t*>(stored), records, h.RecordLength, n);
  for (int axis = 0; axis < 3 && n > 0; ++axis)
  {
    const double a = low[axis] * h.Scale[axis] + h.Offset[axis];
    const double z = high[axis] * h.Scale[axis] + h.Offset[axis];
    summary.Bounds[axis] = std::min(a, z); // a negative scale swaps them
    summary.Bounds[3 + axis] = std::max(a, z);
  }
}

void BlockEncoder::EncodeColumns(std::size_t first, std::size_t n, std::uint8_t* records) const
{
  const std::size_t stride = this->Info.Header.RecordLength;
  for (std::size_t d = 0; d < this->Info.Dimensions.size(); ++d)
  {
    const LASDimension& dimension = this->Info.Dimensions[d];
    if (!this->Columns[d])
    {
      continue;
    }
    const std::size_t bytes = LASColumnBytes(dimension);
    const auto* from = this->Column(d) + first * bytes;
    std::uint8_t* to = records + dimension.ByteOffset;
    if (dimension.Scaled)
    {
      WithScaledTypes(dimension,
        [&](auto raw, auto value)
        { EncodeScaled<decltype(raw), decltype(value)>(from, dimension, to, stride, n); });
    }
    else if (dimension.BitCount == 0)
    {
      ScatterBytes(from, to, stride, bytes, n);
    }
  }
}

void BlockEncoder::EncodeBitFields(std::size_t first, std::size_t n, std::uint8_t* records) const
{
  const std::size_t stride = this->Info.Header.RecordLength;
  // Eight points at a time: eight bytes of each field's column in one 64-bit word, masked
  // and shifted in place (a field's bits stay within its byte), then one byte per record.
  for (const BitFieldByte& packed : this->BitFields)
  {
    std::uint8_t* to = records + packed.ByteOffset;
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8)
    {
      std::uint64_t values = 0;
      for (const BitField& field : packed.Fields)
      {
        values |= (Load<std::uint64_t>(this->Column(field.Dimension) + first + i) &
                    (field.Mask * EveryByte))
                  << field.Shift;
      }
      for (std::size_t k = 0; k < 8; ++k)
      {
        to[(i + k) * stride] = static_cast<std::uint8_t>(values >> (8 * k));
      }
    }
    for (; i < n; ++i)
    {
      unsigned value = 0;
      for (const BitField& field : packed.Fields)
      {
        value |= (this->Column(field.Dimension)[first + i] & field.Mask) << field.Shift;
      }
      to[i * stride] = static_cast<std::uint8_t>(value);
    }
  }
}

void BlockEncoder::CountReturns(std::size_t first, std::size_t n, BlockSummary& summary) const
{
  if (this->ReturnDimension < 0)
  {
    return;
  }
  const std::uint8_t* returns = this->Column(this->ReturnDimension) + first;
  const int limit = this->Info.Header.PointFormat > 5 ? 15 : 5;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (returns[i] >= 1 && returns[i] <= limit)
    {
      ++summary.ByReturn[returns[i] - 1];
    }
  }
}

} // namespace las
} // namespace pcbilateral
