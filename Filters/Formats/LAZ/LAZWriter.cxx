#include "LAZWriter.h"

#include "LASBinary.h"
#include "LAZEntropyEncoder.h"
#include "LAZItemEncoders.h"
#include "LAZLayeredEncoder.h"
#include "ProgressCheck.h"

#include <algorithm>
#include <memory>

namespace pcbilateral
{

namespace
{
using las::Store;

/// One chunk of the pointwise compressor: its first point raw, then the others coded item by
/// item.
std::vector<std::uint8_t> CompressPointwiseChunk(const std::uint8_t* records,
  std::size_t count,
  std::size_t recordLength,
  const LAZParameters& parameters)
{
  std::vector<std::unique_ptr<laz::ItemEncoder>> items;
  std::vector<std::size_t> offsets;
  std::size_t offset = 0;
  for (const LAZItem& item : parameters.Items)
  {
    items.push_back(laz::MakeItemEncoder(item));
    offsets.push_back(offset);
    offset += item.Size;
  }
  laz::ArithmeticEncoder coded;
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    items[i]->Start(records + offsets[i]);
  }
  for (std::size_t p = 1; p < count; ++p)
  {
    const std::uint8_t* record = records + p * recordLength;
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      items[i]->Encode(coded, record + offsets[i]);
    }
  }
  coded.Finish();
  std::vector<std::uint8_t> out(records, records + recordLength);
  out.insert(out.end(), coded.Bytes().begin(), coded.Bytes().end());
  return out;
}

} // namespace

std::string LAZParametersFor(int pointFormat, std::size_t recordLength, LAZParameters& parameters)
{
  // The standard record of formats 0 to 3, then 6 to 8.
  static const std::size_t standard[9] = { 20, 28, 26, 34, 0, 0, 30, 36, 38 };
  if (pointFormat < 0 || pointFormat > 8 || standard[pointFormat] == 0)
  {
    return "LAZ files of point format " + std::to_string(pointFormat) +
           " (with waveforms) are not written (formats 0 to 3 and 6 to 8 are): write .las";
  }
  const bool layered = pointFormat >= 6;
  const std::uint16_t version = layered ? 3 : 2;
  parameters = LAZParameters();
  parameters.Compressor = static_cast<std::uint16_t>(
    layered ? LAZCompressor::LayeredChunked : LAZCompressor::PointwiseChunked);
  parameters.VersionMajor = layered ? 3 : 2;
  parameters.VersionMinor = layered ? 4 : 2;
  parameters.ChunkSize = LAZWrittenChunkSize;
  auto add = [&](LAZItemType type, std::size_t size) {
    parameters.Items.push_back({ static_cast<std::uint16_t>(type), std::uint16_t(size), version });
  };
  if (layered)
  {
    add(LAZItemType::Point14, 30);
    if (pointFormat == 7)
    {
      add(LAZItemType::RGB14, 6);
    }
    if (pointFormat == 8)
    {
      add(LAZItemType::RGBNIR14, 8);
    }
  }
  else
  {
    add(LAZItemType::Point10, 20);
    if (pointFormat == 1 || pointFormat == 3)
    {
      add(LAZItemType::GPSTime11, 8);
    }
    if (pointFormat >= 2)
    {
      add(LAZItemType::RGB12, 6);
    }
  }
  if (recordLength > standard[pointFormat])
  {
    add(layered ? LAZItemType::Byte14 : LAZItemType::Byte, recordLength - standard[pointFormat]);
  }
  return std::string();
}

std::vector<std::uint8_t> EncodeLAZParameters(const LAZParameters& parameters)
{
  std::vector<std::uint8_t> data(34 + 6 * parameters.Items.size(), 0);
  std::uint8_t* d = data.data();
  Store<std::uint16_t>(d, parameters.Compressor);
  Store<std::uint16_t>(d + 2, parameters.Coder);
  d[4] = parameters.VersionMajor;
  d[5] = parameters.VersionMinor;
  Store<std::uint16_t>(d + 6, parameters.VersionRevision);
  Store<std::uint32_t>(d + 8, parameters.Options);
  Store<std::uint32_t>(d + 12, parameters.ChunkSize);
  Store<std::int64_t>(d + 16, -1); // no special EVLRs
  Store<std::int64_t>(d + 24, -1);
  Store<std::uint16_t>(d + 32, static_cast<std::uint16_t>(parameters.Items.size()));
  for (std::size_t i = 0; i < parameters.Items.size(); ++i)
  {
    Store<std::uint16_t>(d + 34 + 6 * i, parameters.Items[i].Type);
    Store<std::uint16_t>(d + 36 + 6 * i, parameters.Items[i].Size);
    Store<std::uint16_t>(d + 38 + 6 * i, parameters.Items[i].Version);
  }
  return data;
}

std::vector<std::uint8_t> CompressLAZChunk(const std::uint8_t* records,
  std::size_t count,
  std::size_t recordLength,
  const LAZParameters& parameters)
{
  return parameters.Compressor == static_cast<std::uint16_t>(LAZCompressor::LayeredChunked)
           ? laz::CompressLayeredChunk(records, count, recordLength, parameters)
           : CompressPointwiseChunk(records, count, recordLength, parameters);
}

std::vector<std::uint8_t> EncodeLAZChunkTable(const std::vector<std::uint64_t>& points,
  const std::vector<std::uint64_t>& bytes,
  bool variable)
{
  std::vector<std::uint8_t> table(8, 0);
  Store<std::uint32_t>(table.data() + 4, static_cast<std::uint32_t>(bytes.size()));
  laz::ArithmeticEncoder encoder;
  laz::IntegerEncoder entries(32, 2);
  // Each entry is coded as a difference with the previous chunk's: its points (only when the
  // chunks' sizes vary), then its bytes.
  std::int32_t previousPoints = 0;
  std::int32_t previousBytes = 0;
  for (std::size_t c = 0; c < bytes.size(); ++c)
  {
    if (variable)
    {
      const auto count = static_cast<std::int32_t>(points[c]);
      entries.Encode(encoder, previousPoints, count, 0);
      previousPoints = count;
    }
    const auto size = static_cast<std::int32_t>(bytes[c]);
    entries.Encode(encoder, previousBytes, size, 1);
    previousBytes = size;
  }
  encoder.Finish();
  table.insert(table.end(), encoder.Bytes().begin(), encoder.Bytes().end());
  return table;
}

std::vector<std::uint8_t> CompressLAZPoints(const std::uint8_t* records,
  std::size_t count,
  std::size_t recordLength,
  const LAZParameters& parameters,
  std::uint64_t pointDataOffset)
{
  const std::size_t chunkSize = parameters.ChunkSize;
  const std::size_t chunkCount = (count + chunkSize - 1) / chunkSize;
  std::vector<std::vector<std::uint8_t>> chunks(chunkCount);
  ParallelProgress progress(chunkCount);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < static_cast<std::int64_t>(chunkCount); ++c)
  {
    if (progress.StopAsked())
    {
      continue; // (the caller asks too, and writes nothing)
    }
    const std::size_t first = static_cast<std::size_t>(c) * chunkSize;
    const std::uint8_t* chunk = records + first * recordLength;
    const std::size_t points = std::min(chunkSize, count - first);
    chunks[static_cast<std::size_t>(c)] = CompressLAZChunk(chunk, points, recordLength, parameters);
    progress.Done(1);
  }
  std::size_t total = 8;
  std::vector<std::uint64_t> chunkPoints, chunkBytes;
  for (const std::vector<std::uint8_t>& chunk : chunks)
  {
    total += chunk.size();
    chunkPoints.push_back(std::min(chunkSize, count - chunkPoints.size() * chunkSize));
    chunkBytes.push_back(chunk.size());
  }
  const std::vector<std::uint8_t> table =
    EncodeLAZChunkTable(chunkPoints, chunkBytes, parameters.ChunkSize == VariableChunkSize);
  std::vector<std::uint8_t> out;
  out.reserve(total + table.size());
  out.resize(8);
  Store<std::uint64_t>(out.data(), pointDataOffset + total);
  for (const std::vector<std::uint8_t>& chunk : chunks)
  {
    out.insert(out.end(), chunk.begin(), chunk.end());
  }
  out.insert(out.end(), table.begin(), table.end());
  return out;
}

} // namespace pcbilateral
