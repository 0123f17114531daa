#include "LAZReader.h"

#include "LASBinary.h"
#include "LAZFormat.h"
#include "LAZItemDecoders.h"
#include "LAZLayeredDecoder.h"
#include "ProgressCheck.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

namespace pcbilateral
{

namespace
{
using las::Str;

/// Decodes the `points` records of a chunk of the pointwise compressors into `out`.
std::string DecodePointwiseChunk(const std::uint8_t* begin,
  const std::uint8_t* end,
  const LAZParameters& parameters,
  std::size_t recordLength,
  std::uint64_t points,
  std::uint8_t* out)
{
  if (static_cast<std::size_t>(end - begin) < recordLength)
  {
    return "truncated: the chunk is shorter than its first point";
  }
  std::vector<std::unique_ptr<laz::ItemDecoder>> items;
  std::vector<std::size_t> offsets;
  std::size_t offset = 0;
  for (const LAZItem& item : parameters.Items)
  {
    items.push_back(laz::MakeItemDecoder(item));
    if (!items.back())
    {
      return "the LAZ item " + LAZItemName(item) + " is not supported";
    }
    offsets.push_back(offset);
    offset += item.Size;
  }
  std::memcpy(out, begin, recordLength);
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    items[i]->Start(out + offsets[i]);
  }
  laz::ArithmeticDecoder decoder(begin + recordLength, end);
  for (std::uint64_t p = 1; p < points; ++p)
  {
    if ((p & 4095) == 0 && decoder.Overrun())
    {
      break; // damaged: reported below, without decoding the rest
    }
    std::uint8_t* record = out + p * recordLength;
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      items[i]->Decode(decoder, record + offsets[i]);
    }
  }
  if (decoder.Overrun())
  {
    return "truncated or damaged: its compressed points end before its last point";
  }
  return std::string();
}

std::string DecodeChunk(const std::uint8_t* data,
  const LAZChunk& chunk,
  const LAZParameters& parameters,
  std::size_t recordLength,
  std::uint8_t* out)
{
  const std::uint8_t* begin = data + chunk.Offset;
  const std::uint8_t* end = begin + chunk.Bytes;
  if (static_cast<LAZCompressor>(parameters.Compressor) == LAZCompressor::LayeredChunked)
  {
    return laz::DecodeLayeredChunk(begin, end, parameters, recordLength, chunk.Points, out);
  }
  return DecodePointwiseChunk(begin, end, parameters, recordLength, chunk.Points, out);
}

/// Decodes the chunks [firstChunk, lastChunk], each by one thread, copying the points
/// [first, first + count) into `records`.
std::string DecodeChunks(const std::uint8_t* data,
  const std::vector<LAZChunk>& chunks,
  std::size_t firstChunk,
  std::size_t lastChunk,
  const LAZParameters& parameters,
  std::size_t recordLength,
  std::uint64_t first,
  std::uint64_t count,
  std::uint8_t* records)
{
  std::vector<std::string> problems(lastChunk + 1 - firstChunk);
  const auto total = static_cast<std::int64_t>(problems.size());
  ParallelProgress progress(count);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t k = 0; k < total; ++k)
  {
    if (progress.StopAsked())
    {
      continue;
    }
    const LAZChunk& chunk = chunks[firstChunk + static_cast<std::size_t>(k)];
    const std::uint64_t begin = std::max(first, chunk.FirstPoint);
    const std::uint64_t end = std::min(first + count, chunk.FirstPoint + chunk.Points);
    std::string& problem = problems[static_cast<std::size_t>(k)];
    if (begin == chunk.FirstPoint && end == chunk.FirstPoint + chunk.Points)
    {
      // The whole chunk is wanted: decoded in place.
      problem = DecodeChunk(
        data, chunk, parameters, recordLength, records + (begin - first) * recordLength);
    }
    else
    {
      std::vector<std::uint8_t> scratch(chunk.Points * recordLength);
      problem = DecodeChunk(data, chunk, parameters, recordLength, scratch.data());
      std::memcpy(records + (begin - first) * recordLength,
        scratch.data() + (begin - chunk.FirstPoint) * recordLength,
        (end - begin) * recordLength);
    }
    if (!problem.empty())
    {
      problem = "chunk " + Str(firstChunk + k + 1) + " of " + Str(chunks.size()) + " (" +
                Str(chunk.Points) + " points at byte " + Str(chunk.Offset) + "): " + problem;
    }
    progress.Done(end - begin);
  }
  if (progress.StopAsked())
  {
    return AbortedMessage;
  }
  for (const std::string& problem : problems)
  {
    if (!problem.empty())
    {
      return problem;
    }
  }
  return std::string();
}
} // namespace

bool IsLAZ(const std::uint8_t* data, std::size_t size)
{
  return size > 104 && std::memcmp(data, "LASF", 4) == 0 && (data[104] & 0xC0) != 0;
}

std::string DecompressLAZPoints(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::uint64_t first,
  std::uint64_t count,
  std::uint8_t* records)
{
  const LASHeader& h = info.Header;
  LAZParameters parameters;
  std::string problem =
    ParseLAZParameters(info.LASzipRecord, h.PointFormat, h.RecordLength, parameters);
  std::vector<LAZChunk> chunks;
  if (problem.empty())
  {
    problem =
      ReadLAZChunkTable(data, size, h.OffsetToPointData, h.NumberOfPoints, parameters, chunks);
  }
  if (problem.empty() && (first > h.NumberOfPoints || count > h.NumberOfPoints - first))
  {
    problem = "points " + Str(first) + " to " + Str(first + count) + " asked for, the file has " +
              Str(h.NumberOfPoints);
  }
  if (problem.empty() && count > 0)
  {
    auto holds = [](const LAZChunk& chunk, std::uint64_t point)
    { return chunk.FirstPoint + chunk.Points <= point; };
    const auto firstChunk = static_cast<std::size_t>(
      std::partition_point(
        chunks.begin(), chunks.end(), [&](const LAZChunk& c) { return holds(c, first); }) -
      chunks.begin());
    const auto lastChunk =
      static_cast<std::size_t>(std::partition_point(chunks.begin(),
                                 chunks.end(),
                                 [&](const LAZChunk& c) { return holds(c, first + count - 1); }) -
                               chunks.begin());
    problem = DecodeChunks(
      data, chunks, firstChunk, lastChunk, parameters, h.RecordLength, first, count, records);
  }
  return problem.empty() ? problem : sourceName + ": " + problem;
}

std::string DecompressLAZChunks(const std::uint8_t* data,
  const LASFileInfo& info,
  const std::string& sourceName,
  const std::vector<LAZChunk>& chunks,
  std::uint8_t* records)
{
  const LASHeader& h = info.Header;
  LAZParameters parameters;
  const std::string problem =
    ParseLAZParameters(info.LASzipRecord, h.PointFormat, h.RecordLength, parameters);
  if (!problem.empty())
  {
    return sourceName + ": " + problem;
  }
  std::vector<std::uint64_t> starts(chunks.size() + 1, 0);
  for (std::size_t k = 0; k < chunks.size(); ++k)
  {
    starts[k + 1] = starts[k] + chunks[k].Points;
  }
  std::vector<std::string> problems(chunks.size());
  const auto total = static_cast<std::int64_t>(chunks.size());
  ParallelProgress progress(starts.back());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t k = 0; k < total; ++k)
  {
    if (progress.StopAsked())
    {
      continue;
    }
    const auto index = static_cast<std::size_t>(k);
    const LAZChunk& chunk = chunks[index];
    problems[index] = DecodeChunk(
      data, chunk, parameters, h.RecordLength, records + starts[index] * h.RecordLength);
    if (!problems[index].empty())
    {
      problems[index] = sourceName + ": the chunk of " + Str(chunk.Points) + " points at byte " +
                        Str(chunk.Offset) + ": " + problems[index];
    }
    progress.Done(chunk.Points);
  }
  if (progress.StopAsked())
  {
    return AbortedMessage;
  }
  for (const std::string& message : problems)
  {
    if (!message.empty())
    {
      return message;
    }
  }
  return std::string();
}

std::string UncompressedLASRecords(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::vector<std::uint8_t>& decompressed,
  const std::uint8_t*& records)
{
  return UncompressedLASRecordRange(
    data, size, info, sourceName, 0, info.Header.NumberOfPoints, decompressed, records);
}

std::string UncompressedLASRecordRange(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::uint64_t first,
  std::uint64_t count,
  std::vector<std::uint8_t>& decompressed,
  const std::uint8_t*& records)
{
  const LASHeader& h = info.Header;
  if (first > h.NumberOfPoints || count > h.NumberOfPoints - first)
  {
    return sourceName + ": points " + Str(first) + " to " + Str(first + count) +
           " asked for, the file has " + Str(h.NumberOfPoints);
  }
  if (info.LASzipRecord.empty())
  {
    records = data + h.OffsetToPointData + first * h.RecordLength;
    return std::string();
  }
  decompressed.clear();
  // The LASzip record is checked before the memory of the points is asked for: a record length
  // its items do not add up to must not cost gigabytes first.
  LAZParameters parameters;
  std::string problem =
    ParseLAZParameters(info.LASzipRecord, h.PointFormat, h.RecordLength, parameters);
  if (!problem.empty())
  {
    return sourceName + ": " + problem;
  }
  const std::uint64_t compressedBytes = size - h.OffsetToPointData;
  if (h.NumberOfPoints > LAZMostPointsPerByte * compressedBytes + 1)
  {
    return sourceName + ": truncated or damaged: " + Str(h.NumberOfPoints) +
           " points announced, impossible in " + Str(compressedBytes) +
           " bytes of compressed points";
  }
  try
  {
    // Zeroed 8 MB at a time, asking between: the first touch of the whole buffer (400 MB for
    // 12 million points) took 0.12 s before the read's first question (pcb_abort_gaps).
    const std::size_t bytes = count * h.RecordLength;
    decompressed.reserve(bytes);
    constexpr std::size_t BlockBytes = std::size_t(8) << 20;
    while (decompressed.size() < bytes)
    {
      if (ProgressPoint(0, 1))
      {
        return AbortedMessage;
      }
      decompressed.resize(std::min(bytes, decompressed.size() + BlockBytes));
    }
  }
  catch (const std::bad_alloc&)
  {
    problem = sourceName + ": not enough memory for " + Str(count) + " points";
  }
  if (problem.empty())
  {
    problem = DecompressLAZPoints(data, size, info, sourceName, first, count, decompressed.data());
  }
  records = decompressed.data();
  return problem;
}

std::string LASColoursFitEightBits(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::uint64_t first,
  std::uint64_t count,
  bool& fit)
{
  fit = true;
  const auto rgb = std::find_if(info.Dimensions.begin(),
    info.Dimensions.end(),
    [](const LASDimension& dimension) { return dimension.Name == "RGB"; });
  if (rgb == info.Dimensions.end())
  {
    return std::string();
  }
  // A block of points a few LAZ chunks long (50,000 points each by default).
  constexpr std::uint64_t PointsPerBlock = std::uint64_t(1) << 18;
  const std::size_t stride = info.Header.RecordLength;
  std::vector<std::uint8_t> decompressed;
  for (std::uint64_t start = first; start < first + count && fit; start += PointsPerBlock)
  {
    const std::uint64_t points = std::min(PointsPerBlock, first + count - start);
    const std::uint8_t* records = nullptr;
    std::string problem = UncompressedLASRecordRange(
      data, size, info, sourceName, start, points, decompressed, records);
    if (!problem.empty())
    {
      return problem;
    }
    for (std::uint64_t i = 0; i < points * 3 && fit; ++i)
    {
      fit =
        las::Load<std::uint16_t>(records + (i / 3) * stride + rgb->ByteOffset + 2 * (i % 3)) <= 255;
    }
  }
  return std::string();
}

} // namespace pcbilateral
