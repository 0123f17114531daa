#include "LASWriter.h"

#include "LASBinary.h"
#include "LASHeaderBytes.h"
#include "LASPointEncoder.h"
#include "LASPointFormat.h"
#include "LASRecordBytes.h"
#include "LASWritePoints.h"
#include "LAZWriter.h"
#include "ReplacingFile.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace pcbilateral
{

namespace
{
using namespace las;

/// Encodes and writes the point records at `offset`, the file's end, mapped where possible.
/// Returns whether every write succeeded (if not, errno says why).
bool WritePoints(std::FILE* file,
  std::uint64_t offset,
  const BlockEncoder& encoder,
  std::vector<BlockSummary>& summaries)
{
  const MappedWrite mapped = WritePointsMapped(file, offset, encoder, summaries);
  return mapped == MappedWrite::NotMapped ? WritePointsInChunks(file, encoder, summaries)
                                          : mapped == MappedWrite::Written;
}

} // namespace

std::string WriteLAS(const std::string& path,
  const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns)
{
  const LASHeader& h = info.Header;
  const std::string problem = CheckWritable(h, count);
  if (!problem.empty())
  {
    return path + ": " + problem;
  }
  const RecordsToWrite records = SortRecords(info);
  if (!records.Extended.empty() && h.VersionMinor < 4)
  {
    return path + ": a variable-length record longer than 65535 bytes needs LAS 1.4";
  }
  // The header written: the given one with this file's sizes, offsets, counts and bounds.
  LASHeader written = h;
  written.HeaderSize = static_cast<std::uint16_t>(HeaderSizeOfVersion(h.VersionMinor));
  const std::size_t offsetToPoints = written.HeaderSize + records.VLRBytes.size();
  if (offsetToPoints > std::numeric_limits<std::uint32_t>::max())
  {
    return path + ": the variable-length records are too long for a LAS header";
  }
  written.OffsetToPointData = static_cast<std::uint32_t>(offsetToPoints);
  written.NumberOfPoints = count;

  ReplacingFile output(path);
  std::FILE* file = output.Get();
  if (!file)
  {
    return output.OpenError();
  }
  // The header's place first; it is written again at the end with the bounds and counts.
  std::vector<std::uint8_t> header(written.HeaderSize, 0);
  const std::vector<std::uint8_t>& vlrBytes = records.VLRBytes;
  bool ok = std::fwrite(header.data(), 1, header.size(), file) == header.size() &&
            std::fwrite(vlrBytes.data(), 1, vlrBytes.size(), file) == vlrBytes.size();

  const BlockEncoder encoder(info, count, positions, columns);
  std::vector<BlockSummary> summaries(encoder.Blocks());
  int failure = 0; // the errno of a failed write of the records
  if (ok)
  {
    ok = WritePoints(file, written.OffsetToPointData, encoder, summaries);
    failure = ok ? 0 : errno;
  }
  if (AnyOutOfRange(summaries))
  {
    return path + ": a point's coordinates do not fit the LAS records' 32-bit integers with "
                  "the scale and offset of the header (or are not finite)";
  }

  std::vector<std::uint8_t> evlrBytes;
  for (const LASRecord* record : records.Extended)
  {
    AppendRecord(evlrBytes, *record, true);
  }
  ok = ok && std::fwrite(evlrBytes.data(), 1, evlrBytes.size(), file) == evlrBytes.size();

  SumBlocks(summaries, written);
  header = EncodeHeader(written,
    records.VLRCount,
    static_cast<std::uint32_t>(records.Extended.size()),
    count * static_cast<std::uint64_t>(h.RecordLength),
    false);
  ok = ok && std::fseek(file, 0, SEEK_SET) == 0 &&
       std::fwrite(header.data(), 1, header.size(), file) == header.size();
  return output.Commit(ok, failure);
}

namespace
{
/// The records of the points encoded in memory, in parallel, for compression.
std::vector<std::uint8_t> EncodeAllRecords(const BlockEncoder& encoder,
  std::size_t count,
  std::size_t recordLength,
  std::vector<BlockSummary>& summaries)
{
  std::vector<std::uint8_t> records(count * recordLength, 0);
  const auto blocks = static_cast<std::int64_t>(summaries.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    summaries[static_cast<std::size_t>(b)] = encoder.Encode(static_cast<std::size_t>(b),
      records.data() + static_cast<std::size_t>(b) * PointsPerBlock * recordLength);
  }
  return records;
}
} // namespace

std::string WriteLAZ(const std::string& path,
  const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns)
{
  const LASHeader& h = info.Header;
  LAZParameters parameters;
  std::string problem = CheckWritable(h, count);
  if (problem.empty())
  {
    problem = LAZParametersFor(h.PointFormat, h.RecordLength, parameters);
  }
  if (problem.empty() && count == 0)
  {
    problem = "a LAZ file of no points is not written: write .las";
  }
  // A COPC file's records (its octree) describe its chunks, which are not the ones written.
  LASFileInfo kept = info;
  auto isCOPC = [](const LASRecord& record) { return record.UserId == "copc"; };
  kept.VLRs.erase(std::remove_if(kept.VLRs.begin(), kept.VLRs.end(), isCOPC), kept.VLRs.end());
  kept.EVLRs.erase(std::remove_if(kept.EVLRs.begin(), kept.EVLRs.end(), isCOPC), kept.EVLRs.end());
  RecordsToWrite records = SortRecords(kept);
  if (problem.empty() && !records.Extended.empty() && h.VersionMinor < 4)
  {
    problem = "a variable-length record longer than 65535 bytes needs LAS 1.4";
  }
  if (!problem.empty())
  {
    return path + ": " + problem;
  }
  LASRecord laszip;
  laszip.UserId = "laszip encoded";
  laszip.RecordId = 22204;
  laszip.Description = "LASzip chunked, by pcbilateral";
  laszip.Data = EncodeLAZParameters(parameters);
  AppendRecord(records.VLRBytes, laszip, false);
  ++records.VLRCount;
  LASHeader written = h;
  written.HeaderSize = static_cast<std::uint16_t>(HeaderSizeOfVersion(h.VersionMinor));
  written.OffsetToPointData =
    static_cast<std::uint32_t>(written.HeaderSize + records.VLRBytes.size());
  written.NumberOfPoints = count;

  const BlockEncoder encoder(info, count, positions, columns);
  std::vector<BlockSummary> summaries(encoder.Blocks());
  const std::vector<std::uint8_t> raw = EncodeAllRecords(encoder, count, h.RecordLength, summaries);
  if (AnyOutOfRange(summaries))
  {
    return path + ": a point's coordinates do not fit the LAS records' 32-bit integers with "
                  "the scale and offset of the header (or are not finite)";
  }
  const std::vector<std::uint8_t> points =
    CompressLAZPoints(raw.data(), count, h.RecordLength, parameters, written.OffsetToPointData);
  SumBlocks(summaries, written);
  std::vector<std::uint8_t> bytes = EncodeHeader(written,
    records.VLRCount,
    static_cast<std::uint32_t>(records.Extended.size()),
    points.size(),
    true);
  bytes.insert(bytes.end(), records.VLRBytes.begin(), records.VLRBytes.end());
  bytes.insert(bytes.end(), points.begin(), points.end());
  for (const LASRecord* record : records.Extended)
  {
    AppendRecord(bytes, *record, true);
  }
  ReplacingFile output(path);
  std::FILE* file = output.Get();
  if (!file)
  {
    return output.OpenError();
  }
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  return output.Commit(ok, ok ? 0 : errno);
}

LASFileInfo DefaultLASFileInfo(std::size_t count, const double bounds[6], bool gpsTime, bool rgb)
{
  LASFileInfo info;
  LASHeader& h = info.Header;
  const bool huge = count > std::numeric_limits<std::uint32_t>::max();
  h.VersionMinor = huge ? 4 : 2;
  h.PointFormat = huge ? static_cast<std::uint8_t>(rgb ? 7 : 6)
                       : static_cast<std::uint8_t>((gpsTime ? 1 : 0) + (rgb ? 2 : 0));
  h.RecordLength = static_cast<std::uint16_t>(LASStandardRecordLength(h.PointFormat));
  h.SystemIdentifier = "pcbilateral";
  h.GeneratingSoftware = "PointCloudBilateral";
  for (int axis = 0; axis < 3; ++axis)
  {
    const double low = std::isfinite(bounds[axis]) ? bounds[axis] : 0.0;
    const double high = std::isfinite(bounds[3 + axis]) ? bounds[3 + axis] : low;
    // A round offset at or below the lowest value; the finest power of ten that keeps the
    // whole extent within 2^31 steps, but no finer than a nanometre of a metre's units.
    h.Offset[axis] = std::floor(low);
    const double extent = std::max(high - h.Offset[axis], 1e-300);
    const double exponent = std::ceil(std::log10(extent / 2.0e9));
    h.Scale[axis] = std::pow(10.0, std::max(exponent, -9.0));
  }
  LASDimensionsFor(h.PointFormat, h.RecordLength, info.VLRs, info.Dimensions);
  return info;
}

} // namespace pcbilateral
