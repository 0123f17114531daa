// Writing one LAS or LAZ file in parts, each part's points by another writer (the processes of
// an MPI run), none of them holding the whole cloud. Plain C++17, no VTK types and no MPI: the
// caller exchanges the few numbers that the parts must share (counts, byte sizes, the parts'
// summaries, a LAZ file's chunk sizes) in whatever way it communicates.
//
// A LAS file: every part's records lie at the file's point data plus the points before it
// (an exclusive prefix sum of the parts' counts) times the record length, so each writer
// writes its records there; the header, written once, takes the totals of all the parts'
// summaries. A LAZ file: each part compresses its own chunks (at most LAZWrittenChunkSize
// points each; the LASzip record says the chunks' sizes vary, since a part's last chunk is
// cut where the part ends) and writes them at the compressed bytes before it; the chunk table
// (two numbers per chunk) is gathered and written once, after the chunks.
//
//   head (header and VLRs) | LAZ: 8 bytes | part 0's points | part 1's | ... | LAZ: chunk table |
//   EVLRs
#ifndef pcbilateral_LASWriteParts_h
#define pcbilateral_LASWriteParts_h

#include "LASHeader.h"
#include "LAZFormat.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace pcbilateral
{

/// What the points of one part add to the file's header.
struct LASPartSummary
{
  std::uint64_t Count = 0;
  /// The bounds of the stored coordinates (min x, y, z, max x, y, z); meaningful when Count > 0.
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  std::uint64_t PointsByReturn[15] = {};
  /// A coordinate did not fit the records' 32-bit integers with the header's scale and offset.
  bool OutOfRange = false;
};

/// `into` extended by `part`: the summary of both parts' points as one file has them.
void MergeLASPartSummary(LASPartSummary& into, const LASPartSummary& part);

/// The layout of a file written in parts: what comes before and after the point data.
class LASPartsLayout
{
public:
  /// A file with the header and records of `info` and `total` points, LAZ when `compressed`.
  LASPartsLayout(const LASFileInfo& info, std::uint64_t total, bool compressed);

  /// Empty, or why such a file cannot be written (as WriteLAS and WriteLAZ would say it).
  const std::string& Problem() const { return this->Why; }

  /// Where the point data starts: the first record of a LAS file; a LAZ file's chunk table
  /// offset (8 bytes), its first chunk after it.
  std::uint64_t PointDataOffset() const { return this->Header.OffsetToPointData; }

  /// A LAZ file's LASzip record (chunks of varying sizes).
  const LAZParameters& Compression() const { return this->Parameters; }

  /**
   * The bytes from the file's start to its point data, for the summary of all the parts and
   * `pointBytes` bytes of point data (a LAZ file's: from its chunk table offset to the end of
   * the chunk table); a LAZ file's 8 bytes of chunk table offset are not included.
   */
  std::vector<std::uint8_t> Head(const LASPartSummary& whole, std::uint64_t pointBytes) const;

  /// The EVLRs' bytes, written after the point data.
  std::vector<std::uint8_t> Tail() const;

private:
  LASFileInfo Info;
  LASHeader Header;
  bool Compressed;
  LAZParameters Parameters;
  std::vector<std::uint8_t> VLRBytes;
  std::uint32_t VLRCount = 0;
  std::vector<LASRecord> Extended;
  std::string Why;
};

/**
 * Encodes `count` points (as WriteLAS takes them) into records of `info` and writes them at
 * byte `offset` of `file`, opened for update, with fwrite while the next ones are encoded.
 * Fills `summary`. Returns an empty string or one line (a coordinate out of range: nothing
 * more is written; a failed write, with errno's reason).
 */
std::string WriteLASPart(std::FILE* file,
  std::uint64_t offset,
  const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns,
  LASPartSummary& summary);

/// A part's compressed points: its chunks one after another, and each chunk's points and bytes.
struct LAZPart
{
  std::vector<std::uint8_t> Bytes;
  std::vector<std::uint64_t> ChunkPoints;
  std::vector<std::uint64_t> ChunkBytes;
};

/**
 * Encodes `count` points into records of `info` and compresses them in chunks of at most
 * LAZWrittenChunkSize points (in parallel) with `parameters`. Fills `summary`; returns an empty
 * string or one line (a coordinate out of range).
 */
std::string CompressLAZPart(const LASFileInfo& info,
  const LAZParameters& parameters,
  std::size_t count,
  const double* positions,
  const void* const* columns,
  LAZPart& part,
  LASPartSummary& summary);

} // namespace pcbilateral

#endif
