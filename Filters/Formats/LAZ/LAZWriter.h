// Compressing LAS point records into LAZ (LASzip's chunked compressor, items version 2, for
// point formats 0 to 3; its layered one, items version 3, for 6 to 8), for WriteLAZ
// (LASWriter.h). Plain C++17, no VTK types.
#ifndef pcbilateral_LAZWriter_h
#define pcbilateral_LAZWriter_h

#include "LAZFormat.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcbilateral
{

/// Points per chunk of the LAZ files written (LASzip's default).
constexpr std::uint32_t LAZWrittenChunkSize = 50000;

/**
 * The LASzip record for records of `pointFormat` of `recordLength` bytes: the chunked
 * compressor and the items of the format (then the extra bytes) in version 2 for formats 0 to
 * 3, the layered compressor and items version 3 for 6 to 8. Returns an empty string, or why
 * such records are not written as LAZ (the waveform formats 4, 5, 9 and 10).
 */
std::string LAZParametersFor(int pointFormat, std::size_t recordLength, LAZParameters& parameters);

/// The LASzip record's data (the VLR "laszip encoded" 22204) for `parameters`.
std::vector<std::uint8_t> EncodeLAZParameters(const LAZParameters& parameters);

/// One chunk of `count` records compressed: the bytes CompressLAZPoints gives for each chunk.
std::vector<std::uint8_t> CompressLAZChunk(const std::uint8_t* records,
  std::size_t count,
  std::size_t recordLength,
  const LAZParameters& parameters);

/**
 * The chunk table of chunks of `points[c]` points and `bytes[c]` bytes: its version, its count,
 * then the entries, arithmetic-coded; each chunk's point count only when `variable` (the
 * LASzip record's chunk size is VariableChunkSize).
 */
std::vector<std::uint8_t> EncodeLAZChunkTable(const std::vector<std::uint64_t>& points,
  const std::vector<std::uint64_t>& bytes,
  bool variable);

/**
 * Compresses `count` records of `recordLength` bytes into the bytes of a LAZ file from its point
 * data on (which starts at byte `pointDataOffset` of the file): the chunk table's offset, the
 * chunks, compressed in parallel (OpenMP; the bytes do not depend on the number of threads), and
 * the chunk table.
 */
std::vector<std::uint8_t> CompressLAZPoints(const std::uint8_t* records,
  std::size_t count,
  std::size_t recordLength,
  const LAZParameters& parameters,
  std::uint64_t pointDataOffset);

} // namespace pcbilateral

#endif
