// PCL's point cloud format (PCD, version 0.7): the header, the ascii, binary and
// binary_compressed (LZF) encodings, reading into columns and writing them back.
// Plain C++17, no VTK types, no PCL.
#ifndef pcbilateral_PCDFile_h
#define pcbilateral_PCDFile_h

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{

/// How a PCD file stores its points (its DATA line).
enum class PCDEncoding
{
  ASCII,
  Binary,
  /// The fields one after another (all x, then all y, ...), compressed with LZF.
  BinaryCompressed
};

/// "ascii", "binary" or "binary_compressed".
const char* PCDEncodingName(PCDEncoding encoding);

/// One field of a point (FIELDS, SIZE, TYPE and COUNT of the header).
struct PCDField
{
  std::string Name;
  /// 'I' (signed integer), 'U' (unsigned integer) or 'F' (floating point).
  char Type = 'F';
  /// Bytes per value: 1, 2, 4 or 8 (4 or 8 for 'F').
  unsigned Size = 4;
  /// Values per point.
  unsigned Count = 1;

  std::size_t Bytes() const { return static_cast<std::size_t>(this->Size) * this->Count; }
  /// `_`: padding that holds no data (skipped when read, zeros when written).
  bool IsPadding() const { return this->Name == "_"; }
  bool IsCoordinate() const { return this->Name == "x" || this->Name == "y" || this->Name == "z"; }
};

/// The header of a PCD file.
struct PCDHeader
{
  /// Every field in file order, padding and x y z included.
  std::vector<PCDField> Fields;
  /// An organised frame has Height > 1 and Width * Height points; otherwise Height is 1.
  std::uint64_t Width = 0;
  std::uint64_t Height = 1;
  /// The acquisition viewpoint: translation tx ty tz, then the orientation as a quaternion
  /// qw qx qy qz.
  double Viewpoint[7] = { 0, 0, 0, 1, 0, 0, 0 };
  std::uint64_t NumberOfPoints = 0;
  PCDEncoding Encoding = PCDEncoding::Binary;
  /// Where the data starts: the byte after the DATA line.
  std::size_t DataOffset = 0;

  /// The bytes of one point: the sum of the fields' Bytes().
  std::size_t PointBytes() const;
};

/// One field's values: Count values of its type per point, point after point, in the
/// machine's (little-endian) byte order.
struct PCDColumn
{
  PCDField Field;
  std::vector<std::uint8_t> Bytes;
};

/// A PCD cloud as columns.
struct PCDCloud
{
  PCDHeader Header;
  std::size_t NumberOfPoints = 0;
  /// x y z interleaved, as doubles (exact for every field type but 64-bit integers beyond 2^53).
  std::vector<double> Positions;
  /// The fields other than x y z and padding, in file order.
  std::vector<PCDColumn> Columns;
  /// Points without coordinates (NaN) left out when reading (PCDReadOptions::KeepNaNPoints off).
  std::size_t NumberOfDroppedPoints = 0;
};

struct PCDReadOptions
{
  /// Keep points whose coordinates are not finite (an organised frame's pixels without depth),
  /// so that the cloud keeps its WIDTH x HEIGHT layout; off: they are left out and counted.
  bool KeepNaNPoints = false;
  /// Piece `Piece` of `NumberOfPieces` (a process's share of a distributed read): only the
  /// file's points [floor(Piece N / NumberOfPieces), floor((Piece + 1) N / NumberOfPieces))
  /// are kept (PointPieces.h), NaN points among them dropped as above. The whole file is still
  /// checked against its header (its size; for ascii, its number of lines, though only the
  /// share's values are parsed); binary data is read only at the share's records;
  /// binary_compressed data, a single LZF block, is decompressed whole and trimmed.
  int Piece = 0;
  int NumberOfPieces = 1;
};

/**
 * Parses the header at the start of `data`. Returns an empty string, or one line naming
 * `source` and the problem (not a PCD file, a keyword missing, SIZE, TYPE or COUNT not one per
 * field, an unknown type or size, POINTS other than WIDTH x HEIGHT, a field named twice, no x y
 * z fields, an unknown encoding).
 */
std::string ParsePCDHeader(const char* data,
  std::size_t size,
  const std::string& source,
  PCDHeader& header);

/**
 * Parses and decodes a whole PCD file held in memory. Errors are one line naming `source`: those
 * of ParsePCDHeader, and data shorter than the header announces, a line of ascii data with
 * another number of values or a value that is not of its field's type, compressed sizes that
 * do not match the header or the data, LZF data that does not decompress to its announced size.
 * Nothing is read outside [data, data + size).
 */
std::string DecodePCD(const char* data,
  std::size_t size,
  const std::string& source,
  const PCDReadOptions& options,
  PCDCloud& cloud);

/// Reads a file (see DecodePCD).
std::string ReadPCD(const std::string& path, const PCDReadOptions& options, PCDCloud& cloud);

/**
 * Writes a cloud in `encoding`. The fields are those of cloud.Header.Fields in their order:
 * x y z from the positions (converted to the field's type), padding as zeros, every other
 * field from the column of the same position among the non-coordinate, non-padding fields.
 * WIDTH and HEIGHT are the header's when they multiply to the number of points, else the number
 * of points and 1. ascii values are written with the shortest digits that read back to the same
 * value; packed colours (a 4-byte `rgb` field of type F) as the unsigned integer of their bits,
 * as PCL does, since a colour's bits can be a NaN. Written beside `path` and renamed when
 * complete. Returns an empty string or one line naming the path.
 */
std::string WritePCD(const std::string& path, const PCDCloud& cloud, PCDEncoding encoding);

/**
 * WritePCD in the binary or ascii encoding a range of points at a time: the same bytes as WritePCD
 * given every point at once. Open writes the header of `header`'s fields for `count` points (WIDTH
 * and HEIGHT as WritePCD sets them); each Append takes a cloud of those fields (its Positions and
 * Columns, as WritePCD reads them); Close checks that `count` points came and moves the file
 * onto the path (no file is left after a failure). Each returns an empty string or one line.
 */
class PCDBinaryStreamWriter
{
public:
  PCDBinaryStreamWriter();
  ~PCDBinaryStreamWriter();
  PCDBinaryStreamWriter(const PCDBinaryStreamWriter&) = delete;
  PCDBinaryStreamWriter& operator=(const PCDBinaryStreamWriter&) = delete;

  /// `encoding`: binary, or ascii (the same text as WritePCD's); binary_compressed is one block
  /// and is refused.
  std::string Open(const std::string& path,
    const PCDHeader& header,
    std::size_t count,
    PCDEncoding encoding = PCDEncoding::Binary);
  std::string Append(const PCDCloud& range);
  std::string Close();

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/**
 * The data block of a binary_compressed file (after its header): its two sizes checked against
 * the header's `count` points and the block's `size`, then decompressed into `fields` (every
 * field's values for every point, one field after another). An empty string or DecodePCD's
 * message (without the file's name).
 */
std::string DecompressPCDFields(const std::uint8_t* data,
  std::size_t size,
  const PCDHeader& header,
  std::size_t count,
  std::vector<std::uint8_t>& fields);

/**
 * WritePCD in binary_compressed from the fields already laid out one after another (`fields`:
 * `count` points, header.PointBytes() bytes each, as DecompressPCDFields gives them): the same
 * bytes as WritePCD given the same values as columns, without copying them.
 */
std::string WritePCDCompressedFields(const std::string& path,
  const PCDHeader& header,
  std::size_t count,
  const std::uint8_t* fields);

/// Whether a field holds packed colours: a 4-byte field named rgb or rgba.
bool IsPCDPackedColour(const PCDField& field);

/**
 * A packed colour column as 8-bit channels: R G B per point for `rgb`, R G B A for `rgba`
 * (PCL's 0xAARRGGBB in the 32 bits of the value, a float's bits for type F).
 */
std::vector<std::uint8_t> UnpackPCDColours(const PCDColumn& column);

/// The inverse of UnpackPCDColours: `channels` is 3 (the alpha byte written as 255, PCL's
/// opaque default) or 4 bytes per point.
PCDColumn PackPCDColours(const PCDField& field,
  const std::uint8_t* colours,
  int channels,
  std::size_t numberOfPoints);

} // namespace pcbilateral

#endif
