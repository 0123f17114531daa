// Points (coordinates and columns) encoded into LAS point records, a block at a time, for
// either way of writing them (LASWritePoints.h). Private to the LAS codec.
#ifndef pcbilateral_LASPointEncoder_h
#define pcbilateral_LASPointEncoder_h

#include "LASBitFields.h"
#include "LASHeader.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{
namespace las
{

constexpr std::size_t PointsPerBlock = 8192;

/// What a block of encoded points adds to the header: the bounds of its stored coordinates, its
/// points by return number, and whether a coordinate did not fit the 32-bit records.
struct BlockSummary
{
  double Bounds[6];
  std::uint64_t ByReturn[15];
  bool OutOfRange;
};

/// Encodes points into LAS records a block (PointsPerBlock points) at a time, for both ways of
/// writing them: straight into a memory mapping of the file, or into chunks written with fwrite.
class BlockEncoder
{
public:
  BlockEncoder(const LASFileInfo& info,
    std::size_t count,
    const double* positions,
    const void* const* columns);

  std::size_t Blocks() const { return (this->Count + PointsPerBlock - 1) / PointsPerBlock; }

  /// The bytes of the records of the blocks from `block` on, `blocks` of them at most.
  std::size_t Bytes(std::size_t block, std::size_t blocks) const
  {
    const std::size_t first = block * PointsPerBlock;
    return (std::min(this->Count, first + blocks * PointsPerBlock) - first) *
           this->Info.Header.RecordLength;
  }

  /// Encodes block `b` into `records`, whose bytes must be zero before: the bytes and bits of
  /// fields without a column (and the bytes no dimension names) are not written. Every other
  /// byte is stored whole, never read back.
  BlockSummary Encode(std::size_t b, std::uint8_t* records) const;

private:
  const std::uint8_t* Column(std::size_t d) const
  {
    return static_cast<const std::uint8_t*>(this->Columns[d]);
  }
  void EncodeCoordinates(std::size_t first,
    std::size_t n,
    std::uint8_t* records,
    BlockSummary& summary) const;
  void EncodeColumns(std::size_t first, std::size_t n, std::uint8_t* records) const;
  void EncodeBitFields(std::size_t first, std::size_t n, std::uint8_t* records) const;
  void CountReturns(std::size_t first, std::size_t n, BlockSummary& summary) const;

  const LASFileInfo& Info;
  std::size_t Count;
  const double* Positions;
  const void* const* Columns;
  std::vector<BitFieldByte> BitFields;
  int ReturnDimension = -1;
};

} // namespace las
} // namespace pcbilateral

#endif
