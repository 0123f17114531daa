// One variable-length record's bytes: its header (54 bytes, 60 for an extended one) and its
// data. Shared by the header's parser, EncodeLASRecords / DecodeLASRecords and the writer.
// Private to the LAS codec.
#ifndef pcbilateral_LASRecordBytes_h
#define pcbilateral_LASRecordBytes_h

#include "LASRecord.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcbilateral
{
namespace las
{

constexpr std::size_t VLRHeaderSize = 54;
constexpr std::size_t EVLRHeaderSize = 60;

inline std::size_t RecordHeaderSize(bool extended)
{
  return extended ? EVLRHeaderSize : VLRHeaderSize;
}

/// The length of the data of the record whose header starts at `at` (its whole header must be
/// there).
std::uint64_t RecordDataLength(const std::uint8_t* at, bool extended);

/// The record whose header starts at `at`, with `length` bytes of data after the header (all
/// of which must be there).
LASRecord DecodeRecord(const std::uint8_t* at, bool extended, std::uint64_t length);

/// Appends the record's header and data to `out`.
void AppendRecord(std::vector<std::uint8_t>& out, const LASRecord& record, bool extended);

} // namespace las
} // namespace pcbilateral

#endif
