#include "LASFormat.h"

#include "HugePages.h"
#include "ReplacingFile.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>
#include <type_traits>

#ifdef _OPENMP
#include <omp.h>
#endif

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define PCB_LAS_MMAP 1
#endif
#ifdef __linux__
#include <linux/magic.h>
#include <sys/vfs.h>
#endif

namespace pcbilateral
{

namespace
{
constexpr std::size_t LegacyHeaderSize = 227;
constexpr std::size_t VLRHeaderSize = 54;
constexpr std::size_t EVLRHeaderSize = 60;
constexpr std::size_t ExtraBytesDescriptorSize = 192;

bool HostIsLittleEndian()
{
  const std::uint16_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// The file is little-endian, as is every host this is built on (checked at run time).
template<typename T>
T Load(const std::uint8_t* at)
{
  T value;
  std::memcpy(&value, at, sizeof(T));
  return value;
}

template<typename T>
void Store(std::uint8_t* at, T value)
{
  std::memcpy(at, &value, sizeof(T));
}

std::string FixedString(const std::uint8_t* at, std::size_t length)
{
  const auto* begin = reinterpret_cast<const char*>(at);
  return std::string(begin, strnlen(begin, length));
}

void StoreString(std::uint8_t* at, const std::string& text, std::size_t length)
{
  std::memset(at, 0, length);
  std::memcpy(at, text.data(), std::min(text.size(), length));
}

std::string Str(std::uint64_t value)
{
  return std::to_string(value);
}

void Add(std::vector<LASDimension>& dimensions,
  const char* name,
  LASValueType type,
  std::size_t offset,
  int shift = 0,
  int bits = 0,
  int components = 1)
{
  LASDimension dimension;
  dimension.Name = name;
  dimension.Type = type;
  dimension.ColumnType = type;
  dimension.ByteOffset = offset;
  dimension.BitShift = shift;
  dimension.BitCount = bits;
  dimension.Components = components;
  dimensions.push_back(dimension);
}

void AddWavePacket(std::vector<LASDimension>& dimensions, std::size_t at)
{
  Add(dimensions, "WavePacketDescriptorIndex", LASValueType::UInt8, at);
  Add(dimensions, "WaveformDataOffset", LASValueType::UInt64, at + 1);
  Add(dimensions, "WaveformPacketSize", LASValueType::UInt32, at + 9);
  Add(dimensions, "ReturnPointWaveformLocation", LASValueType::Float32, at + 13);
  Add(dimensions, "WaveformXYZt", LASValueType::Float32, at + 17, 0, 0, 3);
}

/// Dispatches on the stored integer type of a scaled field (8 to 32 bits).
template<typename Function>
void WithRawType(LASValueType type, Function function)
{
  switch (type)
  {
    case LASValueType::UInt8:
      return function(std::uint8_t());
    case LASValueType::Int8:
      return function(std::int8_t());
    case LASValueType::UInt16:
      return function(std::uint16_t());
    case LASValueType::Int16:
      return function(std::int16_t());
    case LASValueType::UInt32:
      return function(std::uint32_t());
    default:
      return function(std::int32_t());
  }
}

/// Calls function(Raw(), Value()) with the stored integer type and the decoded column's type
/// (float or double) of a scaled field.
template<typename Function>
void WithScaledTypes(const LASDimension& dimension, Function function)
{
  WithRawType(dimension.Type,
    [&](auto raw)
    {
      if (dimension.ColumnType == LASValueType::Float32)
      {
        function(raw, float());
      }
      else
      {
        function(raw, double());
      }
    });
}

/// The scale, offset and no-data value of an extra-bytes descriptor (`options` bits 0, 3 and
/// 4; the minimum and maximum, bits 1 and 2, describe the values and change nothing), applied
/// when the stored values are integers of 32 bits or fewer that the scaling gives back exactly.
/// Other types keep their stored values, and the descriptor stays in the record either way.
void ApplyExtraBytesScaling(const std::uint8_t* descriptor, int options, LASDimension& dimension)
{
  const bool integer = dimension.Type != LASValueType::Float32 &&
                       dimension.Type != LASValueType::Float64 && LASSizeOf(dimension.Type) <= 4;
  if (!integer || (options & (8 | 16)) == 0)
  {
    return;
  }
  double scale[3] = { 1.0, 1.0, 1.0 };
  double offset[3] = { 0.0, 0.0, 0.0 };
  double noData[3] = { 0.0, 0.0, 0.0 };
  bool hasNoData = (options & 1) != 0;
  for (int c = 0; c < dimension.Components; ++c)
  {
    // Each of these fields is 3 values of 8 bytes (one per component of the deprecated
    // arrays); a no-data value of an integer type is stored as a 64-bit integer.
    if (options & 8)
    {
      scale[c] = Load<double>(descriptor + 112 + 8 * c);
    }
    if (options & 16)
    {
      offset[c] = Load<double>(descriptor + 136 + 8 * c);
    }
    if (!LASScalingIsExact(scale[c], offset[c]))
    {
      return;
    }
    WithRawType(dimension.Type,
      [&](auto raw)
      {
        using Raw = decltype(raw);
        const std::uint8_t* stored = descriptor + 40 + 8 * c;
        noData[c] = std::is_signed_v<Raw> ? static_cast<double>(Load<std::int64_t>(stored))
                                          : static_cast<double>(Load<std::uint64_t>(stored));
        // A no-data value the type cannot hold marks nothing.
        hasNoData = hasNoData &&
                    noData[c] >= static_cast<double>(std::numeric_limits<Raw>::lowest()) &&
                    noData[c] <= static_cast<double>(std::numeric_limits<Raw>::max());
      });
  }
  dimension.Scaled = true;
  dimension.ColumnType = LASValueType::Float64;
  dimension.HasNoData = hasNoData;
  for (int c = 0; c < 3; ++c)
  {
    dimension.Scale[c] = scale[c];
    dimension.Offset[c] = offset[c];
    dimension.NoData[c] = noData[c];
  }
}

const LASRecord* FindExtraBytesRecord(const std::vector<LASRecord>& records)
{
  for (const LASRecord& record : records)
  {
    if (record.UserId == "LASF_Spec" && record.RecordId == 4)
    {
      return &record;
    }
  }
  return nullptr;
}

bool IsLAZRecord(const LASRecord& record)
{
  return record.UserId == "laszip encoded" && record.RecordId == 22204;
}

std::string CompressedMessage(const std::string& source)
{
  return source + ": is compressed (LAZ); decompress it first, e.g. with 'laszip -i " +
         std::filesystem::path(source).filename().string() +
         " -o out.las' or 'pdal translate in.laz out.las'";
}

/// Copies whole values of `bytes` bytes from records of `stride` bytes into a packed column.
template<std::size_t Bytes>
void Gather(const std::uint8_t* from, std::size_t stride, std::uint8_t* to, std::size_t count)
{
  std::size_t i = 0;
  if constexpr (Bytes == 1 || Bytes == 2)
  {
    // Values of one or two bytes are put together in a 64-bit word (little-endian host), so
    // one store writes 8 or 4 of them: the stores, not the loads, limit these loops.
    constexpr std::size_t PerWord = 8 / Bytes;
    for (; i + PerWord <= count; i += PerWord)
    {
      std::uint64_t word = 0;
      for (std::size_t k = 0; k < PerWord; ++k)
      {
        word |= static_cast<std::uint64_t>(
                  Load<std::conditional_t<Bytes == 1, std::uint8_t, std::uint16_t>>(
                    from + (i + k) * stride))
                << (8 * Bytes * k);
      }
      Store<std::uint64_t>(to + i * Bytes, word);
    }
  }
  for (; i < count; ++i)
  {
    std::memcpy(to + i * Bytes, from + i * stride, Bytes);
  }
}

template<std::size_t Bytes>
void Scatter(const std::uint8_t* from, std::uint8_t* to, std::size_t stride, std::size_t count)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    std::memcpy(to + i * stride, from + i * Bytes, Bytes);
  }
}

void GatherBytes(const std::uint8_t* from,
  std::size_t stride,
  std::uint8_t* to,
  std::size_t bytes,
  std::size_t count)
{
  switch (bytes)
  {
    case 1:
      return Gather<1>(from, stride, to, count);
    case 2:
      return Gather<2>(from, stride, to, count);
    case 4:
      return Gather<4>(from, stride, to, count);
    case 6:
      return Gather<6>(from, stride, to, count);
    case 8:
      return Gather<8>(from, stride, to, count);
    case 12:
      return Gather<12>(from, stride, to, count);
    default:
      for (std::size_t i = 0; i < count; ++i)
      {
        std::memcpy(to + i * bytes, from + i * stride, bytes);
      }
  }
}

#if defined(PCB_X86_CLONES) && defined(__linux__) && defined(__GNUC__) && !defined(__clang__)
// The same IEEE operations, vectorised where the machine has AVX2 or AVX-512 (floor needs
// SSE4.1's rounding instruction to vectorise): the same integers on every machine. The clones
// are picked at load time through the dynamic linker's indirect functions (Linux). GCC
// vectorises the loop only when it may ignore floating-point exception flags, which nothing
// here reads (the values are the same).
#define PCB_LAS_VECTOR_CLONES                                                                      \
  __attribute__((target_clones("avx512f", "avx2", "default"), optimize("no-trapping-math")))
#elif defined(PCB_X86_CLONES) && defined(__linux__) && defined(__clang__)
#define PCB_LAS_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PCB_LAS_VECTOR_CLONES
#endif

/// The coordinates of n points (interleaved x y z) as the records' integers, floor((value -
/// offset) / scale + 0.5), into stored (interleaved too); their extremes widen low and high.
/// Returns false when one does not fit 32 bits or is not finite (it is stored as 0). The
/// interleaved values are taken 24 at a time (8 points), with the scales and offsets repeated
/// to match, so that the loop vectorises without regrouping the coordinates by axis.
PCB_LAS_VECTOR_CLONES
bool QuantizeCoordinates(const double* __restrict xyz,
  std::size_t n,
  const double scale[3],
  const double offset[3],
  std::int32_t* __restrict stored,
  std::int32_t low[3],
  std::int32_t high[3])
{
  constexpr std::size_t Period = 24;
  double scales[Period], offsets[Period];
  std::int32_t lowest[Period], highest[Period];
  for (std::size_t k = 0; k < Period; ++k)
  {
    scales[k] = scale[k % 3];
    offsets[k] = offset[k % 3];
    lowest[k] = low[k % 3];
    highest[k] = high[k % 3];
  }
  std::int32_t outOfRange = 0;
  const std::size_t total = 3 * n;
  for (std::size_t start = 0; start < total; start += Period)
  {
    const std::size_t length = std::min(Period, total - start);
    for (std::size_t k = 0; k < length; ++k)
    {
      const double q = std::floor((xyz[start + k] - offsets[k]) / scales[k] + 0.5);
      // Also false for NaN; no branch, so that the loop vectorises.
      const std::int32_t fits = (q >= -2147483648.0) & (q <= 2147483647.0);
      outOfRange |= fits ^ 1;
      const std::int32_t value = static_cast<std::int32_t>(fits ? q : 0.0);
      stored[start + k] = value;
      lowest[k] = value < lowest[k] ? value : lowest[k];
      highest[k] = value > highest[k] ? value : highest[k];
    }
  }
  for (std::size_t k = 0; k < Period; ++k)
  {
    low[k % 3] = std::min(low[k % 3], lowest[k]);
    high[k % 3] = std::max(high[k % 3], highest[k]);
  }
  return outOfRange == 0;
}

void ScatterBytes(const std::uint8_t* from,
  std::uint8_t* to,
  std::size_t stride,
  std::size_t bytes,
  std::size_t count)
{
  switch (bytes)
  {
    case 1:
      return Scatter<1>(from, to, stride, count);
    case 2:
      return Scatter<2>(from, to, stride, count);
    case 4:
      return Scatter<4>(from, to, stride, count);
    case 6:
      return Scatter<6>(from, to, stride, count);
    case 8:
      return Scatter<8>(from, to, stride, count);
    case 12:
      return Scatter<12>(from, to, stride, count);
    default:
      for (std::size_t i = 0; i < count; ++i)
      {
        std::memcpy(to + i * stride, from + i * bytes, bytes);
      }
  }
}

constexpr std::size_t PointsPerBlock = 8192;
} // namespace

std::size_t LASSizeOf(LASValueType type)
{
  switch (type)
  {
    case LASValueType::UInt8:
    case LASValueType::Int8:
      return 1;
    case LASValueType::UInt16:
    case LASValueType::Int16:
      return 2;
    case LASValueType::UInt32:
    case LASValueType::Int32:
    case LASValueType::Float32:
      return 4;
    default:
      return 8;
  }
}

std::size_t LASColumnBytes(const LASDimension& dimension)
{
  return LASSizeOf(dimension.ColumnType) * static_cast<std::size_t>(dimension.Components);
}

bool LASScalingIsExact(double scale, double offset)
{
  // The rounding errors of both ways stay far below half a step: (4 |raw| + 3 |offset /
  // scale|) 2^-53 < 0.2 for |raw| < 2^32, and raw * scale is never subnormal nor infinite.
  const double magnitude = std::fabs(scale);
  return std::isfinite(scale) && std::isfinite(offset) && magnitude >= 0x1p-900 &&
         magnitude <= 0x1p900 && std::fabs(offset) <= 0x1p48 * magnitude;
}

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
  using T = LASValueType;
  Add(dimensions, "Intensity", T::UInt16, 12);
  if (pointFormat <= 5)
  {
    Add(dimensions, "ReturnNumber", T::UInt8, 14, 0, 3);
    Add(dimensions, "NumberOfReturns", T::UInt8, 14, 3, 3);
    Add(dimensions, "ScanDirectionFlag", T::UInt8, 14, 6, 1);
    Add(dimensions, "EdgeOfFlightLine", T::UInt8, 14, 7, 1);
    Add(dimensions, "Classification", T::UInt8, 15, 0, 5);
    Add(dimensions, "Synthetic", T::UInt8, 15, 5, 1);
    Add(dimensions, "KeyPoint", T::UInt8, 15, 6, 1);
    Add(dimensions, "Withheld", T::UInt8, 15, 7, 1);
    Add(dimensions, "ScanAngleRank", T::Int8, 16);
    Add(dimensions, "UserData", T::UInt8, 17);
    Add(dimensions, "PointSourceId", T::UInt16, 18);
    const bool gps = pointFormat == 1 || pointFormat >= 3;
    if (gps)
    {
      Add(dimensions, "GpsTime", T::Float64, 20);
    }
    if (pointFormat == 2 || pointFormat == 3 || pointFormat == 5)
    {
      Add(dimensions, "RGB", T::UInt16, gps ? 28 : 20, 0, 0, 3);
    }
    if (pointFormat == 4 || pointFormat == 5)
    {
      AddWavePacket(dimensions, pointFormat == 4 ? 28 : 34);
    }
  }
  else
  {
    Add(dimensions, "ReturnNumber", T::UInt8, 14, 0, 4);
    Add(dimensions, "NumberOfReturns", T::UInt8, 14, 4, 4);
    Add(dimensions, "Synthetic", T::UInt8, 15, 0, 1);
    Add(dimensions, "KeyPoint", T::UInt8, 15, 1, 1);
    Add(dimensions, "Withheld", T::UInt8, 15, 2, 1);
    Add(dimensions, "Overlap", T::UInt8, 15, 3, 1);
    Add(dimensions, "ScannerChannel", T::UInt8, 15, 4, 2);
    Add(dimensions, "ScanDirectionFlag", T::UInt8, 15, 6, 1);
    Add(dimensions, "EdgeOfFlightLine", T::UInt8, 15, 7, 1);
    Add(dimensions, "Classification", T::UInt8, 16);
    Add(dimensions, "UserData", T::UInt8, 17);
    // Stored in units of 0.006 degree; read in degrees, like ScanAngleRank of formats 0-5.
    // A float holds every stored value closely enough to give it back (within 0.002 unit).
    Add(dimensions, "ScanAngle", T::Int16, 18);
    dimensions.back().ColumnType = T::Float32;
    dimensions.back().Scaled = true;
    dimensions.back().Scale[0] = 0.006;
    Add(dimensions, "PointSourceId", T::UInt16, 20);
    Add(dimensions, "GpsTime", T::Float64, 22);
    if (pointFormat == 7 || pointFormat == 8 || pointFormat == 10)
    {
      Add(dimensions, "RGB", T::UInt16, 30, 0, 0, 3);
    }
    if (pointFormat == 8 || pointFormat == 10)
    {
      Add(dimensions, "NIR", T::UInt16, 36);
    }
    if (pointFormat == 9 || pointFormat == 10)
    {
      AddWavePacket(dimensions, pointFormat == 9 ? 30 : 38);
    }
  }

  // The extra bytes, named by their descriptors.
  std::size_t at = standard;
  // "Colors" is taken too: the readers add the display colours under that name, which would
  // replace an extra-bytes field of that name (and the writer would write them in its place).
  std::set<std::string> names = { "Colors" };
  for (const LASDimension& dimension : dimensions)
  {
    names.insert(dimension.Name);
  }
  const LASRecord* described = FindExtraBytesRecord(vlrs);
  const std::size_t descriptors = described ? described->Data.size() / ExtraBytesDescriptorSize : 0;
  for (std::size_t k = 0; k < descriptors; ++k)
  {
    const std::uint8_t* d = described->Data.data() + k * ExtraBytesDescriptorSize;
    const int dataType = d[2];
    const int options = d[3];
    LASDimension dimension;
    if (dataType == 0)
    {
      // Undocumented bytes: the options byte gives their number.
      dimension.Type = T::UInt8;
      dimension.Components = options;
    }
    else if (dataType <= 30)
    {
      dimension.Type = static_cast<T>((dataType - 1) % 10);
      dimension.ColumnType = dimension.Type;
      dimension.Components = 1 + (dataType - 1) / 10; // 11-30: deprecated arrays of 2 and 3
      ApplyExtraBytesScaling(d, options, dimension);
    }
    else
    {
      return "the extra-bytes record describes an unknown data type " + std::to_string(dataType);
    }
    const std::size_t bytes = LASSizeOf(dimension.Type) * dimension.Components;
    if (at + bytes > recordLength)
    {
      return "the extra-bytes record describes more bytes than the point records hold (" +
             Str(recordLength - standard) + ")";
    }
    if (bytes == 0)
    {
      continue;
    }
    std::string name = FixedString(d + 4, 32);
    if (name.empty())
    {
      name = "ExtraBytes" + Str(k + 1);
    }
    for (int suffix = 2; names.count(name) != 0; ++suffix)
    {
      name = FixedString(d + 4, 32) + "_" + std::to_string(suffix);
    }
    names.insert(name);
    dimension.Name = name;
    dimension.ByteOffset = at;
    at += bytes;
    dimensions.push_back(dimension);
  }
  if (at < recordLength)
  {
    // Bytes no descriptor names are kept as they are, so that they are written back.
    LASDimension rest;
    rest.Name = names.count("ExtraBytes") ? "ExtraBytesUndescribed" : "ExtraBytes";
    rest.Type = T::UInt8;
    rest.Components = static_cast<int>(recordLength - at);
    rest.ByteOffset = at;
    dimensions.push_back(rest);
  }
  return std::string();
}

std::string ParseLASHeader(const std::uint8_t* data,
  std::size_t size,
  const std::string& source,
  LASFileInfo& info)
{
  info = LASFileInfo();
  if (!HostIsLittleEndian())
  {
    return source + ": LAS files are read on little-endian machines only";
  }
  if (size < 4 || std::memcmp(data, "LASF", 4) != 0)
  {
    return source + ": not a LAS file (it does not start with the signature 'LASF')";
  }
  if (size < LegacyHeaderSize)
  {
    return source + ": truncated: " + Str(size) + " bytes, shorter than a LAS header (" +
           Str(LegacyHeaderSize) + " bytes)";
  }
  LASHeader& h = info.Header;
  h.FileSourceId = Load<std::uint16_t>(data + 4);
  h.GlobalEncoding = Load<std::uint16_t>(data + 6);
  std::memcpy(h.ProjectId, data + 8, 16);
  h.VersionMajor = data[24];
  h.VersionMinor = data[25];
  h.SystemIdentifier = FixedString(data + 26, 32);
  h.GeneratingSoftware = FixedString(data + 58, 32);
  h.CreationDay = Load<std::uint16_t>(data + 90);
  h.CreationYear = Load<std::uint16_t>(data + 92);
  h.HeaderSize = Load<std::uint16_t>(data + 94);
  h.OffsetToPointData = Load<std::uint32_t>(data + 96);
  const std::uint32_t vlrCount = Load<std::uint32_t>(data + 100);
  const std::uint8_t formatByte = data[104];
  h.RecordLength = Load<std::uint16_t>(data + 105);
  const std::string version = std::to_string(h.VersionMajor) + "." + std::to_string(h.VersionMinor);
  if (h.VersionMajor != 1 || h.VersionMinor > 4)
  {
    return source + ": unsupported LAS version " + version + " (versions 1.0 to 1.4 are read)";
  }
  // LASzip marks its files by setting the top bits of the point format.
  if (formatByte & 0xC0)
  {
    return CompressedMessage(source);
  }
  h.PointFormat = formatByte;
  if (h.PointFormat > 10)
  {
    return source + ": point format " + std::to_string(h.PointFormat) +
           " is not supported (LAS defines point formats 0 to 10)";
  }
  const std::size_t versionHeaderSize =
    h.VersionMinor >= 4 ? 375 : (h.VersionMinor == 3 ? 235 : LegacyHeaderSize);
  if (h.HeaderSize < versionHeaderSize)
  {
    return source + ": the header size " + Str(h.HeaderSize) + " is too small for LAS " + version +
           " (" + Str(versionHeaderSize) + " bytes)";
  }
  if (h.HeaderSize > size)
  {
    return source + ": truncated: the header announces " + Str(h.HeaderSize) +
           " bytes of header, the file has " + Str(size);
  }
  if (h.OffsetToPointData < h.HeaderSize || h.OffsetToPointData > size)
  {
    return source + ": the offset to the point data (" + Str(h.OffsetToPointData) +
           ") is outside the file (header " + Str(h.HeaderSize) + " bytes, file " + Str(size) +
           " bytes)";
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    h.Scale[axis] = Load<double>(data + 131 + 8 * axis);
    h.Offset[axis] = Load<double>(data + 155 + 8 * axis);
    h.Bounds[3 + axis] = Load<double>(data + 179 + 16 * axis);
    h.Bounds[axis] = Load<double>(data + 187 + 16 * axis);
    if (!std::isfinite(h.Scale[axis]) || h.Scale[axis] == 0.0 || !std::isfinite(h.Offset[axis]))
    {
      return source + ": the header's scale or offset of " + "xyz"[axis] +
             " is zero or not a finite number";
    }
  }

  // The VLRs, between the header and the point data.
  std::size_t at = h.HeaderSize;
  if (vlrCount > (h.OffsetToPointData - at) / VLRHeaderSize)
  {
    return source + ": the header announces " + Str(vlrCount) +
           " variable-length records, more than fit before the point data at byte " +
           Str(h.OffsetToPointData);
  }
  for (std::uint32_t k = 0; k < vlrCount; ++k)
  {
    const std::size_t length =
      at + VLRHeaderSize <= h.OffsetToPointData ? Load<std::uint16_t>(data + at + 20) : 0;
    if (at + VLRHeaderSize + length > h.OffsetToPointData)
    {
      return source + ": the header announces " + Str(vlrCount) + " variable-length records but " +
             "record " + Str(k + 1) + " runs past the start of the point data at byte " +
             Str(h.OffsetToPointData);
    }
    LASRecord record;
    record.Reserved = Load<std::uint16_t>(data + at);
    record.UserId = FixedString(data + at + 2, 16);
    record.RecordId = Load<std::uint16_t>(data + at + 18);
    record.Description = FixedString(data + at + 22, 32);
    record.Data.assign(data + at + VLRHeaderSize, data + at + VLRHeaderSize + length);
    if (IsLAZRecord(record))
    {
      return CompressedMessage(source);
    }
    info.VLRs.push_back(std::move(record));
    at += VLRHeaderSize + length;
  }

  // The number of points: LAS 1.4 has a 64-bit count, and its 32-bit one may be 0.
  const std::uint64_t legacyCount = Load<std::uint32_t>(data + 107);
  h.NumberOfPoints = legacyCount;
  for (int r = 0; r < 5; ++r)
  {
    h.PointsByReturn[r] = Load<std::uint32_t>(data + 111 + 4 * r);
  }
  if (h.VersionMinor >= 4)
  {
    const std::uint64_t count = Load<std::uint64_t>(data + 247);
    if (count != 0 || h.PointFormat > 5)
    {
      h.NumberOfPoints = count;
      for (int r = 0; r < 15; ++r)
      {
        h.PointsByReturn[r] = Load<std::uint64_t>(data + 255 + 8 * r);
      }
    }
  }
  std::string problem = LASDimensionsFor(h.PointFormat, h.RecordLength, info.VLRs, info.Dimensions);
  if (!problem.empty())
  {
    return source + ": " + problem;
  }
  const std::size_t pointBytes = size - h.OffsetToPointData;
  const std::size_t available = pointBytes / h.RecordLength;
  if (h.NumberOfPoints > available)
  {
    return source + ": truncated: the header announces " + Str(h.NumberOfPoints) +
           " points, the file holds " + Str(available) + " (" + Str(pointBytes) +
           " bytes of point records of " + Str(h.RecordLength) + " bytes)";
  }

  // The extended VLRs (LAS 1.4), after the point data.
  if (h.VersionMinor >= 4)
  {
    const std::uint64_t start = Load<std::uint64_t>(data + 235);
    const std::uint32_t count = Load<std::uint32_t>(data + 243);
    const std::uint64_t pointsEnd = h.OffsetToPointData + h.NumberOfPoints * h.RecordLength;
    if (count > 0 && (start < pointsEnd || start > size || count > (size - start) / EVLRHeaderSize))
    {
      return source + ": the header announces " + Str(count) +
             " extended variable-length records at byte " + Str(start) + ", outside the file's " +
             Str(size) + " bytes after its points";
    }
    std::uint64_t e = start;
    for (std::uint32_t k = 0; k < count; ++k)
    {
      const std::uint64_t length =
        e + EVLRHeaderSize <= size ? Load<std::uint64_t>(data + e + 20) : size;
      if (e + EVLRHeaderSize > size || length > size - e - EVLRHeaderSize)
      {
        return source + ": truncated: extended variable-length record " + Str(k + 1) +
               " runs past the end of the file";
      }
      LASRecord record;
      record.Extended = true;
      record.Reserved = Load<std::uint16_t>(data + e);
      record.UserId = FixedString(data + e + 2, 16);
      record.RecordId = Load<std::uint16_t>(data + e + 18);
      record.Description = FixedString(data + e + 28, 32);
      record.Data.assign(data + e + EVLRHeaderSize, data + e + EVLRHeaderSize + length);
      info.EVLRs.push_back(std::move(record));
      e += EVLRHeaderSize + length;
    }
    // An extra-bytes description may sit in an EVLR.
    if (!FindExtraBytesRecord(info.VLRs) && FindExtraBytesRecord(info.EVLRs))
    {
      problem = LASDimensionsFor(h.PointFormat, h.RecordLength, info.EVLRs, info.Dimensions);
      if (!problem.empty())
      {
        return source + ": " + problem;
      }
    }
  }
  return std::string();
}

namespace
{
/// The decoded value of a stored integer of a scaled field (NaN for its no-data value).
template<typename Raw>
double ScaledValue(Raw raw, const LASDimension& dimension, int component)
{
  if (dimension.HasNoData && static_cast<double>(raw) == dimension.NoData[component])
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return static_cast<double>(raw) * dimension.Scale[component] + dimension.Offset[component];
}

/// A scaled field's stored integers (Raw) decoded into its column (Value).
template<typename Raw, typename Value>
void DecodeScaled(const std::uint8_t* from,
  std::size_t stride,
  const LASDimension& dimension,
  std::uint8_t* to,
  std::size_t count)
{
  const int components = dimension.Components;
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      const Value value = static_cast<Value>(
        ScaledValue(Load<Raw>(from + i * stride + c * sizeof(Raw)), dimension, c));
      Store<Value>(to + (i * components + c) * sizeof(Value), value);
    }
  }
}

/// The stored integer of a value of a scaled field: rounded to the nearest step, NaN as the
/// no-data value (else 0), clamped to the type's range.
template<typename Raw>
Raw ScaledRaw(double value, const LASDimension& dimension, int component)
{
  if (std::isnan(value))
  {
    return static_cast<Raw>(dimension.HasNoData ? dimension.NoData[component] : 0.0);
  }
  const double raw = std::round((value - dimension.Offset[component]) / dimension.Scale[component]);
  return static_cast<Raw>(
    std::min<double>(std::max<double>(raw, static_cast<double>(std::numeric_limits<Raw>::lowest())),
      static_cast<double>(std::numeric_limits<Raw>::max())));
}

/// A scaled field's column (Value) encoded into its stored integers (Raw).
template<typename Raw, typename Value>
void EncodeScaled(const std::uint8_t* from,
  const LASDimension& dimension,
  std::uint8_t* to,
  std::size_t stride,
  std::size_t count)
{
  const int components = dimension.Components;
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      const double value = Load<Value>(from + (i * components + c) * sizeof(Value));
      Store<Raw>(to + i * stride + c * sizeof(Raw), ScaledRaw<Raw>(value, dimension, c));
    }
  }
}

/// Points decoded at once by a thread: their records stay in its cache for all the passes.
constexpr std::size_t PointsPerDecodedBlock = 4096;

/// A byte's value in each byte of a 64-bit word: eight points' bit fields are decoded and
/// encoded together, the eight bytes of a word (the host is little-endian, as checked when the
/// header is parsed; a field's mask keeps its bits within its byte).
constexpr std::uint64_t EveryByte = 0x0101010101010101ull;

/// A field packed in bits of a byte of the record.
struct BitField
{
  std::size_t Dimension;
  unsigned Mask;
  unsigned Shift;
};

/// The bit fields of one byte of the record, decoded or encoded together: one pass over the
/// records reads or writes that byte once for all of them.
struct BitFieldByte
{
  std::size_t ByteOffset = 0;
  std::vector<BitField> Fields;
};

/// The bit fields of the dimensions that have a column, by byte.
std::vector<BitFieldByte> GroupBitFields(const LASFileInfo& info, const void* const* columns)
{
  std::vector<BitFieldByte> bytes;
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const LASDimension& dimension = info.Dimensions[d];
    if (!columns[d] || dimension.BitCount == 0)
    {
      continue;
    }
    auto byte = std::find_if(bytes.begin(),
      bytes.end(),
      [&](const BitFieldByte& b) { return b.ByteOffset == dimension.ByteOffset; });
    if (byte == bytes.end())
    {
      bytes.push_back(BitFieldByte{ dimension.ByteOffset, {} });
      byte = bytes.end() - 1;
    }
    byte->Fields.push_back(
      BitField{ d, (1u << dimension.BitCount) - 1u, static_cast<unsigned>(dimension.BitShift) });
  }
  return bytes;
}

/// Decodes blocks of point records into the columns, one pass per field, except the fields
/// packed in bits of one byte: one pass reads the byte once and writes each of its fields.
class BlockDecoder
{
public:
  BlockDecoder(const LASFileInfo& info, double* positions, void* const* columns)
    : Info(info)
    , Positions(positions)
    , Columns(columns)
    , BitFields(GroupBitFields(info, columns))
  {
  }

  /// Decodes the `count` records at `block`, the points from `first` on.
  void Decode(const std::uint8_t* block, std::size_t first, std::size_t count) const
  {
    const std::size_t stride = this->Info.Header.RecordLength;
    const double* scale = this->Info.Header.Scale;
    const double* offset = this->Info.Header.Offset;
    double* p = this->Positions + 3 * first;
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::uint8_t* record = block + i * stride;
      for (int axis = 0; axis < 3; ++axis)
      {
        p[3 * i + axis] = Load<std::int32_t>(record + 4 * axis) * scale[axis] + offset[axis];
      }
    }
    for (std::size_t d = 0; d < this->Info.Dimensions.size(); ++d)
    {
      const LASDimension& dimension = this->Info.Dimensions[d];
      if (!this->Columns[d] || dimension.BitCount > 0)
      {
        continue;
      }
      const std::uint8_t* from = block + dimension.ByteOffset;
      std::uint8_t* to = this->Column(d, first);
      if (dimension.Scaled)
      {
        WithScaledTypes(dimension,
          [&](auto raw, auto value)
          { DecodeScaled<decltype(raw), decltype(value)>(from, stride, dimension, to, count); });
      }
      else
      {
        GatherBytes(from, stride, to, LASColumnBytes(dimension), count);
      }
    }
    for (const BitFieldByte& byte : this->BitFields)
    {
      this->DecodeBitFields(block + byte.ByteOffset, stride, byte, first, count);
    }
  }

private:
  std::uint8_t* Column(std::size_t d, std::size_t first) const
  {
    return static_cast<std::uint8_t*>(this->Columns[d]) +
           first * LASColumnBytes(this->Info.Dimensions[d]);
  }

  void DecodeBitFields(const std::uint8_t* from,
    std::size_t stride,
    const BitFieldByte& byte,
    std::size_t first,
    std::size_t count) const
  {
    constexpr std::size_t MostFields = 8;
    std::uint8_t* to[MostFields];
    unsigned shift[MostFields];
    unsigned mask[MostFields];
    const std::size_t fields = std::min(byte.Fields.size(), MostFields); // bits of one byte
    for (std::size_t f = 0; f < fields; ++f)
    {
      to[f] = this->Column(byte.Fields[f].Dimension, first);
      shift[f] = byte.Fields[f].Shift;
      mask[f] = byte.Fields[f].Mask;
    }
    // Eight points at a time, as the eight bytes of a 64-bit word (the host is little-endian,
    // as checked when the header was parsed): shifting the word moves each point's bits within
    // its byte, as long as a field does not go beyond its byte, which the mask makes sure of.
    // One store writes a field of eight points.
    std::size_t i = 0;
    for (; i + 8 <= count; i += 8)
    {
      std::uint64_t bytes = 0;
      for (unsigned k = 0; k < 8; ++k)
      {
        bytes |= static_cast<std::uint64_t>(from[(i + k) * stride]) << (8 * k);
      }
      for (std::size_t f = 0; f < fields; ++f)
      {
        Store<std::uint64_t>(to[f] + i, (bytes >> shift[f]) & (mask[f] * EveryByte));
      }
    }
    for (; i < count; ++i)
    {
      const unsigned value = from[i * stride];
      for (std::size_t f = 0; f < fields; ++f)
      {
        to[f][i] = static_cast<std::uint8_t>((value >> shift[f]) & mask[f]);
      }
    }
  }

  const LASFileInfo& Info;
  double* Positions;
  void* const* Columns;
  std::vector<BitFieldByte> BitFields;
};
} // namespace

void DecodeLASPoints(const LASFileInfo& info,
  const std::uint8_t* records,
  std::size_t count,
  double* positions,
  void* const* columns)
{
  // Fresh memory as huge pages: a page fault per 4 KB of the columns (1.5 times the file's
  // size) would cost more than the decoding.
  AdviseHugePages(positions, 3 * sizeof(double) * count);
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    if (columns[d])
    {
      AdviseHugePages(columns[d], LASColumnBytes(info.Dimensions[d]) * count);
    }
  }
  const std::size_t stride = info.Header.RecordLength;
  const auto blocks =
    static_cast<std::int64_t>((count + PointsPerDecodedBlock - 1) / PointsPerDecodedBlock);
  // Each thread decodes one contiguous range of blocks, so it is the first to touch (and
  // place) the memory it writes.
  const BlockDecoder decoder(info, positions, columns);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    const std::size_t first = static_cast<std::size_t>(b) * PointsPerDecodedBlock;
    decoder.Decode(records + first * stride, first, std::min(PointsPerDecodedBlock, count - first));
  }
}

LASFileBytes::~LASFileBytes()
{
#ifdef PCB_LAS_MMAP
  if (this->Mapped)
  {
    munmap(const_cast<std::uint8_t*>(this->Bytes), this->Length);
  }
#endif
}

std::string LASFileBytes::Open(const std::string& path)
{
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
  {
    return path + ": " + std::strerror(ENOENT);
  }
  if (std::filesystem::is_directory(status))
  {
    return path + ": is a directory, not a point file";
  }
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error)
  {
    return path + ": " + error.message();
  }
  this->Length = static_cast<std::size_t>(size);
  static const std::uint8_t empty = 0;
  this->Bytes = &empty;
  if (this->Length == 0)
  {
    return std::string();
  }
#ifdef PCB_LAS_MMAP
  // Mapped: no copy. The pages are mapped all at once where the system can (Linux's
  // MAP_POPULATE): a fault per 4 KB page as the decoding touches them made reading take twice
  // as long as a plain read of the bytes (pcb_benchmark --las); with it, about as long.
#ifdef MAP_POPULATE
  constexpr int PopulateFlag = MAP_POPULATE;
#else
  constexpr int PopulateFlag = 0;
#endif
  const int descriptor = ::open(path.c_str(), O_RDONLY);
  if (descriptor >= 0)
  {
    void* mapped =
      mmap(nullptr, this->Length, PROT_READ, MAP_PRIVATE | PopulateFlag, descriptor, 0);
    ::close(descriptor);
    if (mapped != MAP_FAILED)
    {
      madvise(mapped, this->Length, MADV_WILLNEED);
      this->Bytes = static_cast<const std::uint8_t*>(mapped);
      this->Mapped = true;
      return std::string();
    }
  }
#endif
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
  {
    return path + ": cannot be opened for reading (" + std::strerror(errno) + ")";
  }
  this->Buffer.reset(new std::uint8_t[this->Length]);
  const std::size_t read = std::fread(this->Buffer.get(), 1, this->Length, file);
  std::fclose(file);
  if (read != this->Length)
  {
    return path + ": read error";
  }
  this->Bytes = this->Buffer.get();
  return std::string();
}

namespace
{
/// The header block of a LAS file to write, with its counts, bounds and offsets filled in.
std::vector<std::uint8_t> EncodeHeader(const LASFileInfo& info,
  std::size_t headerSize,
  std::size_t offsetToPoints,
  std::uint32_t vlrs,
  std::uint32_t evlrs,
  std::uint64_t count,
  const std::uint64_t byReturn[15],
  const double bounds[6])
{
  const LASHeader& h = info.Header;
  std::vector<std::uint8_t> out(headerSize, 0);
  std::uint8_t* d = out.data();
  std::memcpy(d, "LASF", 4);
  Store<std::uint16_t>(d + 4, h.FileSourceId);
  // Bit 1 says waveform data is inside the file: it is not kept, so it is not written.
  Store<std::uint16_t>(d + 6, static_cast<std::uint16_t>(h.GlobalEncoding & ~2u));
  std::memcpy(d + 8, h.ProjectId, 16);
  d[24] = h.VersionMajor;
  d[25] = h.VersionMinor;
  StoreString(d + 26, h.SystemIdentifier, 32);
  StoreString(d + 58, h.GeneratingSoftware, 32);
  Store<std::uint16_t>(d + 90, h.CreationDay);
  Store<std::uint16_t>(d + 92, h.CreationYear);
  Store<std::uint16_t>(d + 94, static_cast<std::uint16_t>(headerSize));
  Store<std::uint32_t>(d + 96, static_cast<std::uint32_t>(offsetToPoints));
  Store<std::uint32_t>(d + 100, vlrs);
  d[104] = h.PointFormat;
  Store<std::uint16_t>(d + 105, h.RecordLength);
  const bool legacy = h.PointFormat <= 5 && count <= std::numeric_limits<std::uint32_t>::max();
  Store<std::uint32_t>(d + 107, legacy ? static_cast<std::uint32_t>(count) : 0u);
  for (int r = 0; r < 5; ++r)
  {
    Store<std::uint32_t>(d + 111 + 4 * r,
      legacy ? static_cast<std::uint32_t>(std::min<std::uint64_t>(byReturn[r], 0xFFFFFFFFu)) : 0u);
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    Store<double>(d + 131 + 8 * axis, h.Scale[axis]);
    Store<double>(d + 155 + 8 * axis, h.Offset[axis]);
    Store<double>(d + 179 + 16 * axis, bounds[3 + axis]);
    Store<double>(d + 187 + 16 * axis, bounds[axis]);
  }
  if (h.VersionMinor >= 4)
  {
    const std::uint64_t evlrStart =
      evlrs ? offsetToPoints + count * static_cast<std::uint64_t>(h.RecordLength) : 0;
    Store<std::uint64_t>(d + 235, evlrStart);
    Store<std::uint32_t>(d + 243, evlrs);
    Store<std::uint64_t>(d + 247, count);
    for (int r = 0; r < 15; ++r)
    {
      Store<std::uint64_t>(d + 255 + 8 * r, byReturn[r]);
    }
  }
  return out;
}

void AppendRecord(std::vector<std::uint8_t>& out, const LASRecord& record, bool extended)
{
  const std::size_t headerSize = extended ? EVLRHeaderSize : VLRHeaderSize;
  const std::size_t at = out.size();
  out.resize(at + headerSize + record.Data.size(), 0);
  std::uint8_t* d = out.data() + at;
  Store<std::uint16_t>(d, record.Reserved);
  StoreString(d + 2, record.UserId, 16);
  Store<std::uint16_t>(d + 18, record.RecordId);
  if (extended)
  {
    Store<std::uint64_t>(d + 20, record.Data.size());
    StoreString(d + 28, record.Description, 32);
  }
  else
  {
    Store<std::uint16_t>(d + 20, static_cast<std::uint16_t>(record.Data.size()));
    StoreString(d + 22, record.Description, 32);
  }
  std::copy(record.Data.begin(), record.Data.end(), d + headerSize);
}

/// What a block of encoded points adds to the header: the bounds of its stored coordinates, its
/// points by return number, and whether a coordinate did not fit the 32-bit records.
struct BlockSummary
{
  double Bounds[6];
  std::uint64_t ByReturn[15];
  bool OutOfRange;
};

/// Encodes points into LAS records a block (PointsPerBlock points) at a time, for both ways of
/// writing them: straight into a memory mapping of the file, or into chunks written with fwrite.
class BlockEncoder
{
public:
  BlockEncoder(const LASFileInfo& info,
    std::size_t count,
    const double* positions,
    const void* const* columns)
    : Info(info)
    , Count(count)
    , Positions(positions)
    , Columns(columns)
    , BitFields(GroupBitFields(info, columns))
  {
    for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
    {
      if (info.Dimensions[d].Name == "ReturnNumber" && columns[d])
      {
        this->ReturnDimension = static_cast<int>(d);
      }
    }
  }

  std::size_t Blocks() const { return (this->Count + PointsPerBlock - 1) / PointsPerBlock; }

  /// The bytes of the records of the blocks from `block` on, `blocks` of them at most.
  std::size_t Bytes(std::size_t block, std::size_t blocks) const
  {
    const std::size_t first = block * PointsPerBlock;
    return (std::min(this->Count, first + blocks * PointsPerBlock) - first) *
           this->Info.Header.RecordLength;
  }

  /// Encodes block `b` into `records`, whose bytes must be zero before: the bytes and bits of
  /// fields without a column (and the bytes no dimension names) are not written. Every other
  /// byte is stored whole, never read back.
  BlockSummary Encode(std::size_t b, std::uint8_t* records) const
  {
    const LASHeader& h = this->Info.Header;
    const std::size_t stride = h.RecordLength;
    const std::size_t first = b * PointsPerBlock;
    const std::size_t n = std::min(PointsPerBlock, this->Count - first);
    constexpr double Infinity = std::numeric_limits<double>::infinity();
    BlockSummary summary{
      { Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity }, {}, false
    };
    // The stored integers of the coordinates and their extremes, from which the bounds are
    // computed once.
    std::int32_t low[3] = { INT32_MAX, INT32_MAX, INT32_MAX };
    std::int32_t high[3] = { INT32_MIN, INT32_MIN, INT32_MIN };
    std::int32_t stored[3 * PointsPerBlock];
    summary.OutOfRange =
      !QuantizeCoordinates(this->Positions + 3 * first, n, h.Scale, h.Offset, stored, low, high);
    Scatter<12>(reinterpret_cast<const std::uint8_t*>(stored), records, stride, n);
    for (int axis = 0; axis < 3 && n > 0; ++axis)
    {
      const double a = low[axis] * h.Scale[axis] + h.Offset[axis];
      const double z = high[axis] * h.Scale[axis] + h.Offset[axis];
      summary.Bounds[axis] = std::min(a, z); // a negative scale swaps them
      summary.Bounds[3 + axis] = std::max(a, z);
    }
    for (std::size_t d = 0; d < this->Info.Dimensions.size(); ++d)
    {
      const LASDimension& dimension = this->Info.Dimensions[d];
      if (!this->Columns[d])
      {
        continue;
      }
      const std::size_t bytes = LASColumnBytes(dimension);
      const auto* from = this->Column(d) + first * bytes;
      std::uint8_t* to = records + dimension.ByteOffset;
      if (dimension.Scaled)
      {
        WithScaledTypes(dimension,
          [&](auto raw, auto value)
          { EncodeScaled<decltype(raw), decltype(value)>(from, dimension, to, stride, n); });
      }
      else if (dimension.BitCount == 0)
      {
        ScatterBytes(from, to, stride, bytes, n);
      }
    }
    // Eight points at a time: eight bytes of each field's column in one 64-bit word, masked
    // and shifted in place (a field's bits stay within its byte), then one byte per record.
    for (const BitFieldByte& packed : this->BitFields)
    {
      std::uint8_t* to = records + packed.ByteOffset;
      std::size_t i = 0;
      for (; i + 8 <= n; i += 8)
      {
        std::uint64_t values = 0;
        for (const BitField& field : packed.Fields)
        {
          values |= (Load<std::uint64_t>(this->Column(field.Dimension) + first + i) &
                      (field.Mask * EveryByte))
                    << field.Shift;
        }
        for (std::size_t k = 0; k < 8; ++k)
        {
          to[(i + k) * stride] = static_cast<std::uint8_t>(values >> (8 * k));
        }
      }
      for (; i < n; ++i)
      {
        unsigned value = 0;
        for (const BitField& field : packed.Fields)
        {
          value |= (this->Column(field.Dimension)[first + i] & field.Mask) << field.Shift;
        }
        to[i * stride] = static_cast<std::uint8_t>(value);
      }
    }
    if (this->ReturnDimension >= 0)
    {
      const std::uint8_t* returns = this->Column(this->ReturnDimension) + first;
      const int limit = h.PointFormat > 5 ? 15 : 5;
      for (std::size_t i = 0; i < n; ++i)
      {
        if (returns[i] >= 1 && returns[i] <= limit)
        {
          ++summary.ByReturn[returns[i] - 1];
        }
      }
    }
    return summary;
  }

private:
  const std::uint8_t* Column(std::size_t d) const
  {
    return static_cast<const std::uint8_t*>(this->Columns[d]);
  }

  const LASFileInfo& Info;
  std::size_t Count;
  const double* Positions;
  const void* const* Columns;
  std::vector<BitFieldByte> BitFields;
  int ReturnDimension = -1;
};

/// Writes the records in chunks of a few blocks with fwrite, by one thread started for the
/// whole file, while the next chunks are encoded (three chunks in turn). Stops at the first
/// chunk with a point out of range (its summary says so; the chunk is not written). Returns
/// whether every write succeeded (if not, errno says why).
bool WritePointsInChunks(std::FILE* file,
  const BlockEncoder& encoder,
  std::vector<BlockSummary>& summaries)
{
  // 128k points, about 4.5 MB, per write: the chunk stays in the (last-level) cache between
  // its encoding and its writing, and the first write starts early (with 1M points, 34 MB of
  // fresh memory per chunk, page faults cost more than the encoding). 10M points of format 3
  // into /dev/shm, 2 cores: with a thread started for each write (std::async), 1 MB chunks took
  // 0.13-0.18 s, these 0.11-0.14 s (9 or 18 MB: no faster); with the one writing thread below,
  // 1 MB chunks 0.11-0.18 s, these 0.11-0.19 s, medians 0.176 and 0.139 in the same rounds.
  constexpr std::size_t BlocksAtOnce = 16;
  const std::size_t blockCount = encoder.Blocks();
  // A few chunks: one is written (by a thread of its own) while the next ones are encoded. Not
  // zero-filled: every block is cleared before it is encoded.
  constexpr std::size_t Slots = 3;
  const std::size_t chunkCount = (blockCount + BlocksAtOnce - 1) / BlocksAtOnce;
  // Allocated before the writing thread starts, so that nothing throws while it runs.
  std::unique_ptr<std::uint8_t[]> chunks[Slots];
  for (std::size_t c = 0; c < std::min(Slots, chunkCount); ++c)
  {
    chunks[c].reset(new std::uint8_t[encoder.Bytes(0, BlocksAtOnce)]);
  }
  // The chunks encoded and written so far, the errno of a failed write (errno itself is the
  // writing thread's), and whether the encoding stopped.
  std::mutex mutex;
  std::condition_variable changed;
  std::size_t encoded = 0;
  std::size_t written = 0;
  int failure = 0;
  bool stopped = false;
  std::thread writer(
    [&]()
    {
      for (std::size_t c = 0; c < chunkCount; ++c)
      {
        {
          std::unique_lock<std::mutex> lock(mutex);
          changed.wait(lock, [&]() { return encoded > c || stopped; });
          if (encoded <= c)
          {
            return;
          }
        }
        const std::size_t bytes = encoder.Bytes(c * BlocksAtOnce, BlocksAtOnce);
        const int error =
          std::fwrite(chunks[c % Slots].get(), 1, bytes, file) == bytes ? 0 : (errno ? errno : EIO);
        std::lock_guard<std::mutex> lock(mutex);
        written = c + 1;
        failure = error;
        changed.notify_all();
        if (error)
        {
          return;
        }
      }
    });
  // One thread fewer than the cores encode, the last one writes: with as many encoding threads
  // as cores, the one that shares its core with the writing holds the others up at the end of
  // every chunk (measured on 2 cores: 0.19-0.21 s for 10M points of format 3, against 0.16 s
  // with one encoding thread).
#ifdef _OPENMP
  const int encoders = std::max(1, omp_get_max_threads() - 1);
#else
  const int encoders = 1;
#endif
  bool inRange = true;
  for (std::size_t c = 0; c < chunkCount && inRange; ++c)
  {
    {
      std::unique_lock<std::mutex> lock(mutex);
      changed.wait(lock, [&]() { return written + Slots > c || failure; });
      if (failure)
      {
        break;
      }
    }
    std::uint8_t* chunk = chunks[c % Slots].get();
    const std::size_t firstBlock = c * BlocksAtOnce;
    const auto blocks = static_cast<std::int64_t>(std::min(BlocksAtOnce, blockCount - firstBlock));
#pragma omp parallel for schedule(static) num_threads(encoders)
    for (std::int64_t b = 0; b < blocks; ++b)
    {
      const std::size_t block = firstBlock + static_cast<std::size_t>(b);
      std::uint8_t* records = chunk + encoder.Bytes(firstBlock, static_cast<std::size_t>(b));
      std::memset(records, 0, encoder.Bytes(block, 1));
      summaries[block] = encoder.Encode(block, records);
    }
    for (std::int64_t b = 0; b < blocks; ++b)
    {
      inRange = inRange && !summaries[firstBlock + static_cast<std::size_t>(b)].OutOfRange;
    }
    std::lock_guard<std::mutex> lock(mutex);
    encoded = inRange ? c + 1 : encoded;
    changed.notify_all();
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    stopped = true;
    changed.notify_all();
  }
  writer.join();
  errno = failure ? failure : errno;
  return inRange && failure == 0;
}

enum class MappedWrite
{
  Written,
  Failed,   // errno says why
  NotMapped // not possible here: write the records another way
};

/// Writes the records straight into a memory mapping of the file, every thread encoding its
/// blocks there: no copy of the records into the page cache by fwrite, and no thread left only
/// writing. The file (opened empty, its header and VLRs written) is first extended over the
/// records with fallocate, which reserves their blocks: a full disk is an error now, rather than
/// a SIGBUS when a page of the mapping is stored into later, and the new range reads as zeros,
/// as the encoder needs (it leaves the fields without a column alone). In tmpfs, on a file system
/// without fallocate, where the file cannot be mapped, or with PCB_LAS_WRITE_MAPPED=0 in the
/// environment, the records are not written and NotMapped is returned (the file may have been
/// extended over them by then). Leaves the file's position after the records.
MappedWrite WritePointsMapped(std::FILE* file,
  std::uint64_t offset,
  const BlockEncoder& encoder,
  std::vector<BlockSummary>& summaries)
{
#if defined(PCB_LAS_MMAP) && defined(__linux__)
  const char* mapped = std::getenv("PCB_LAS_WRITE_MAPPED");
  const std::size_t bytes = encoder.Bytes(0, encoder.Blocks());
  if (bytes == 0 || (mapped && std::strcmp(mapped, "0") == 0))
  {
    return MappedWrite::NotMapped;
  }
  if (std::fflush(file) != 0)
  {
    return MappedWrite::Failed;
  }
  const int descriptor = fileno(file);
  struct stat status;
  struct statfs system;
  // The records' range must lie past the file's end, so that fallocate makes it zeros. Not in
  // tmpfs (/dev/shm), where fallocate takes a page of memory at a time on one thread (80 ms for
  // 340 MB here) and the first store into each page of the mapping clears it: slower than the
  // fwrite of the other path (0.18 s against 0.16 s for 10M points of format 3).
  if (fstat(descriptor, &status) != 0 || static_cast<std::uint64_t>(status.st_size) != offset ||
      fstatfs(descriptor, &system) != 0 || system.f_type == TMPFS_MAGIC)
  {
    return MappedWrite::NotMapped;
  }
  // Linux's fallocate rather than posix_fallocate: where the file system has no fallocate,
  // glibc's posix_fallocate writes a byte into every block instead, which is slower than the
  // fwrite of the other path; fallocate says EOPNOTSUPP, and the other path is taken.
  if (fallocate(descriptor, 0, static_cast<off_t>(offset), static_cast<off_t>(bytes)) != 0)
  {
    return errno == ENOSPC || errno == EFBIG || errno == EDQUOT ? MappedWrite::Failed
                                                                : MappedWrite::NotMapped;
  }
  // A mapping starts at a page: from the page holding the first record.
  const std::uint64_t page = static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
  const std::uint64_t start = offset / page * page;
  const std::size_t length = static_cast<std::size_t>(offset + bytes - start);
  void* mapping = mmap(
    nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, descriptor, static_cast<off_t>(start));
  if (mapping == MAP_FAILED)
  {
    return MappedWrite::NotMapped;
  }
  std::uint8_t* records = static_cast<std::uint8_t*>(mapping) + (offset - start);
  const auto blocks = static_cast<std::int64_t>(encoder.Blocks());
  // Each thread encodes one contiguous part of the file, and takes the page faults of its part.
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    const auto block = static_cast<std::size_t>(b);
    summaries[block] = encoder.Encode(block, records + encoder.Bytes(0, block));
  }
  if (munmap(mapping, length) != 0 ||
      std::fseek(file, static_cast<long>(offset + bytes), SEEK_SET) != 0)
  {
    return MappedWrite::Failed;
  }
  return MappedWrite::Written;
#else
  (void)file;
  (void)offset;
  (void)encoder;
  (void)summaries;
  return MappedWrite::NotMapped;
#endif
}
} // namespace

std::vector<std::uint8_t> EncodeLASRecords(const std::vector<LASRecord>& records, bool extended)
{
  std::vector<std::uint8_t> bytes;
  for (const LASRecord& record : records)
  {
    AppendRecord(bytes, record, extended);
  }
  return bytes;
}

bool DecodeLASRecords(const std::uint8_t* bytes,
  std::size_t size,
  bool extended,
  std::vector<LASRecord>& records)
{
  records.clear();
  const std::size_t headerSize = extended ? EVLRHeaderSize : VLRHeaderSize;
  for (std::size_t at = 0; at < size;)
  {
    if (size - at < headerSize)
    {
      return false;
    }
    const std::uint64_t length =
      extended ? Load<std::uint64_t>(bytes + at + 20) : Load<std::uint16_t>(bytes + at + 20);
    if (length > size - at - headerSize)
    {
      return false;
    }
    LASRecord record;
    record.Extended = extended;
    record.Reserved = Load<std::uint16_t>(bytes + at);
    record.UserId = FixedString(bytes + at + 2, 16);
    record.RecordId = Load<std::uint16_t>(bytes + at + 18);
    record.Description = FixedString(bytes + at + (extended ? 28 : 22), 32);
    record.Data.assign(bytes + at + headerSize, bytes + at + headerSize + length);
    records.push_back(std::move(record));
    at += headerSize + length;
  }
  return true;
}

std::string WriteLAS(const std::string& path,
  const LASFileInfo& info,
  std::size_t count,
  const double* positions,
  const void* const* columns)
{
  const LASHeader& h = info.Header;
  const std::size_t standard = LASStandardRecordLength(h.PointFormat);
  if (standard == 0 || h.RecordLength < standard)
  {
    return path + ": cannot write point format " + std::to_string(h.PointFormat) +
           " with records of " + Str(h.RecordLength) + " bytes";
  }
  if (h.VersionMajor != 1 || h.VersionMinor > 4 || (h.PointFormat > 5 && h.VersionMinor < 4))
  {
    return path + ": cannot write point format " + std::to_string(h.PointFormat) + " in LAS " +
           std::to_string(h.VersionMajor) + "." + std::to_string(h.VersionMinor);
  }
  if (h.VersionMinor < 4 && count > std::numeric_limits<std::uint32_t>::max())
  {
    return path + ": " + Str(count) + " points do not fit in LAS 1." +
           std::to_string(h.VersionMinor) + " (at most 4294967295; LAS 1.4 holds more)";
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!std::isfinite(h.Scale[axis]) || h.Scale[axis] == 0.0 || !std::isfinite(h.Offset[axis]))
    {
      return path + ": the scale or offset of " + "xyz"[axis] + " is zero or not finite";
    }
  }
  const std::size_t headerSize =
    h.VersionMinor >= 4 ? 375 : (h.VersionMinor == 3 ? 235 : LegacyHeaderSize);
  std::vector<std::uint8_t> vlrBytes;
  std::uint32_t vlrCount = 0;
  std::vector<const LASRecord*> extended;
  for (const LASRecord& record : info.VLRs)
  {
    if (record.Extended || record.Data.size() > 0xFFFF)
    {
      extended.push_back(&record);
      continue;
    }
    AppendRecord(vlrBytes, record, false);
    ++vlrCount;
  }
  for (const LASRecord& record : info.EVLRs)
  {
    extended.push_back(&record);
  }
  if (!extended.empty() && h.VersionMinor < 4)
  {
    return path + ": a variable-length record longer than 65535 bytes needs LAS 1.4";
  }
  const std::size_t offsetToPoints = headerSize + vlrBytes.size();
  if (offsetToPoints > std::numeric_limits<std::uint32_t>::max())
  {
    return path + ": the variable-length records are too long for a LAS header";
  }

  ReplacingFile output(path);
  std::FILE* file = output.Get();
  if (!file)
  {
    return output.OpenError();
  }

  // The header's place first; it is written again at the end with the bounds and counts.
  std::vector<std::uint8_t> header(headerSize, 0);
  bool ok = std::fwrite(header.data(), 1, header.size(), file) == header.size() &&
            std::fwrite(vlrBytes.data(), 1, vlrBytes.size(), file) == vlrBytes.size();

  const BlockEncoder encoder(info, count, positions, columns);
  std::vector<BlockSummary> summaries(encoder.Blocks());
  int failure = 0; // the errno of a failed write of the records
  if (ok)
  {
    const MappedWrite mapped = WritePointsMapped(file, offsetToPoints, encoder, summaries);
    ok = mapped == MappedWrite::NotMapped ? WritePointsInChunks(file, encoder, summaries)
                                          : mapped == MappedWrite::Written;
    failure = ok ? 0 : errno;
  }
  for (const BlockSummary& summary : summaries)
  {
    if (summary.OutOfRange)
    {
      return path + ": a point's coordinates do not fit the LAS records' 32-bit integers with "
                    "the scale and offset of the header (or are not finite)";
    }
  }

  std::vector<std::uint8_t> evlrBytes;
  for (const LASRecord* record : extended)
  {
    AppendRecord(evlrBytes, *record, true);
  }
  ok = ok && std::fwrite(evlrBytes.data(), 1, evlrBytes.size(), file) == evlrBytes.size();

  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  std::uint64_t byReturn[15] = {};
  for (std::size_t b = 0; b < summaries.size(); ++b)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      bounds[axis] =
        b == 0 ? summaries[b].Bounds[axis] : std::min(bounds[axis], summaries[b].Bounds[axis]);
      bounds[3 + axis] = b == 0 ? summaries[b].Bounds[3 + axis]
                                : std::max(bounds[3 + axis], summaries[b].Bounds[3 + axis]);
    }
    for (int r = 0; r < 15; ++r)
    {
      byReturn[r] += summaries[b].ByReturn[r];
    }
  }
  header = EncodeHeader(info,
    headerSize,
    offsetToPoints,
    vlrCount,
    static_cast<std::uint32_t>(extended.size()),
    count,
    byReturn,
    bounds);
  ok = ok && std::fseek(file, 0, SEEK_SET) == 0 &&
       std::fwrite(header.data(), 1, header.size(), file) == header.size();
  return output.Commit(ok, failure);
}

LASFileInfo DefaultLASFileInfo(std::size_t count, const double bounds[6], bool gpsTime, bool rgb)
{
  LASFileInfo info;
  LASHeader& h = info.Header;
  const bool huge = count > std::numeric_limits<std::uint32_t>::max();
  h.VersionMinor = huge ? 4 : 2;
  h.PointFormat = huge ? static_cast<std::uint8_t>(rgb ? 7 : 6)
                       : static_cast<std::uint8_t>((gpsTime ? 1 : 0) + (rgb ? 2 : 0));
  h.RecordLength = static_cast<std::uint16_t>(LASStandardRecordLength(h.PointFormat));
  h.SystemIdentifier = "pcbilateral";
  h.GeneratingSoftware = "PointCloudBilateral";
  for (int axis = 0; axis < 3; ++axis)
  {
    const double low = std::isfinite(bounds[axis]) ? bounds[axis] : 0.0;
    const double high = std::isfinite(bounds[3 + axis]) ? bounds[3 + axis] : low;
    // A round offset at or below the lowest value; the finest power of ten that keeps the
    // whole extent within 2^31 steps, but no finer than a nanometre of a metre's units.
    h.Offset[axis] = std::floor(low);
    const double extent = std::max(high - h.Offset[axis], 1e-300);
    const double exponent = std::ceil(std::log10(extent / 2.0e9));
    h.Scale[axis] = std::pow(10.0, std::max(exponent, -9.0));
  }
  LASDimensionsFor(h.PointFormat, h.RecordLength, info.VLRs, info.Dimensions);
  return info;
}

} // namespace pcbilateral
