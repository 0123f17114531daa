#include "LASPointFormat.h"

#include "LASBinary.h"
#include "LASExtraBytes.h"

namespace pcbilateral
{

namespace
{
using T = LASValueType;
/// In a format without the field.
constexpr int NA = -1;

/// A standard field of the records of one family of point formats: 0 to 5, or 6 to 10.
struct StandardField
{
  const char* Name;
  LASValueType Type;
  /// For the fields packed in bits of one byte: the first bit and how many.
  int BitShift;
  int BitCount;
  int Components;
  /// Scaled fields are stored in units of Scale and decoded into floats; 0 for the others.
  double Scale;
  /// Where the field starts in the records of each format of the family, or NA.
  int ByteOffset[6];
};

// The fields in the order of their columns: name, type, first bit and number of bits (of a bit
// field), components, scale (of a scaled field), and where the field starts in each format.
// clang-format off
const StandardField LegacyFields[] = {
  //                                                in format:    0   1   2   3   4   5
  { "Intensity",                   T::UInt16,  0, 0, 1, 0,     { 12, 12, 12, 12, 12, 12 } },
  { "ReturnNumber",                T::UInt8,   0, 3, 1, 0,     { 14, 14, 14, 14, 14, 14 } },
  { "NumberOfReturns",             T::UInt8,   3, 3, 1, 0,     { 14, 14, 14, 14, 14, 14 } },
  { "ScanDirectionFlag",           T::UInt8,   6, 1, 1, 0,     { 14, 14, 14, 14, 14, 14 } },
  { "EdgeOfFlightLine",            T::UInt8,   7, 1, 1, 0,     { 14, 14, 14, 14, 14, 14 } },
  { "Classification",              T::UInt8,   0, 5, 1, 0,     { 15, 15, 15, 15, 15, 15 } },
  { "Synthetic",                   T::UInt8,   5, 1, 1, 0,     { 15, 15, 15, 15, 15, 15 } },
  { "KeyPoint",                    T::UInt8,   6, 1, 1, 0,     { 15, 15, 15, 15, 15, 15 } },
  { "Withheld",                    T::UInt8,   7, 1, 1, 0,     { 15, 15, 15, 15, 15, 15 } },
  { "ScanAngleRank",               T::Int8,    0, 0, 1, 0,     { 16, 16, 16, 16, 16, 16 } },
  { "UserData",                    T::UInt8,   0, 0, 1, 0,     { 17, 17, 17, 17, 17, 17 } },
  { "PointSourceId",               T::UInt16,  0, 0, 1, 0,     { 18, 18, 18, 18, 18, 18 } },
  { "GpsTime",                     T::Float64, 0, 0, 1, 0,     { NA, 20, NA, 20, 20, 20 } },
  { "RGB",                         T::UInt16,  0, 0, 3, 0,     { NA, NA, 20, 28, NA, 28 } },
  { "WavePacketDescriptorIndex",   T::UInt8,   0, 0, 1, 0,     { NA, NA, NA, NA, 28, 34 } },
  { "WaveformDataOffset",          T::UInt64,  0, 0, 1, 0,     { NA, NA, NA, NA, 29, 35 } },
  { "WaveformPacketSize",          T::UInt32,  0, 0, 1, 0,     { NA, NA, NA, NA, 37, 43 } },
  { "ReturnPointWaveformLocation", T::Float32, 0, 0, 1, 0,     { NA, NA, NA, NA, 41, 47 } },
  { "WaveformXYZt",                T::Float32, 0, 0, 3, 0,     { NA, NA, NA, NA, 45, 51 } },
};

const StandardField ExtendedFields[] = {
  //                                                in format:    6   7   8   9  10
  { "Intensity",                   T::UInt16,  0, 0, 1, 0,     { 12, 12, 12, 12, 12 } },
  { "ReturnNumber",                T::UInt8,   0, 4, 1, 0,     { 14, 14, 14, 14, 14 } },
  { "NumberOfReturns",             T::UInt8,   4, 4, 1, 0,     { 14, 14, 14, 14, 14 } },
  { "Synthetic",                   T::UInt8,   0, 1, 1, 0,     { 15, 15, 15, 15, 15 } },
  { "KeyPoint",                    T::UInt8,   1, 1, 1, 0,     { 15, 15, 15, 15, 15 } },
  { "Withheld",                    T::UInt8,   2, 1, 1, 0,     { 15, 15, 15, 15, 15 } },
  { "Overlap",                     T::UInt8,   3, 1, 1, 0,     { 15, 15, 15, 15, 15 } },
  { "ScannerChannel",              T::UInt8,   4, 2, 1, 0,     { 15, 15, 15, 15, 15 } },
  { "ScanDirectionFlag",           T::UInt8,   6, 1, 1, 0,     { 15, 15, 15, 15, 15 } },
  { "EdgeOfFlightLine",            T::UInt8,   7, 1, 1, 0,     { 15, 15, 15, 15, 15 } },
  { "Classification",              T::UInt8,   0, 0, 1, 0,     { 16, 16, 16, 16, 16 } },
  { "UserData",                    T::UInt8,   0, 0, 1, 0,     { 17, 17, 17, 17, 17 } },
  // Stored in units of 0.006 degree; read in degrees, like ScanAngleRank of formats 0-5.
  // A float holds every stored value closely enough to give it back (within 0.002 unit).
  { "ScanAngle",                   T::Int16,   0, 0, 1, 0.006, { 18, 18, 18, 18, 18 } },
  { "PointSourceId",               T::UInt16,  0, 0, 1, 0,     { 20, 20, 20, 20, 20 } },
  { "GpsTime",                     T::Float64, 0, 0, 1, 0,     { 22, 22, 22, 22, 22 } },
  { "RGB",                         T::UInt16,  0, 0, 3, 0,     { NA, 30, 30, NA, 30 } },
  { "NIR",                         T::UInt16,  0, 0, 1, 0,     { NA, NA, 36, NA, 36 } },
  { "WavePacketDescriptorIndex",   T::UInt8,   0, 0, 1, 0,     { NA, NA, NA, 30, 38 } },
  { "WaveformDataOffset",          T::UInt64,  0, 0, 1, 0,     { NA, NA, NA, 31, 39 } },
  { "WaveformPacketSize",          T::UInt32,  0, 0, 1, 0,     { NA, NA, NA, 39, 47 } },
  { "ReturnPointWaveformLocation", T::Float32, 0, 0, 1, 0,     { NA, NA, NA, 43, 51 } },
  { "WaveformXYZt",                T::Float32, 0, 0, 3, 0,     { NA, NA, NA, 47, 55 } },
};
// clang-format on

template<std::size_t Rows>
void AddFields(const StandardField (&table)[Rows],
  int formatInFamily,
  std::vector<LASDimension>& dimensions)
{
  for (const StandardField& field : table)
  {
    const int offset = field.ByteOffset[formatInFamily];
    if (offset == NA)
    {
      continue;
    }
    LASDimension dimension;
    dimension.Name = field.Name;
    dimension.Type = field.Type;
    dimension.ColumnType = field.Scale != 0 ? T::Float32 : field.Type;
    dimension.ByteOffset = static_cast<std::size_t>(offset);
    dimension.BitShift = field.BitShift;
    dimension.BitCount = field.BitCount;
    dimension.Components = field.Components;
    dimension.Scaled = field.Scale != 0;
    dimension.Scale[0] = field.Scale != 0 ? field.Scale : 1.0;
    dimensions.push_back(dimension);
  }
}
} // namespace

std::size_t LASStandardRecordLength(int pointFormat)
{
  static const std::size_t lengths[] = { 20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67 };
  return pointFormat >= 0 && pointFormat <= 10 ? lengths[pointFormat] : 0;
}

std::string LASDimensionsFor(int pointFormat,
  std::size_t recordLength,
  const std::vector<LASRecord>& vlrs,
  std::vector<LASDimension>& dimensions)
{
  using las::Str;
  dimensions.clear();
  const std::size_t standard = LASStandardRecordLength(pointFormat);
  if (standard == 0)
  {
    return "point format " + std::to_string(pointFormat) +
           " is not supported (LAS defines point formats 0 to 10)";
  }
  if (recordLength < standard)
  {
    return "the point record length " + Str(recordLength) + " is shorter than point format " +
           std::to_string(pointFormat) + " needs (" + Str(standard) + " bytes)";
  }
  if (pointFormat <= 5)
  {
    AddFields(LegacyFields, pointFormat, dimensions);
  }
  else
  {
    AddFields(ExtendedFields, pointFormat - 6, dimensions);
  }
  return las::AddExtraBytesDimensions(standard, recordLength, vlrs, dimensions);
}

const std::vector<LASRecord>& LASExtraBytesRecords(const std::vector<LASRecord>& vlrs,
  const std::vector<LASRecord>& evlrs)
{
  return las::FindExtraBytesRecord(vlrs) || !las::FindExtraBytesRecord(evlrs) ? vlrs : evlrs;
}

} // namespace pcbilateral
