#include "LASWriteParts.h"

#include "LASBinary.h"
#include "LASHeaderBytes.h"
#include "LASPointEncoder.h"
#include "LASRecordBytes.h"
#include "LASWritePoints.h"
#include "LAZWriter.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

namespace pcbilateral
{

namespace
{
using namespace las;

/// The summary of a part from its blocks' summaries.
LASPartSummary SummarizeBlocks(const std::vector<BlockSummary>& blocks, std::size_t count)
{
  LASHeader sums;
  SumBlocks(blocks, sums);
  LASPartSummary summary;
  summary.Count = count;
  std::copy_n(sums.Bounds, 6, summary.Bounds);
  std::copy_n(sums.PointsByReturn, 15, summary.PointsByReturn);
  summary.OutOfRange = AnyOutOfRange(blocks);
  return summary;
}
} // namespace

void MergeLASPartSummary(LASPartSummary& into, const LASPartSummary& part)
{
  if (part.Count > 0)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      const bool first = into.Count == 0;
      into.Bounds[axis] =
        first ? part.Bounds[axis] : std::min(into.Bounds[axis], part.Bounds[axis]);
      into.Bounds[3 + axis] =
        first ? part.Bounds[3 + axis] : std::max(into.Bounds[3 + axis], part.Bounds[3 + axis]);
    }
  }
  into.Count += part.Count;
  for (int r = 0; r < 15; ++r)
  {
    into.PointsByReturn[r] += part.PointsByReturn[r];
  }
  into.OutOfRange = into.OutOfRange || part.OutOfRange;
}

LASPartsLayout::LASPartsLayout(const LASFileInfo& info, std::uint64_t total, bool compressed)
  : Info(info)
  , Header(info.Header)
  , Compressed(compressed)
{
  const LASHeader& h = info.Header;
  this->Why = CheckWritable(h, static_cast<std::size_t>(total));
  if (compressed && this->Why.empty())
  {
    this->Why = LAZParametersFor(h.PointFormat, h.RecordLength, this->Parameters);
    // Each part's last chunk ends where the part ends: the chunks' sizes vary.
    this->Parameters.ChunkSize = VariableChunkSize;
  }
  if (compressed && this->Why.empty() && total == 0)
  {
    this->Why = "a LAZ file of no points is not written: write .las";
  }
  // As WriteLAZ: a COPC file's records (its octree) describe chunks that are not the ones written.
  if (compressed)
  {
    DropCOPCRecords(this->Info);
  }
  RecordsToWrite records = SortRecords(this->Info);
  if (this->Why.empty() && !records.Extended.empty() && h.VersionMinor < 4)
  {
    this->Why = "a variable-length record longer than 65535 bytes needs LAS 1.4";
  }
  if (compressed)
  {
    AddLASzipRecord(records, this->Parameters);
  }
  for (const LASRecord* record : records.Extended)
  {
    this->Extended.push_back(*record);
  }
  this->VLRBytes = std::move(records.VLRBytes);
  this->VLRCount = records.VLRCount;
  this->Header.HeaderSize = static_cast<std::uint16_t>(HeaderSizeOfVersion(h.VersionMinor));
  const std::uint64_t offsetToPoints = this->Header.HeaderSize + this->VLRBytes.size();
  if (this->Why.empty() && offsetToPoints > std::numeric_limits<std::uint32_t>::max())
  {
    this->Why = "the variable-length records are too long for a LAS header";
  }
  this->Header.OffsetToPointData = static_cast<std::uint32_t>(offsetToPoints);
  this->Header.NumberOfPoints = total;
}

std::vector<std::uint8_t> LASPartsLayout::Head(const LASPartSummary& whole,
  std::uint64_t pointBytes) const
{
  LASHeader written = this->Header;
  for (int i = 0; i < 6; ++i)
  {
    written.Bounds[i] = whole.Count > 0 ? whole.Bounds[i] : 0.0;
  }
  std::copy_n(whole.PointsByReturn, 15, written.PointsByReturn);
  std::vector<std::uint8_t> head = EncodeHeader(written,
    this->VLRCount,
    static_cast<std::uint32_t>(this->Extended.size()),
    pointBytes,
    this->Compressed);
  head.insert(head.end(), this->VLRBytes.begin(), this->VLRBytes.end());
  return head;
}

std::vector<std::uint8_t> LASPartsLayout::Tail() const
{
  std::vector<std::uint8_t> tail;
  for (const LASRecord& record : this->Extended)
  {
    AppendRecord(tail, record, true);
  }
  return tail;
}

std::string WriteLASPart(std::FILE* file,
  std::uint64_t offset,
  const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns,
  LASPartSummary& summary)
{
  summary = LASPartSummary();
  if (count == 0)
  {
    return std::string();
  }
  const BlockEncoder encoder(info, count, positions, columns);
  std::vector<BlockSummary> blocks(encoder.Blocks());
  errno = 0;
  const bool written = fseeko(file, static_cast<off_t>(offset), SEEK_SET) == 0 &&
                       WritePointsInChunks(file, encoder, blocks) && std::fflush(file) == 0;
  const int failure = errno;
  summary = SummarizeBlocks(blocks, count);
  if (summary.OutOfRange)
  {
    return OutOfRangeMessage;
  }
  if (!written)
  {
    return std::string("write failed (") + std::strerror(failure ? failure : EIO) + ")";
  }
  return std::string();
}

std::string CompressLAZPart(const LASFileInfo& info,
  const LAZParameters& parameters,
  std::size_t count,
  const double* positions,
  const void* const* columns,
  LAZPart& part,
  LASPartSummary& summary)
{
  part = LAZPart();
  summary = LASPartSummary();
  if (count == 0)
  {
    return std::string();
  }
  const std::size_t recordLength = info.Header.RecordLength;
  const BlockEncoder encoder(info, count, positions, columns);
  std::vector<BlockSummary> blocks(encoder.Blocks());
  std::vector<std::uint8_t> records(count * recordLength, 0);
  const auto blockCount = static_cast<std::int64_t>(blocks.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blockCount; ++b)
  {
    const auto block = static_cast<std::size_t>(b);
    blocks[block] = encoder.Encode(block, records.data() + encoder.Bytes(0, block));
  }
  summary = SummarizeBlocks(blocks, count);
  if (summary.OutOfRange)
  {
    return OutOfRangeMessage;
  }
  const std::size_t chunkSize = LAZWrittenChunkSize;
  const std::size_t chunkCount = (count + chunkSize - 1) / chunkSize;
  std::vector<std::vector<std::uint8_t>> chunks(chunkCount);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < static_cast<std::int64_t>(chunkCount); ++c)
  {
    const std::size_t first = static_cast<std::size_t>(c) * chunkSize;
    chunks[static_cast<std::size_t>(c)] = CompressLAZChunk(records.data() + first * recordLength,
      std::min(chunkSize, count - first),
      recordLength,
      parameters);
  }
  for (std::size_t c = 0; c < chunkCount; ++c)
  {
    part.ChunkPoints.push_back(std::min(chunkSize, count - c * chunkSize));
    part.ChunkBytes.push_back(chunks[c].size());
    part.Bytes.insert(part.Bytes.end(), chunks[c].begin(), chunks[c].end());
    std::vector<std::uint8_t>().swap(chunks[c]);
  }
  return std::string();
}

} // namespace pcbilateral
