// Writing uncompressed LAS files (ASPRS LAS 1.0 to 1.4, point formats 0 to 10) from points in
// columns. Plain C++17, no VTK types.
#ifndef pcbilateral_LASWriter_h
#define pcbilateral_LASWriter_h

#include "LASHeader.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{

/**
 * Writes a LAS file with the version, point format, scales, offsets, record length and (E)VLRs
 * of `info`, and its dimensions filled from `columns` (as DecodeLASPoints lays them out; a null
 * column writes zeros). The bounds, point counts and counts by return are computed from the
 * points. Coordinates that do not fit the 32-bit records with the scale and offset are an
 * error. Writes to a temporary file beside `path` and renames it, so a failed write leaves no
 * file. Returns an empty string or a one-line message.
 */
std::string WriteLAS(const std::string& path,
  const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns);

/**
 * Writes a LAZ file (LASzip-compressed LAS, chunks of 50,000 points compressed in parallel) as
 * WriteLAS writes a LAS file, with the LASzip record added to the VLRs. Point formats 0 to 3
 * (pointwise items) and 6 to 8 (layered); the waveform formats are a one-line error. Returns an
 * empty string or a one-line message.
 */
std::string WriteLAZ(const std::string& path,
  const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns);

/**
 * A header for points that come from no LAS file: LAS 1.2 (1.4 beyond 2^32 - 1 points), the
 * smallest point format holding GPS time and colour when asked for, offsets at the bounds'
 * lower corner and a power-of-ten scale fine enough to keep the points' precision within the
 * 32-bit records. `bounds` is min x, min y, min z, max x, max y, max z.
 */
LASFileInfo DefaultLASFileInfo(std::size_t count, const double bounds[6], bool gpsTime, bool rgb);

class ReplacingFile;

/**
 * Writes an uncompressed LAS file a run of points at a time, for a cloud that is never in memory
 * whole (pcbilateral --memory-limit): the same bytes as WriteLAS given all the points at once.
 *
 *   LASStreamWriter writer;
 *   writer.Open(path, info, count);     // header and VLRs
 *   writer.Append(n, positions, columns) ... // count points in all, in file order
 *   writer.Close();                      // EVLRs, then the header with the bounds and counts
 *
 * Each call returns an empty string or a one-line message; after a message the file is not
 * written (the temporary file beside `path` is removed when the writer is destroyed).
 */
class LASStreamWriter
{
public:
  LASStreamWriter();
  ~LASStreamWriter();
  LASStreamWriter(const LASStreamWriter&) = delete;
  LASStreamWriter& operator=(const LASStreamWriter&) = delete;

  std::string Open(const std::string& path, const LASFileInfo& info, std::uint64_t count);
  /// The next `count` points, their columns laid out as DecodeLASPoints lays them out.
  std::string Append(std::size_t count, const double* positions, const void* const* columns);
  std::string Close();

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/**
 * Writes a LAZ file a run of points at a time, as LASStreamWriter writes a LAS file: the same
 * bytes as WriteLAZ given all the points at once. The chunks start at the multiples of
 * LAZWrittenChunkSize points whatever the runs appended (the records of a chunk not yet full
 * wait for the next run: at most a chunk's records are held between runs); each full chunk is
 * compressed and written as soon as it is, the chunk table and the header by Close.
 */
class LAZStreamWriter
{
public:
  LAZStreamWriter();
  ~LAZStreamWriter();
  LAZStreamWriter(const LAZStreamWriter&) = delete;
  LAZStreamWriter& operator=(const LAZStreamWriter&) = delete;

  std::string Open(const std::string& path, const LASFileInfo& info, std::uint64_t count);
  /// The next `count` points, their columns laid out as DecodeLASPoints lays them out.
  std::string Append(std::size_t count, const double* positions, const void* const* columns);
  std::string Close();

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace pcbilateral

#endif
