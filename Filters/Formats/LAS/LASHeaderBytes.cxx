#include "LASHeaderBytes.h"

#include "LASBinary.h"
#include "LASPointFormat.h"
#include "LASRecordBytes.h"
#include "LAZWriter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace pcbilateral
{
namespace las
{

/// Whether a file with the header `h` and `count` points can be written. Returns an empty
/// string, or what is wrong.
std::string CheckWritable(const LASHeader& h, std::size_t count)
{
  const std::size_t standard = LASStandardRecordLength(h.PointFormat);
  if (standard == 0 || h.RecordLength < standard)
  {
    return "cannot write point format " + std::to_string(h.PointFormat) + " with records of " +
           Str(h.RecordLength) + " bytes";
  }
  if (h.VersionMajor != 1 || h.VersionMinor > 4 || (h.PointFormat > 5 && h.VersionMinor < 4))
  {
    return "cannot write point format " + std::to_string(h.PointFormat) + " in LAS " +
           std::to_string(h.VersionMajor) + "." + std::to_string(h.VersionMinor);
  }
  if (h.VersionMinor < 4 && count > std::numeric_limits<std::uint32_t>::max())
  {
    return Str(count) + " points do not fit in LAS 1." + std::to_string(h.VersionMinor) +
           " (at most 4294967295; LAS 1.4 holds more)";
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!std::isfinite(h.Scale[axis]) || h.Scale[axis] == 0.0 || !std::isfinite(h.Offset[axis]))
    {
      return std::string("the scale or offset of ") + "xyz"[axis] + " is zero or not finite";
    }
  }
  return std::string();
}

RecordsToWrite SortRecords(const LASFileInfo& info)
{
  RecordsToWrite records;
  for (const LASRecord& record : info.VLRs)
  {
    if (record.Extended || record.Data.size() > 0xFFFF)
    {
      records.Extended.push_back(&record);
      continue;
    }
    AppendRecord(records.VLRBytes, record, false);
    ++records.VLRCount;
  }
  for (const LASRecord& record : info.EVLRs)
  {
    records.Extended.push_back(&record);
  }
  return records;
}

const char* const OutOfRangeMessage = "a point's coordinates do not fit the LAS records' 32-bit "
                                      "integers with the scale and offset of the header (or are "
                                      "not finite)";

void DropCOPCRecords(LASFileInfo& info)
{
  auto isCOPC = [](const LASRecord& record) { return record.UserId == "copc"; };
  info.VLRs.erase(std::remove_if(info.VLRs.begin(), info.VLRs.end(), isCOPC), info.VLRs.end());
  info.EVLRs.erase(std::remove_if(info.EVLRs.begin(), info.EVLRs.end(), isCOPC), info.EVLRs.end());
}

void AddLASzipRecord(RecordsToWrite& records, const LAZParameters& parameters)
{
  LASRecord laszip;
  laszip.UserId = "laszip encoded";
  laszip.RecordId = 22204;
  laszip.Description = "LASzip chunked, by pcbilateral";
  laszip.Data = EncodeLAZParameters(parameters);
  AppendRecord(records.VLRBytes, laszip, false);
  ++records.VLRCount;
}

/// The header block of a LAS file to write: `h` with this file's sizes, offsets, counts and
/// bounds, and its numbers of VLRs and EVLRs, which follow `pointBytes` of point data
/// (compressed ones for LAZ, whose point format gets LASzip's mark).
std::vector<std::uint8_t> EncodeHeader(const LASHeader& h,
  std::uint32_t vlrs,
  std::uint32_t evlrs,
  std::uint64_t pointBytes,
  bool compressed)
{
  std::vector<std::uint8_t> out(h.HeaderSize, 0);
  std::uint8_t* d = out.data();
  std::memcpy(d, "LASF", 4);
  Store<std::uint16_t>(d + 4, h.FileSourceId);
  // Bit 1 says waveform data is inside the file: it is not kept, so it is not written.
  Store<std::uint16_t>(d + 6, static_cast<std::uint16_t>(h.GlobalEncoding & ~2u));
  std::memcpy(d + 8, h.ProjectId, 16);
  d[24] = h.VersionMajor;
  d[25] = h.VersionMinor;
  StoreString(d + 26, h.SystemIdentifier, 32);
  StoreString(d + 58, h.GeneratingSoftware, 32);
  Store<std::uint16_t>(d + 90, h.CreationDay);
  Store<std::uint16_t>(d + 92, h.CreationYear);
  Store<std::uint16_t>(d + 94, h.HeaderSize);
  Store<std::uint32_t>(d + 96, h.OffsetToPointData);
  Store<std::uint32_t>(d + 100, vlrs);
  d[104] = static_cast<std::uint8_t>(h.PointFormat | (compressed ? 0x80 : 0));
  Store<std::uint16_t>(d + 105, h.RecordLength);
  const bool legacy =
    h.PointFormat <= 5 && h.NumberOfPoints <= std::numeric_limits<std::uint32_t>::max();
  Store<std::uint32_t>(d + 107, legacy ? static_cast<std::uint32_t>(h.NumberOfPoints) : 0u);
  for (int r = 0; r < 5; ++r)
  {
    Store<std::uint32_t>(d + 111 + 4 * r,
      legacy ? static_cast<std::uint32_t>(std::min<std::uint64_t>(h.PointsByReturn[r], 0xFFFFFFFFu))
             : 0u);
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    Store<double>(d + 131 + 8 * axis, h.Scale[axis]);
    Store<double>(d + 155 + 8 * axis, h.Offset[axis]);
    Store<double>(d + 179 + 16 * axis, h.Bounds[3 + axis]);
    Store<double>(d + 187 + 16 * axis, h.Bounds[axis]);
  }
  if (h.VersionMinor >= 4)
  {
    const std::uint64_t evlrStart = evlrs ? h.OffsetToPointData + pointBytes : 0;
    Store<std::uint64_t>(d + 235, evlrStart);
    Store<std::uint32_t>(d + 243, evlrs);
    Store<std::uint64_t>(d + 247, h.NumberOfPoints);
    for (int r = 0; r < 15; ++r)
    {
      Store<std::uint64_t>(d + 255 + 8 * r, h.PointsByReturn[r]);
    }
  }
  return out;
}

bool AnyOutOfRange(const std::vector<BlockSummary>& summaries)
{
  return std::any_of(summaries.begin(),
    summaries.end(),
    [](const BlockSummary& summary) { return summary.OutOfRange; });
}

/// The bounds and the points by return of all the blocks into `header`.
void SumBlocks(const std::vector<BlockSummary>& summaries, LASHeader& header)
{
  std::fill_n(header.Bounds, 6, 0.0);
  std::fill_n(header.PointsByReturn, 15, 0);
  for (std::size_t b = 0; b < summaries.size(); ++b)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      header.Bounds[axis] = b == 0 ? summaries[b].Bounds[axis]
                                   : std::min(header.Bounds[axis], summaries[b].Bounds[axis]);
      header.Bounds[3 + axis] =
        b == 0 ? summaries[b].Bounds[3 + axis]
               : std::max(header.Bounds[3 + axis], summaries[b].Bounds[3 + axis]);
    }
    for (int r = 0; r < 15; ++r)
    {
      header.PointsByReturn[r] += summaries[b].ByReturn[r];
    }
  }
}

} // namespace las
} // namespace pcbilateral
