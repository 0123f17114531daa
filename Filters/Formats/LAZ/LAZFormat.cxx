#include "LAZFormat.h"

#include "LASBinary.h"
#include "LAZEntropyDecoder.h"

namespace pcbilateral
{

namespace
{
using las::Load;
using las::Str;

constexpr std::uint64_t MostPointsPerByte = LAZMostPointsPerByte;

/// The items a point format is made of, in order; the extra bytes may follow as one byte item.
std::vector<LAZItemType> ItemsOfPointFormat(int pointFormat)
{
  using T = LAZItemType;
  switch (pointFormat)
  {
    case 0:
      return { T::Point10 };
    case 1:
      return { T::Point10, T::GPSTime11 };
    case 2:
      return { T::Point10, T::RGB12 };
    case 3:
      return { T::Point10, T::GPSTime11, T::RGB12 };
    case 6:
      return { T::Point14 };
    case 7:
      return { T::Point14, T::RGB14 };
    case 8:
      return { T::Point14, T::RGBNIR14 };
    default:
      return {};
  }
}

std::size_t ItemSizeOf(LAZItemType type)
{
  switch (type)
  {
    case LAZItemType::Point10:
      return 20;
    case LAZItemType::GPSTime11:
      return 8;
    case LAZItemType::RGB12:
    case LAZItemType::RGB14:
      return 6;
    case LAZItemType::RGBNIR14:
      return 8;
    case LAZItemType::Point14:
      return 30;
    default:
      return 0;
  }
}

bool ItemVersionSupported(const LAZItem& item)
{
  switch (static_cast<LAZItemType>(item.Type))
  {
    case LAZItemType::Point10:
    case LAZItemType::GPSTime11:
    case LAZItemType::RGB12:
    case LAZItemType::Byte:
      // Version 1 (LASzip 1.x, 2011 and before) has no extra-bytes item here.
      return item.Version == 2 || (item.Version == 1 && item.Type != 0);
    case LAZItemType::Point14:
    case LAZItemType::RGB14:
    case LAZItemType::RGBNIR14:
    case LAZItemType::Byte14:
      return item.Version == 3;
    default:
      return false;
  }
}

/// Whether the items are those of the point format, in its order, with their sizes.
std::string CheckItems(const LAZParameters& parameters, int pointFormat, std::size_t recordLength)
{
  if (pointFormat == 4 || pointFormat == 5 || pointFormat == 9 || pointFormat == 10)
  {
    return "LAZ point format " + std::to_string(pointFormat) +
           " (with waveforms) is not supported; formats 0 to 3 and 6 to 8 are";
  }
  const std::vector<LAZItemType> expected = ItemsOfPointFormat(pointFormat);
  const bool extended = pointFormat >= 6;
  std::size_t total = 0;
  for (std::size_t i = 0; i < parameters.Items.size(); ++i)
  {
    const LAZItem& item = parameters.Items[i];
    const auto type = static_cast<LAZItemType>(item.Type);
    const bool standard = i < expected.size();
    const LAZItemType wanted =
      standard ? expected[i] : (extended ? LAZItemType::Byte14 : LAZItemType::Byte);
    if (type != wanted || (standard && item.Size != ItemSizeOf(type)) || item.Size == 0)
    {
      return "the LASzip record's item " + Str(i + 1) + " (" + LAZItemName(item) + ", " +
             Str(item.Size) + " bytes) does not fit point format " + std::to_string(pointFormat);
    }
    if (!ItemVersionSupported(item))
    {
      return "the LAZ item " + LAZItemName(item) + " is not supported";
    }
    total += item.Size;
  }
  if (parameters.Items.size() < expected.size() || total != recordLength)
  {
    return "the LASzip record's items make records of " + Str(total) + " bytes, the header says " +
           Str(recordLength);
  }
  return std::string();
}
} // namespace

std::string LAZItemName(const LAZItem& item)
{
  const char* name = "unknown item";
  switch (static_cast<LAZItemType>(item.Type))
  {
    case LAZItemType::Byte:
      name = "byte";
      break;
    case LAZItemType::Point10:
      name = "point10";
      break;
    case LAZItemType::GPSTime11:
      name = "gpstime11";
      break;
    case LAZItemType::RGB12:
      name = "rgb12";
      break;
    case LAZItemType::WavePacket13:
      name = "wavepacket13";
      break;
    case LAZItemType::Point14:
      name = "point14";
      break;
    case LAZItemType::RGB14:
      name = "rgb14";
      break;
    case LAZItemType::RGBNIR14:
      name = "rgbnir14";
      break;
    case LAZItemType::WavePacket14:
      name = "wavepacket14";
      break;
    case LAZItemType::Byte14:
      name = "byte14";
      break;
  }
  return std::string(name) + " (type " + Str(item.Type) + ") version " + Str(item.Version);
}

std::string ParseLAZParameters(const std::vector<std::uint8_t>& data,
  int pointFormat,
  std::size_t recordLength,
  LAZParameters& parameters)
{
  constexpr std::size_t FixedPart = 34;
  if (data.size() < FixedPart)
  {
    return "the LASzip record is " + Str(data.size()) + " bytes, shorter than its " +
           Str(FixedPart) + " fixed bytes";
  }
  const std::uint8_t* d = data.data();
  parameters = LAZParameters();
  parameters.Compressor = Load<std::uint16_t>(d);
  parameters.Coder = Load<std::uint16_t>(d + 2);
  parameters.VersionMajor = d[4];
  parameters.VersionMinor = d[5];
  parameters.VersionRevision = Load<std::uint16_t>(d + 6);
  parameters.Options = Load<std::uint32_t>(d + 8);
  parameters.ChunkSize = Load<std::uint32_t>(d + 12);
  const std::uint16_t itemCount = Load<std::uint16_t>(d + 32);
  if (data.size() < FixedPart + 6 * std::size_t(itemCount))
  {
    return "the LASzip record announces " + Str(itemCount) + " items but holds " +
           Str((data.size() - FixedPart) / 6);
  }
  for (std::uint16_t i = 0; i < itemCount; ++i)
  {
    const std::uint8_t* at = d + FixedPart + 6 * std::size_t(i);
    parameters.Items.push_back(
      { Load<std::uint16_t>(at), Load<std::uint16_t>(at + 2), Load<std::uint16_t>(at + 4) });
  }
  const auto compressor = static_cast<LAZCompressor>(parameters.Compressor);
  if (compressor != LAZCompressor::Pointwise && compressor != LAZCompressor::PointwiseChunked &&
      compressor != LAZCompressor::LayeredChunked)
  {
    return "the LAZ compressor " + Str(parameters.Compressor) +
           " is not supported (1 pointwise, 2 chunked and 3 layered chunked are)";
  }
  if (parameters.Coder != 0)
  {
    return "the LAZ coder " + Str(parameters.Coder) + " is not supported (0, arithmetic, is)";
  }
  if ((compressor == LAZCompressor::LayeredChunked) != (pointFormat >= 6))
  {
    return "the LAZ compressor " + Str(parameters.Compressor) + " does not fit point format " +
           std::to_string(pointFormat) + " (formats 6 to 10 are layered, compressor 3)";
  }
  if (parameters.ChunkSize == 0 && compressor != LAZCompressor::Pointwise)
  {
    return "the LASzip record's chunk size is 0";
  }
  return CheckItems(parameters, pointFormat, recordLength);
}

namespace
{
/// Where the chunk table starts: given at the start of the point data, or, when a writer
/// could not go back there (-1), in the file's last 8 bytes.
std::string ChunkTableOffset(const std::uint8_t* data,
  std::size_t size,
  std::uint64_t pointDataOffset,
  std::uint64_t& tableOffset)
{
  if (pointDataOffset + 8 > size)
  {
    return "truncated: the file ends before its chunk table's offset";
  }
  tableOffset = Load<std::uint64_t>(data + pointDataOffset);
  if (tableOffset == ~std::uint64_t(0) && size >= 8)
  {
    tableOffset = Load<std::uint64_t>(data + size - 8);
  }
  if (tableOffset < pointDataOffset + 8 || tableOffset > size || size - tableOffset < 8)
  {
    return "truncated or damaged: the chunk table should be at byte " + Str(tableOffset) +
           ", the file has " + Str(size) + " bytes";
  }
  return std::string();
}

/// Each chunk's point count (if variable) and byte count, coded as differences with the
/// previous chunk's.
std::string DecodeChunkEntries(const std::uint8_t* begin,
  const std::uint8_t* end,
  bool variable,
  std::vector<LAZChunk>& chunks)
{
  laz::ArithmeticDecoder decoder(begin, end);
  laz::IntegerDecoder entries(32, 2);
  std::int32_t points = 0;
  std::int32_t bytes = 0;
  for (LAZChunk& chunk : chunks)
  {
    if (variable)
    {
      points = entries.Decode(decoder, points, 0);
      chunk.Points = static_cast<std::uint32_t>(points);
    }
    bytes = entries.Decode(decoder, bytes, 1);
    chunk.Bytes = static_cast<std::uint32_t>(bytes);
  }
  if (decoder.Overrun())
  {
    return "the chunk table is truncated or corrupt";
  }
  return std::string();
}
} // namespace

std::string ReadLAZChunkTable(const std::uint8_t* data,
  std::size_t size,
  std::uint64_t pointDataOffset,
  std::uint64_t pointCount,
  const LAZParameters& parameters,
  std::vector<LAZChunk>& chunks)
{
  chunks.clear();
  if (static_cast<LAZCompressor>(parameters.Compressor) == LAZCompressor::Pointwise)
  {
    // One stream of all points, up to the end of the file (or its EVLRs: the decoder stops
    // where the points end).
    chunks.push_back({ pointDataOffset, size - pointDataOffset, pointCount, 0 });
    if (pointCount > MostPointsPerByte * (size - pointDataOffset) + 1)
    {
      return "truncated: " + Str(pointCount) + " points announced, impossible in " +
             Str(size - pointDataOffset) + " bytes of compressed points";
    }
    return std::string();
  }
  std::uint64_t tableOffset = 0;
  std::string problem = ChunkTableOffset(data, size, pointDataOffset, tableOffset);
  if (!problem.empty())
  {
    return problem;
  }
  const std::uint32_t version = Load<std::uint32_t>(data + tableOffset);
  const std::uint32_t count = Load<std::uint32_t>(data + tableOffset + 4);
  if (version != 0)
  {
    return "the chunk table's version " + Str(version) + " is not supported (0 is)";
  }
  // Every chunk holds at least one byte, which bounds the count of a corrupt table.
  if (count > tableOffset - pointDataOffset - 8 || (count == 0 && pointCount > 0))
  {
    return "the chunk table lists " + Str(count) + " chunks, impossible in " +
           Str(tableOffset - pointDataOffset - 8) + " bytes of points";
  }
  chunks.resize(count);
  const bool variable = parameters.ChunkSize == VariableChunkSize;
  problem = DecodeChunkEntries(data + tableOffset + 8, data + size, variable, chunks);
  if (!problem.empty())
  {
    return problem;
  }
  std::uint64_t offset = pointDataOffset + 8;
  std::uint64_t first = 0;
  for (LAZChunk& chunk : chunks)
  {
    if (!variable)
    {
      chunk.Points = std::min<std::uint64_t>(parameters.ChunkSize, pointCount - first);
    }
    chunk.Offset = offset;
    chunk.FirstPoint = first;
    if (chunk.Points > MostPointsPerByte * chunk.Bytes + 1)
    {
      return "corrupt chunk table: chunk " + Str(&chunk - chunks.data() + 1) + " of " + Str(count) +
             " claims " + Str(chunk.Points) + " points in " + Str(chunk.Bytes) + " bytes";
    }
    if (chunk.Bytes > tableOffset - offset)
    {
      return "corrupt chunk table: chunk " + Str(&chunk - chunks.data() + 1) + " of " + Str(count) +
             " runs past the chunk table";
    }
    offset += chunk.Bytes;
    first += chunk.Points;
  }
  if (first != pointCount)
  {
    return "corrupt chunk table: its chunks hold " + Str(first) + " points, the header says " +
           Str(pointCount);
  }
  return std::string();
}

} // namespace pcbilateral
