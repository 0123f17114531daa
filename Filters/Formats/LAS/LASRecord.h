// The variable-length records of a LAS file (VLRs, and the extended ones of LAS 1.4) and their
// bytes. Plain C++17, no VTK types.
#ifndef pcbilateral_LASRecord_h
#define pcbilateral_LASRecord_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcbilateral
{

/// A variable-length record (VLR), or an extended one (EVLR, LAS 1.4).
struct LASRecord
{
  bool Extended = false;
  std::uint16_t Reserved = 0;
  std::string UserId;
  std::uint16_t RecordId = 0;
  std::string Description;
  std::vector<std::uint8_t> Data;
};

/// (E)VLRs laid out as in a file (a header of 54 bytes, 60 when extended, then the data).
std::vector<std::uint8_t> EncodeLASRecords(const std::vector<LASRecord>& records, bool extended);

/// The reverse of EncodeLASRecords; false when the bytes do not hold whole records.
bool DecodeLASRecords(const std::uint8_t* bytes,
  std::size_t size,
  bool extended,
  std::vector<LASRecord>& records);

} // namespace pcbilateral

#endif
