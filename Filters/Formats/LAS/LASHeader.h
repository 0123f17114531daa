// The public header block of a LAS file (ASPRS LAS 1.0 to 1.4), and everything a file holds
// besides its point records. Plain C++17, no VTK types. Every offset and count the file gives
// is checked against the file's size before anything is read.
#ifndef pcbilateral_LASHeader_h
#define pcbilateral_LASHeader_h

#include "LASDimension.h"
#include "LASRecord.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcbilateral
{

/// The public header block, decoded.
struct LASHeader
{
  std::uint16_t FileSourceId = 0;
  std::uint16_t GlobalEncoding = 0;
  std::uint8_t ProjectId[16] = {};
  std::uint8_t VersionMajor = 1;
  std::uint8_t VersionMinor = 2;
  std::string SystemIdentifier;
  std::string GeneratingSoftware;
  std::uint16_t CreationDay = 0;
  std::uint16_t CreationYear = 0;
  std::uint16_t HeaderSize = 227;
  std::uint32_t OffsetToPointData = 227;
  std::uint8_t PointFormat = 0;
  std::uint16_t RecordLength = 20;
  std::uint64_t NumberOfPoints = 0;
  std::uint64_t PointsByReturn[15] = {};
  double Scale[3] = { 0.001, 0.001, 0.001 };
  double Offset[3] = { 0, 0, 0 };
  /// min x, min y, min z, max x, max y, max z
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
};

/// Everything but the point records: what a writer needs to write a file like the one read.
struct LASFileInfo
{
  LASHeader Header;
  std::vector<LASRecord> VLRs;
  std::vector<LASRecord> EVLRs;
  /// The fields of the records, standard ones first, then those of the extra bytes.
  std::vector<LASDimension> Dimensions;
  /// A LAZ file's LASzip record (the VLR "laszip encoded" 22204), empty for a LAS file. It is
  /// not among the VLRs: a LAS file written from a LAZ one must not carry it.
  std::vector<std::uint8_t> LASzipRecord;
};

/**
 * Decodes and checks the header and the (E)VLRs of a LAS file held in memory, and that the
 * point records it announces are all there. Returns an empty string, or a one-line message
 * starting with `sourceName`: not a LAS file, compressed (LAZ) unless `acceptCompressed`, a
 * point format beyond 10, a truncated file, counts or offsets beyond the file... A compressed
 * file accepted has its LASzip record in `info.LASzipRecord`, its point format without
 * LASzip's mark, and its records are left to DecompressLAZPoints (LAZReader.h) to check.
 */
std::string ParseLASHeader(const std::uint8_t* data,
  std::size_t size,
  const std::string& sourceName,
  LASFileInfo& info,
  bool acceptCompressed = false);

} // namespace pcbilateral

#endif
