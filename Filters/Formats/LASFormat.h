// Reading and writing uncompressed LAS files (ASPRS LAS 1.0 to 1.4, point formats 0 to 10):
// the header, the variable-length records, and the point records decoded into columns.
// Plain C++17, no VTK types. Every offset and count the file gives is checked against the
// file's size before anything is read.
#ifndef pcbilateral_LASFormat_h
#define pcbilateral_LASFormat_h

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{

/// The value types of the point records' fields (and of the extra bytes).
enum class LASValueType : std::uint8_t
{
  UInt8,
  Int8,
  UInt16,
  Int16,
  UInt32,
  Int32,
  UInt64,
  Int64,
  Float32,
  Float64
};

/// Bytes of one value of a type.
std::size_t LASSizeOf(LASValueType type);

/// One field of the point records, decoded into a column of `Components` values per point.
struct LASDimension
{
  std::string Name;
  LASValueType Type = LASValueType::UInt8;
  int Components = 1;
  /// Where the field starts in a record.
  std::size_t ByteOffset = 0;
  /// For the fields packed in bits of one byte (return number, flags...): the first bit and
  /// how many; 0 for whole values.
  int BitShift = 0;
  int BitCount = 0;
  /// The type of the decoded column: Type, unless the field is scaled.
  LASValueType ColumnType = LASValueType::UInt8;
  /// Scaled fields hold what the stored integers mean: raw * Scale + Offset per component,
  /// as doubles (Float64) or, for the scan angle of formats 6-10 (0.006 degree units), floats.
  /// The writer stores round((value - Offset) / Scale), so the stored integers come back
  /// exactly. Extra bytes are scaled when their descriptor gives a scale or an offset, their
  /// type is an integer of 8 to 32 bits and every such integer maps back exactly.
  bool Scaled = false;
  double Scale[3] = { 1.0, 1.0, 1.0 };
  double Offset[3] = { 0.0, 0.0, 0.0 };
  /// Scaled extra bytes whose descriptor gives a no-data value (a stored integer): that value
  /// reads as NaN, and NaN is written as it.
  bool HasNoData = false;
  double NoData[3] = { 0.0, 0.0, 0.0 };
};

/// Bytes of one point's values in a dimension's decoded column.
std::size_t LASColumnBytes(const LASDimension& dimension);

/**
 * Whether raw * scale + offset, in doubles, gives every integer of 32 bits or fewer back
 * exactly through round((value - offset) / scale): true when the scale is a finite number
 * between 2^-900 and 2^900 in magnitude and the offset less than 2^48 steps.
 */
bool LASScalingIsExact(double scale, double offset);

/// A variable-length record (VLR), or an extended one (EVLR, LAS 1.4).
struct LASRecord
{
  bool Extended = false;
  std::uint16_t Reserved = 0;
  std::string UserId;
  std::uint16_t RecordId = 0;
  std::string Description;
  std::vector<std::uint8_t> Data;
};

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
};

/// The size of a record of a point format without extra bytes (0 for formats beyond 10).
std::size_t LASStandardRecordLength(int pointFormat);

/**
 * The fields of a point format: the standard ones, then the extra bytes of a longer record,
 * named by the extra-bytes VLR (record 4 of "LASF_Spec") when `vlrs` has one; bytes it does
 * not describe become one "ExtraBytes" field of as many unsigned bytes. Returns an empty
 * string, or what is wrong (a record too short for its format, descriptors beyond the record).
 */
std::string LASDimensionsFor(int pointFormat,
  std::size_t recordLength,
  const std::vector<LASRecord>& vlrs,
  std::vector<LASDimension>& dimensions);

/**
 * Decodes and checks the header and the (E)VLRs of a LAS file held in memory, and that the
 * point records it announces are all there. Returns an empty string, or a one-line message
 * starting with `sourceName`: not a LAS file, compressed (LAZ), a point format beyond 10, a
 * truncated file, counts or offsets beyond the file...
 */
std::string ParseLASHeader(const std::uint8_t* data,
  std::size_t size,
  const std::string& sourceName,
  LASFileInfo& info);

/**
 * Decodes `count` point records from `records` (the first byte of the point data):
 * coordinates as doubles into `positions` (x y z interleaved), and each of
 * `info.Dimensions` into `columns[d]` (Components values of the dimension's ColumnType per
 * point; a null column is skipped). Parallel (OpenMP); each thread first touches the part of
 * the outputs it writes, and the outputs are expected to be fresh memory (large ones are
 * advised to the kernel as huge pages).
 */
void DecodeLASPoints(const LASFileInfo& info,
  const std::uint8_t* records,
  std::size_t count,
  double* positions,
  void* const* columns);

/// (E)VLRs laid out as in a file (a header of 54 bytes, 60 when extended, then the data).
std::vector<std::uint8_t> EncodeLASRecords(const std::vector<LASRecord>& records, bool extended);

/// The reverse of EncodeLASRecords; false when the bytes do not hold whole records.
bool DecodeLASRecords(const std::uint8_t* bytes,
  std::size_t size,
  bool extended,
  std::vector<LASRecord>& records);

/// A file's bytes, memory-mapped where the system allows it, else read in one block.
class LASFileBytes
{
public:
  LASFileBytes() = default;
  ~LASFileBytes();
  LASFileBytes(const LASFileBytes&) = delete;
  LASFileBytes& operator=(const LASFileBytes&) = delete;
  /// Returns an empty string, or a one-line message naming the file.
  std::string Open(const std::string& path);
  const std::uint8_t* Data() const { return this->Bytes; }
  std::size_t Size() const { return this->Length; }

private:
  const std::uint8_t* Bytes = nullptr;
  std::size_t Length = 0;
  bool Mapped = false;
  std::unique_ptr<std::uint8_t[]> Buffer;
};

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
 * A header for points that come from no LAS file: LAS 1.2 (1.4 beyond 2^32 - 1 points), the
 * smallest point format holding GPS time and colour when asked for, offsets at the bounds'
 * lower corner and a power-of-ten scale fine enough to keep the points' precision within the
 * 32-bit records. `bounds` is min x, min y, min z, max x, max y, max z.
 */
LASFileInfo DefaultLASFileInfo(std::size_t count, const double bounds[6], bool gpsTime, bool rgb);

} // namespace pcbilateral

#endif
