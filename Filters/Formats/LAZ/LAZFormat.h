// What a LAZ file says about its compression: the LASzip record (the VLR "laszip encoded" 22204:
// the compressor, the chunk size and the items each point record is made of) and the chunk
// table (where each chunk starts and how many points it holds). Plain C++17, no VTK types.
#ifndef pcbilateral_LAZFormat_h
#define pcbilateral_LAZFormat_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcbilateral
{

/// The item types of the LASzip record: the parts a point record is cut into.
enum class LAZItemType : std::uint16_t
{
  Byte = 0,
  Point10 = 6,
  GPSTime11 = 7,
  RGB12 = 8,
  WavePacket13 = 9,
  Point14 = 10,
  RGB14 = 11,
  RGBNIR14 = 12,
  WavePacket14 = 13,
  Byte14 = 14,
};

struct LAZItem
{
  std::uint16_t Type = 0;
  std::uint16_t Size = 0;
  std::uint16_t Version = 0;
};

/// The compressors of the LASzip record.
enum class LAZCompressor : std::uint16_t
{
  None = 0,
  Pointwise = 1,
  PointwiseChunked = 2,
  LayeredChunked = 3,
};

/// The LASzip record, decoded.
struct LAZParameters
{
  std::uint16_t Compressor = 0;
  std::uint16_t Coder = 0;
  std::uint8_t VersionMajor = 0;
  std::uint8_t VersionMinor = 0;
  std::uint16_t VersionRevision = 0;
  std::uint32_t Options = 0;
  /// Points per chunk; VariableChunkSize when the chunk table gives each chunk's count.
  std::uint32_t ChunkSize = 0;
  std::vector<LAZItem> Items;
};

constexpr std::uint32_t VariableChunkSize = 0xFFFFFFFFu;

/// More points than this per compressed byte cannot be real (a million identical points take
/// 12 KB, 84 points a byte): a damaged count is refused before its memory is asked for.
constexpr std::uint64_t LAZMostPointsPerByte = 1024;

/// One chunk: where its bytes start in the file, how many there are, how many points.
struct LAZChunk
{
  std::uint64_t Offset = 0;
  std::uint64_t Bytes = 0;
  std::uint64_t Points = 0;
  /// The index of its first point in the file.
  std::uint64_t FirstPoint = 0;
};

/// The name of an item for messages, e.g. "point10 version 2".
std::string LAZItemName(const LAZItem& item);

/**
 * Decodes the LASzip record's data and checks it describes records of `recordLength` bytes of
 * point format `pointFormat` with items this reader decodes. Returns an empty string or a
 * one-line reason (an unknown compressor or coder, an item type or version not supported, item
 * sizes that do not add up to the record length).
 */
std::string ParseLAZParameters(const std::vector<std::uint8_t>& data,
  int pointFormat,
  std::size_t recordLength,
  LAZParameters& parameters);

/**
 * The chunks of the point data, from the chunk table (or, for the pointwise compressor, the one
 * chunk of all points). `data` and `size` are the whole file; the points lie from
 * `pointDataOffset` on; `pointCount` is the header's. Every chunk is checked to lie within the
 * file and the point counts to add up. Returns an empty string or a one-line reason.
 */
std::string ReadLAZChunkTable(const std::uint8_t* data,
  std::size_t size,
  std::uint64_t pointDataOffset,
  std::uint64_t pointCount,
  const LAZParameters& parameters,
  std::vector<LAZChunk>& chunks);

} // namespace pcbilateral

#endif
