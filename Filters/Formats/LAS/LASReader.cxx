#include "LASReader.h"

#include "HugePages.h"
#include "LASBinary.h"
#include "LASBitFields.h"
#include "LASScaledFields.h"
#include "ProgressCheck.h"

#include <algorithm>
#include <cstring>
#include <type_traits>
#include <vector>

namespace pcbilateral
{

namespace
{
using namespace las;

/// Points decoded at once by a thread: their records stay in its cache for all the passes.
constexpr std::size_t PointsPerDecodedBlock = 4096;

/// Copies whole values of `bytes` bytes from records of `stride` bytes into a packed column.
template<std::size_t Bytes>
void Gather(const std::uint8_t* from, std::size_t stride, std::uint8_t* to, std::size_t count)
{
  std::size_t i = 0;
  if constexpr (Bytes == 1 || Bytes == 2)
  {
    // Values of one or two bytes are put together in a 64-bit word (little-endian host), so
    // one store writes 8 or 4 of them: the stores, not the loads, limit these loops.
    constexpr std::size_t PerWord = 8 / Bytes;
    for (; i + PerWord <= count; i += PerWord)
    {
      std::uint64_t word = 0;
      for (std::size_t k = 0; k < PerWord; ++k)
      {
        word |= static_cast<std::uint64_t>(
                  Load<std::conditional_t<Bytes == 1, std::uint8_t, std::uint16_t>>(
                    from + (i + k) * stride))
                << (8 * Bytes * k);
      }
      Store<std::uint64_t>(to + i * Bytes, word);
    }
  }
  for (; i < count; ++i)
  {
    std::memcpy(to + i * Bytes, from + i * stride, Bytes);
  }
}

void GatherBytes(const std::uint8_t* from,
  std::size_t stride,
  std::uint8_t* to,
  std::size_t bytes,
  std::size_t count)
{
  if (!WithFieldSize(
        bytes, [&](auto size) { Gather<decltype(size)::value>(from, stride, to, count); }))
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      std::memcpy(to + i * bytes, from + i * stride, bytes);
    }
  }
}

/// Decodes blocks of point records into the columns, one pass per field, except the fields
/// packed in bits of one byte: one pass reads the byte once and writes each of its fields.
class BlockDecoder
{
public:
  BlockDecoder(const LASFileInfo& info, double* positions, void* const* columns)
    : Info(info)
    , Positions(positions)
    , Columns(columns)
    , BitFields(GroupBitFields(info, columns))
  {
  }

  /// Decodes the `count` records at `block`, the points from `first` on.
  void Decode(const std::uint8_t* block, std::size_t first, std::size_t count) const
  {
    this->DecodeCoordinates(block, first, count);
    const std::size_t stride = this->Info.Header.RecordLength;
    for (std::size_t d = 0; d < this->Info.Dimensions.size(); ++d)
    {
      const LASDimension& dimension = this->Info.Dimensions[d];
      if (!this->Columns[d] || dimension.BitCount > 0)
      {
        continue;
      }
      const std::uint8_t* from = block + dimension.ByteOffset;
      std::uint8_t* to = this->Column(d, first);
      if (dimension.Scaled)
      {
        WithScaledTypes(dimension,
          [&](auto raw, auto value)
          { DecodeScaled<decltype(raw), decltype(value)>(from, stride, dimension, to, count); });
      }
      else
      {
        GatherBytes(from, stride, to, LASColumnBytes(dimension), count);
      }
    }
    for (const BitFieldByte& byte : this->BitFields)
    {
      this->DecodeBitFields(block + byte.ByteOffset, stride, byte, first, count);
    }
  }

private:
  std::uint8_t* Column(std::size_t d, std::size_t first) const
  {
    return static_cast<std::uint8_t*>(this->Columns[d]) +
           first * LASColumnBytes(this->Info.Dimensions[d]);
  }

  void DecodeCoordinates(const std::uint8_t* block, std::size_t first, std::size_t count) const
  {
    const std::size_t stride = this->Info.Header.RecordLength;
    const double* scale = this->Info.Header.Scale;
    const double* offset = this->Info.Header.Offset;
    double* p = this->Positions + 3 * first;
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::uint8_t* record = block + i * stride;
      for (int axis = 0; axis < 3; ++axis)
      {
        p[3 * i + axis] = Load<std::int32_t>(record + 4 * axis) * scale[axis] + offset[axis];
      }
    }
  }

  void DecodeBitFields(const std::uint8_t* from,
    std::size_t stride,
    const BitFieldByte& byte,
    std::size_t first,
    std::size_t count) const
  {
    constexpr std::size_t MostFields = 8;
    std::uint8_t* to[MostFields];
    unsigned shift[MostFields];
    unsigned mask[MostFields];
    const std::size_t fields = std::min(byte.Fields.size(), MostFields); // bits of one byte
    for (std::size_t f = 0; f < fields; ++f)
    {
      to[f] = this->Column(byte.Fields[f].Dimension, first);
      shift[f] = byte.Fields[f].Shift;
      mask[f] = byte.Fields[f].Mask;
    }
    // Eight points at a time, as the eight bytes of a 64-bit word (the host is little-endian,
    // as checked when the header was parsed): shifting the word moves each point's bits within
    // its byte, as long as a field does not go beyond its byte, which the mask makes sure of.
    // One store writes a field of eight points.
    std::size_t i = 0;
    for (; i + 8 <= count; i += 8)
    {
      std::uint64_t bytes = 0;
      for (unsigned k = 0; k < 8; ++k)
      {
        bytes |= static_cast<std::uint64_t>(from[(i + k) * stride]) << (8 * k);
      }
      for (std::size_t f = 0; f < fields; ++f)
      {
        Store<std::uint64_t>(to[f] + i, (bytes >> shift[f]) & (mask[f] * EveryByte));
      }
    }
    for (; i < count; ++i)
    {
      const unsigned value = from[i * stride];
      for (std::size_t f = 0; f < fields; ++f)
      {
        to[f][i] = static_cast<std::uint8_t>((value >> shift[f]) & mask[f]);
      }
    }
  }

  const LASFileInfo& Info;
  double* Positions;
  void* const* Columns;
  std::vector<BitFieldByte> BitFields;
};
} // namespace

bool DecodeLASPoints(const LASFileInfo& info,
  const std::uint8_t* records,
  std::size_t count,
  double* positions,
  void* const* columns)
{
  // Fresh memory as huge pages: a page fault per 4 KB of the columns (1.5 times the file's
  // size) would cost more than the decoding.
  AdviseHugePages(positions, 3 * sizeof(double) * count);
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    if (columns[d])
    {
      AdviseHugePages(columns[d], LASColumnBytes(info.Dimensions[d]) * count);
    }
  }
  const std::size_t stride = info.Header.RecordLength;
  const auto blocks =
    static_cast<std::int64_t>((count + PointsPerDecodedBlock - 1) / PointsPerDecodedBlock);
  // Each thread decodes one contiguous range of blocks, so it is the first to touch (and
  // place) the memory it writes.
  const BlockDecoder decoder(info, positions, columns);
  ParallelProgress progress(count);
#pragma omp parallel
  {
#pragma omp for schedule(static) nowait
    for (std::int64_t b = 0; b < blocks; ++b)
    {
      const std::size_t first = static_cast<std::size_t>(b) * PointsPerDecodedBlock;
      const std::size_t points = std::min(PointsPerDecodedBlock, count - first);
      if (progress.StopAsked())
      {
        progress.Skipped(points);
        continue;
      }
      decoder.Decode(records + first * stride, first, points);
      progress.Done(points);
    }
    progress.WaitForOthers(); // (the asking thread does not wait in a barrier)
  }
  return !progress.StopAsked();
}

} // namespace pcbilateral
