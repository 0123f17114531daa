// The fields of LAS point records (the standard ones and the extra bytes) and the columns they
// are decoded into. Plain C++17, no VTK types.
#ifndef pcbilateral_LASDimension_h
#define pcbilateral_LASDimension_h

#include <cstddef>
#include <cstdint>
#include <string>

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

} // namespace pcbilateral

#endif
