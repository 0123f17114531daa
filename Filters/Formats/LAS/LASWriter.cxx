#include "LASWriter.h"

#include "FileBytes.h"
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
  if (ProgressStopAsked())
  {
    output.Commit(false);
    return AbortedMessage;
  }
  if (AnyOutOfRange(summaries))
  {
    return path + ": " + OutOfRangeMessage;
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
  // Zeroed 8 MB at a time, asking between: the first touch of the whole buffer took 0.14 s for
  // 12 million points, unasked (pcb_abort_gaps). The caller sees a stop here too.
  std::vector<std::uint8_t> records;
  const std::size_t bytes = count * recordLength;
  records.reserve(bytes);
  constexpr std::size_t BlockBytes = std::size_t(8) << 20;
  while (records.size() < bytes)
  {
    if (ProgressPoint(0, 1))
    {
      return records;
    }
    records.resize(std::min(bytes, records.size() + BlockBytes));
  }
  const auto blocks = static_cast<std::int64_t>(summaries.size());
  ParallelProgress progress(summaries.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    if (progress.StopAsked())
    {
      continue;
    }
    progress.Done(1);
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
  DropCOPCRecords(kept);
  RecordsToWrite records = SortRecords(kept);
  if (problem.empty() && !records.Extended.empty() && h.VersionMinor < 4)
  {
    problem = "a variable-length record longer than 65535 bytes needs LAS 1.4";
  }
  if (!problem.empty())
  {
    return path + ": " + problem;
  }
  AddLASzipRecord(records, parameters);
  LASHeader written = h;
  written.HeaderSize = static_cast<std::uint16_t>(HeaderSizeOfVersion(h.VersionMinor));
  written.OffsetToPointData =
    static_cast<std::uint32_t>(written.HeaderSize + records.VLRBytes.size());
  written.NumberOfPoints = count;

  const BlockEncoder encoder(info, count, positions, columns);
  std::vector<BlockSummary> summaries(encoder.Blocks());
  SetProgressStage(0.0, 0.1);
  const std::vector<std::uint8_t> raw = EncodeAllRecords(encoder, count, h.RecordLength, summaries);
  if (ProgressStopAsked())
  {
    return AbortedMessage;
  }
  if (AnyOutOfRange(summaries))
  {
    return path + ": " + OutOfRangeMessage;
  }
  SetProgressStage(0.1, 0.9);
  const std::vector<std::uint8_t> points =
    CompressLAZPoints(raw.data(), count, h.RecordLength, parameters, written.OffsetToPointData);
  if (ProgressStopAsked())
  {
    return AbortedMessage;
  }
  SetProgressStage(0.9, 1.0);
  SumBlocks(summaries, written);
  std::vector<std::uint8_t> bytes = EncodeHeader(written,
    records.VLRCount,
    static_cast<std::uint32_t>(records.Extended.size()),
    points.size(),
    true);
  bytes.insert(bytes.end(), records.VLRBytes.begin(), records.VLRBytes.end());
  // The points from their own buffer: appended to the header's, they were copied, unasked.
  std::vector<std::uint8_t> after;
  for (const LASRecord* record : records.Extended)
  {
    AppendRecord(after, *record, true);
  }
  ReplacingFile output(path);
  std::FILE* file = output.Get();
  if (!file)
  {
    return output.OpenError();
  }
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size() &&
                  WriteInBlocks(file, points.data(), points.size()) &&
                  std::fwrite(after.data(), 1, after.size(), file) == after.size();
  if (ProgressStopAsked())
  {
    output.Commit(false);
    return AbortedMessage;
  }
  return output.Commit(ok, ok ? 0 : errno);
}

struct LASStreamWriter::Internals
{
  std::string Path;
  LASFileInfo Info;
  LASHeader Written;
  RecordsToWrite Records;
  std::unique_ptr<ReplacingFile> Output;
  std::vector<BlockSummary> Summaries;
  std::vector<std::uint8_t> Buffer;
  std::uint64_t Expected = 0;
  std::uint64_t Appended = 0;
  bool Failed = false;
  int Failure = 0;

  std::string Fail(const std::string& message)
  {
    this->Failed = true;
    return message;
  }
};

LASStreamWriter::LASStreamWriter()
  : Impl(std::make_unique<Internals>())
{
}

LASStreamWriter::~LASStreamWriter() = default;

std::string LASStreamWriter::Open(const std::string& path,
  const LASFileInfo& info,
  std::uint64_t count)
{
  Internals& w = *this->Impl;
  w.Path = path;
  w.Info = info;
  w.Expected = count;
  const std::string problem = CheckWritable(info.Header, static_cast<std::size_t>(count));
  if (!problem.empty())
  {
    return w.Fail(path + ": " + problem);
  }
  w.Records = SortRecords(w.Info);
  if (!w.Records.Extended.empty() && info.Header.VersionMinor < 4)
  {
    return w.Fail(path + ": a variable-length record longer than 65535 bytes needs LAS 1.4");
  }
  w.Written = info.Header;
  w.Written.HeaderSize = static_cast<std::uint16_t>(HeaderSizeOfVersion(info.Header.VersionMinor));
  const std::size_t offsetToPoints = w.Written.HeaderSize + w.Records.VLRBytes.size();
  if (offsetToPoints > std::numeric_limits<std::uint32_t>::max())
  {
    return w.Fail(path + ": the variable-length records are too long for a LAS header");
  }
  w.Written.OffsetToPointData = static_cast<std::uint32_t>(offsetToPoints);
  w.Written.NumberOfPoints = count;
  w.Output = std::make_unique<ReplacingFile>(path);
  std::FILE* file = w.Output->Get();
  if (!file)
  {
    return w.Fail(w.Output->OpenError());
  }
  // The header's place first; Close writes it with the bounds and counts.
  const std::vector<std::uint8_t> header(w.Written.HeaderSize, 0);
  const std::vector<std::uint8_t>& vlrBytes = w.Records.VLRBytes;
  if (std::fwrite(header.data(), 1, header.size(), file) != header.size() ||
      std::fwrite(vlrBytes.data(), 1, vlrBytes.size(), file) != vlrBytes.size())
  {
    w.Failure = errno;
    return w.Fail(path + ": write failed (" + std::strerror(w.Failure) + ")");
  }
  return std::string();
}

std::string LASStreamWriter::Append(std::size_t count,
  const double* positions,
  const void* const* columns)
{
  Internals& w = *this->Impl;
  if (w.Failed || !w.Output || w.Appended + count > w.Expected)
  {
    return w.Fail(w.Path + ": more points written than announced, or after a failure");
  }
  const BlockEncoder encoder(w.Info, count, positions, columns);
  const std::size_t bytes = count * w.Info.Header.RecordLength;
  w.Buffer.assign(bytes, 0);
  std::vector<BlockSummary> summaries(encoder.Blocks());
  const auto blocks = static_cast<std::int64_t>(summaries.size());
  const std::size_t blockBytes = PointsPerBlock * w.Info.Header.RecordLength;
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    summaries[static_cast<std::size_t>(b)] = encoder.Encode(
      static_cast<std::size_t>(b), w.Buffer.data() + static_cast<std::size_t>(b) * blockBytes);
  }
  if (AnyOutOfRange(summaries))
  {
    return w.Fail(w.Path + ": " + OutOfRangeMessage);
  }
  w.Summaries.insert(w.Summaries.end(), summaries.begin(), summaries.end());
  if (std::fwrite(w.Buffer.data(), 1, bytes, w.Output->Get()) != bytes)
  {
    w.Failure = errno;
    return w.Fail(w.Path + ": write failed (" + std::strerror(w.Failure) + ")");
  }
  w.Appended += count;
  return std::string();
}

std::string LASStreamWriter::Close()
{
  Internals& w = *this->Impl;
  if (w.Failed || !w.Output || w.Appended != w.Expected)
  {
    return w.Fail(w.Path + ": fewer points written than announced, or after a failure");
  }
  std::FILE* file = w.Output->Get();
  std::vector<std::uint8_t> evlrBytes;
  for (const LASRecord* record : w.Records.Extended)
  {
    AppendRecord(evlrBytes, *record, true);
  }
  bool ok = std::fwrite(evlrBytes.data(), 1, evlrBytes.size(), file) == evlrBytes.size();
  SumBlocks(w.Summaries, w.Written);
  const std::vector<std::uint8_t> header = EncodeHeader(w.Written,
    w.Records.VLRCount,
    static_cast<std::uint32_t>(w.Records.Extended.size()),
    w.Expected * static_cast<std::uint64_t>(w.Info.Header.RecordLength),
    false);
  ok = ok && std::fseek(file, 0, SEEK_SET) == 0 &&
       std::fwrite(header.data(), 1, header.size(), file) == header.size();
  w.Failed = !ok;
  return w.Output->Commit(ok, ok ? 0 : errno);
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
