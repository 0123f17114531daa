// Reading the point records of a LAZ file (LASzip-compressed LAS): decompressed into the
// records a LAS file would hold, byte for byte, so that everything that reads LAS records
// (DecodeLASPoints, LASReader.h) reads LAZ too. Plain C++17, no VTK types.
#ifndef pcbilateral_LAZReader_h
#define pcbilateral_LAZReader_h

#include "LASHeader.h"
#include "LAZFormat.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcbilateral
{

/// Whether a file's first bytes are those of a LAS file whose points are compressed (LAZ).
bool IsLAZ(const std::uint8_t* data, std::size_t size);

/**
 * Decompresses points [first, first + count) of a LAZ file held in `data` (its `size` bytes),
 * whose header and VLRs `info` holds (ParseLASHeader with compressed files accepted), into
 * `records` (count * RecordLength bytes). Only the chunks holding those points are decoded,
 * in parallel (OpenMP), each chunk by one thread: the records do not depend on the number of
 * threads. Returns an empty string, or a one-line message starting with `sourceName`: a
 * compressor, point format or item not supported (waveforms), a corrupt chunk table, a
 * truncated or damaged chunk.
 */
std::string DecompressLAZPoints(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::uint64_t first,
  std::uint64_t count,
  std::uint8_t* records);

/**
 * Decompresses whole chunks of a LAZ file, `chunks` (some of those ReadLAZChunkTable gives for
 * it, in any order), into `records`, one after the other in the order given: each chunk's
 * Points * RecordLength bytes. In parallel (OpenMP), each chunk by one thread. Returns an empty
 * string or a one-line message starting with `sourceName`.
 */
std::string DecompressLAZChunks(const std::uint8_t* data,
  const LASFileInfo& info,
  const std::string& sourceName,
  const std::vector<LAZChunk>& chunks,
  std::uint8_t* records);

/**
 * The point records of a file ParseLASHeader accepted, uncompressed: a LAS file's own bytes
 * (`records` points into `data`), or a LAZ file's, all decompressed into `decompressed`. Returns
 * an empty string or DecompressLAZPoints' message.
 */
std::string UncompressedLASRecords(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::vector<std::uint8_t>& decompressed,
  const std::uint8_t*& records);

/**
 * The records of points [first, first + count) only (a piece of a distributed read,
 * PointPieces.h): a LAS file's own bytes (`records` points at the first of them in `data`, so
 * a memory-mapped file brings in only their pages), or, for a LAZ file, only the chunks that
 * hold them decompressed and trimmed to the range in `decompressed`. With the whole range it is
 * UncompressedLASRecords. Returns an empty string or a one-line message starting with
 * `sourceName` (a range beyond the file's points, DecompressLAZPoints' messages).
 */
std::string UncompressedLASRecordRange(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::uint64_t first,
  std::uint64_t count,
  std::vector<std::uint8_t>& decompressed,
  const std::uint8_t*& records);

/**
 * Whether every 16-bit RGB value of points [first, first + count) is at most 255 (a file that
 * stores 8-bit colours in the 16-bit fields, as many programs do); true without RGB. Stops at
 * the first larger value; a LAZ file's points are decompressed a block of chunks at a time, so
 * the memory stays that of a block. Returns an empty string or UncompressedLASRecordRange's
 * message.
 */
std::string LASColoursFitEightBits(const std::uint8_t* data,
  std::size_t size,
  const LASFileInfo& info,
  const std::string& sourceName,
  std::uint64_t first,
  std::uint64_t count,
  bool& fit);

} // namespace pcbilateral

#endif
