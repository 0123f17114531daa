#include "LASWriter.h"

#include "LASBinary.h"
#include "LASHeaderBytes.h"
#include "LASPointEncoder.h"
#include "LASRecordBytes.h"
#include "LAZWriter.h"
#include "ReplacingFile.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

namespace pcbilateral
{

using namespace las;

struct LAZStreamWriter::Internals
{
  std::string Path;
  /// The header's records as WriteLAZ writes them: without COPC's, with the LASzip record.
  LASFileInfo Kept;
  LAZParameters Parameters;
  LASHeader Written;
  RecordsToWrite Records;
  std::unique_ptr<ReplacingFile> Output;
  std::vector<BlockSummary> Summaries;
  /// Records encoded but not compressed yet: fewer than a chunk's points after each Append, so
  /// that the chunks start at the multiples of the chunk size, as in WriteLAZ.
  std::vector<std::uint8_t> Pending;
  std::vector<std::uint64_t> ChunkPoints, ChunkBytes;
  std::uint64_t CompressedBytes = 0;
  std::uint64_t Expected = 0;
  std::uint64_t Appended = 0;
  bool Failed = false;

  std::string Fail(const std::string& message)
  {
    this->Failed = true;
    return message;
  }

  std::string WriteFailed()
  {
    return this->Fail(this->Path + ": write failed (" + std::strerror(errno ? errno : EIO) + ")");
  }

  /// Compresses and writes the pending records' first `points` points as chunks (the last one
  /// shorter when `points` is not a multiple of the chunk size), in parallel.
  bool WriteChunks(std::size_t points);
};

bool LAZStreamWriter::Internals::WriteChunks(std::size_t points)
{
  const std::size_t chunkSize = this->Parameters.ChunkSize;
  const std::size_t recordLength = this->Kept.Header.RecordLength;
  const std::size_t chunkCount = (points + chunkSize - 1) / chunkSize;
  std::vector<std::vector<std::uint8_t>> chunks(chunkCount);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < static_cast<std::int64_t>(chunkCount); ++c)
  {
    const std::size_t first = static_cast<std::size_t>(c) * chunkSize;
    chunks[static_cast<std::size_t>(c)] =
      CompressLAZChunk(this->Pending.data() + first * recordLength,
        std::min(chunkSize, points - first),
        recordLength,
        this->Parameters);
  }
  bool ok = true;
  for (std::size_t c = 0; c < chunkCount && ok; ++c)
  {
    this->ChunkPoints.push_back(std::min(chunkSize, points - c * chunkSize));
    this->ChunkBytes.push_back(chunks[c].size());
    this->CompressedBytes += chunks[c].size();
    ok =
      std::fwrite(chunks[c].data(), 1, chunks[c].size(), this->Output->Get()) == chunks[c].size();
  }
  this->Pending.erase(this->Pending.begin(),
    this->Pending.begin() + static_cast<std::ptrdiff_t>(points * recordLength));
  return ok;
}

LAZStreamWriter::LAZStreamWriter()
  : Impl(std::make_unique<Internals>())
{
}

LAZStreamWriter::~LAZStreamWriter() = default;

std::string LAZStreamWriter::Open(const std::string& path,
  const LASFileInfo& info,
  std::uint64_t count)
{
  Internals& w = *this->Impl;
  w.Path = path;
  w.Expected = count;
  const LASHeader& h = info.Header;
  std::string problem = CheckWritable(h, static_cast<std::size_t>(count));
  if (problem.empty())
  {
    problem = LAZParametersFor(h.PointFormat, h.RecordLength, w.Parameters);
  }
  if (problem.empty() && count == 0)
  {
    problem = "a LAZ file of no points is not written: write .las";
  }
  // As WriteLAZ: a COPC file's records describe its chunks, which are not the ones written.
  w.Kept = info;
  DropCOPCRecords(w.Kept);
  w.Records = SortRecords(w.Kept);
  if (problem.empty() && !w.Records.Extended.empty() && h.VersionMinor < 4)
  {
    problem = "a variable-length record longer than 65535 bytes needs LAS 1.4";
  }
  if (!problem.empty())
  {
    return w.Fail(path + ": " + problem);
  }
  AddLASzipRecord(w.Records, w.Parameters);
  w.Written = h;
  w.Written.HeaderSize = static_cast<std::uint16_t>(HeaderSizeOfVersion(h.VersionMinor));
  w.Written.OffsetToPointData =
    static_cast<std::uint32_t>(w.Written.HeaderSize + w.Records.VLRBytes.size());
  w.Written.NumberOfPoints = count;
  w.Output = std::make_unique<ReplacingFile>(path);
  std::FILE* file = w.Output->Get();
  if (!file)
  {
    return w.Fail(w.Output->OpenError());
  }
  // The header's and the chunk table offset's places; Close writes them.
  const std::vector<std::uint8_t> header(w.Written.HeaderSize, 0);
  const std::vector<std::uint8_t>& vlrBytes = w.Records.VLRBytes;
  const std::uint8_t tableOffset[8] = {};
  if (std::fwrite(header.data(), 1, header.size(), file) != header.size() ||
      std::fwrite(vlrBytes.data(), 1, vlrBytes.size(), file) != vlrBytes.size() ||
      std::fwrite(tableOffset, 1, 8, file) != 8)
  {
    return w.WriteFailed();
  }
  return std::string();
}

std::string LAZStreamWriter::Append(std::size_t count,
  const double* positions,
  const void* const* columns)
{
  Internals& w = *this->Impl;
  if (w.Failed || !w.Output || w.Appended + count > w.Expected)
  {
    return w.Fail(w.Path + ": more points written than announced, or after a failure");
  }
  const std::size_t recordLength = w.Kept.Header.RecordLength;
  const BlockEncoder encoder(w.Kept, count, positions, columns);
  const std::size_t pending = w.Pending.size();
  w.Pending.resize(pending + count * recordLength, 0);
  std::vector<BlockSummary> summaries(encoder.Blocks());
  const auto blocks = static_cast<std::int64_t>(summaries.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    const auto block = static_cast<std::size_t>(b);
    summaries[block] = encoder.Encode(block, w.Pending.data() + pending + encoder.Bytes(0, block));
  }
  if (AnyOutOfRange(summaries))
  {
    return w.Fail(w.Path + ": " + OutOfRangeMessage);
  }
  w.Summaries.insert(w.Summaries.end(), summaries.begin(), summaries.end());
  w.Appended += count;
  const std::size_t points = w.Pending.size() / recordLength;
  const std::size_t whole = points - points % w.Parameters.ChunkSize;
  if (whole > 0 && !w.WriteChunks(whole))
  {
    return w.WriteFailed();
  }
  return std::string();
}

std::string LAZStreamWriter::Close()
{
  Internals& w = *this->Impl;
  if (w.Failed || !w.Output || w.Appended != w.Expected)
  {
    return w.Fail(w.Path + ": fewer points written than announced, or after a failure");
  }
  std::FILE* file = w.Output->Get();
  const std::size_t last = w.Pending.size() / w.Kept.Header.RecordLength;
  bool ok = last == 0 || w.WriteChunks(last);
  const std::vector<std::uint8_t> table =
    EncodeLAZChunkTable(w.ChunkPoints, w.ChunkBytes, w.Parameters.ChunkSize == VariableChunkSize);
  std::vector<std::uint8_t> tail = table;
  for (const LASRecord* record : w.Records.Extended)
  {
    AppendRecord(tail, *record, true);
  }
  ok = ok && std::fwrite(tail.data(), 1, tail.size(), file) == tail.size();
  std::uint8_t tableOffset[8];
  Store<std::uint64_t>(tableOffset, w.Written.OffsetToPointData + 8 + w.CompressedBytes);
  SumBlocks(w.Summaries, w.Written);
  const std::vector<std::uint8_t> header = EncodeHeader(w.Written,
    w.Records.VLRCount,
    static_cast<std::uint32_t>(w.Records.Extended.size()),
    8 + w.CompressedBytes + table.size(),
    true);
  ok = ok && std::fseek(file, 0, SEEK_SET) == 0 &&
       std::fwrite(header.data(), 1, header.size(), file) == header.size() &&
       std::fseek(file, static_cast<long>(w.Written.OffsetToPointData), SEEK_SET) == 0 &&
       std::fwrite(tableOffset, 1, 8, file) == 8;
  w.Failed = !ok;
  return w.Output->Commit(ok, ok ? 0 : errno);
}

} // namespace pcbilateral
