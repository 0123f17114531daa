// The parts of a LAS file around its point records, as the writers lay them out: the checks of
// a header before writing, the VLRs and EVLRs in their places, the header block's bytes, and
// the header's totals from the blocks of encoded points. Shared by the one-process writers
// (LASWriter.cxx) and the writing of a file in parts (LASWriteParts.cxx). Private to the LAS
// codec.
#ifndef pcbilateral_LASHeaderBytes_h
#define pcbilateral_LASHeaderBytes_h

#include "LASHeader.h"
#include "LASPointEncoder.h"
#include "LAZFormat.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcbilateral
{
namespace las
{

/// Whether a file with the header `h` and `count` points can be written. Returns an empty
/// string, or what is wrong.
std::string CheckWritable(const LASHeader& h, std::size_t count);

/// The records as they are written: the VLRs' bytes, after the header, and the records written
/// as EVLRs, after the points (the extended ones, and VLRs too long for a VLR).
struct RecordsToWrite
{
  std::vector<std::uint8_t> VLRBytes;
  std::uint32_t VLRCount = 0;
  std::vector<const LASRecord*> Extended;
};

RecordsToWrite SortRecords(const LASFileInfo& info);

/// What a writer says when a point's coordinates do not fit its records (AnyOutOfRange).
extern const char* const OutOfRangeMessage;

/// Removes a COPC file's records from the records to write as LAZ: they describe its octree's
/// chunks, which are not the ones written.
void DropCOPCRecords(LASFileInfo& info);

/// Adds the LASzip record of `parameters` (the compressor's description) to the VLRs.
void AddLASzipRecord(RecordsToWrite& records, const LAZParameters& parameters);

/// The header block of a LAS file to write: `h` with this file's sizes, offsets, counts and
/// bounds, and its numbers of VLRs and EVLRs, which follow `pointBytes` of point data
/// (compressed ones for LAZ, whose point format gets LASzip's mark).
std::vector<std::uint8_t> EncodeHeader(const LASHeader& h,
  std::uint32_t vlrs,
  std::uint32_t evlrs,
  std::uint64_t pointBytes,
  bool compressed);

bool AnyOutOfRange(const std::vector<BlockSummary>& summaries);

/// The bounds and the points by return of all the blocks into `header`.
void SumBlocks(const std::vector<BlockSummary>& summaries, LASHeader& header);

} // namespace las
} // namespace pcbilateral

#endif
