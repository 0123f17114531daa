#include "LASExtraBytes.h"

#include "LASBinary.h"
#include "LASScaledFields.h"

#include <cstdint>
#include <limits>
#include <set>
#include <type_traits>

namespace pcbilateral
{
namespace las
{

namespace
{
constexpr std::size_t DescriptorSize = 192;

/// The scale, offset and no-data value of an extra-bytes descriptor (`options` bits 0, 3 and
/// 4; the minimum and maximum, bits 1 and 2, describe the values and change nothing), applied
/// when the stored values are integers of 32 bits or fewer that the scaling gives back exactly.
/// Other types keep their stored values, and the descriptor stays in the record either way.
void ApplyScaling(const std::uint8_t* descriptor, int options, LASDimension& dimension)
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

/// The type, components and scaling of the field a descriptor describes. Returns an empty
/// string, or what is wrong.
std::string DescribeField(const std::uint8_t* descriptor, LASDimension& dimension)
{
  const int dataType = descriptor[2];
  const int options = descriptor[3];
  if (dataType == 0)
  {
    // Undocumented bytes: the options byte gives their number.
    dimension.Type = LASValueType::UInt8;
    dimension.Components = options;
  }
  else if (dataType <= 30)
  {
    dimension.Type = static_cast<LASValueType>((dataType - 1) % 10);
    dimension.ColumnType = dimension.Type;
    dimension.Components = 1 + (dataType - 1) / 10; // 11-30: deprecated arrays of 2 and 3
    ApplyScaling(descriptor, options, dimension);
  }
  else
  {
    return "the extra-bytes record describes an unknown data type " + std::to_string(dataType);
  }
  return std::string();
}

/// The name of descriptor `k`, made unique among `taken` (and added to them).
std::string UniqueName(const std::uint8_t* descriptor, std::size_t k, std::set<std::string>& taken)
{
  std::string name = FixedString(descriptor + 4, 32);
  if (name.empty())
  {
    name = "ExtraBytes" + Str(k + 1);
  }
  for (int suffix = 2; taken.count(name) != 0; ++suffix)
  {
    name = FixedString(descriptor + 4, 32) + "_" + std::to_string(suffix);
  }
  taken.insert(name);
  return name;
}
} // namespace

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

std::string AddExtraBytesDimensions(std::size_t standardLength,
  std::size_t recordLength,
  const std::vector<LASRecord>& records,
  std::vector<LASDimension>& dimensions)
{
  std::size_t at = standardLength;
  // "Colors" is taken too: the readers add the display colours under that name, which would
  // replace an extra-bytes field of that name (and the writer would write them in its place).
  std::set<std::string> names = { "Colors" };
  for (const LASDimension& dimension : dimensions)
  {
    names.insert(dimension.Name);
  }
  const LASRecord* described = FindExtraBytesRecord(records);
  const std::size_t descriptors = described ? described->Data.size() / DescriptorSize : 0;
  for (std::size_t k = 0; k < descriptors; ++k)
  {
    const std::uint8_t* descriptor = described->Data.data() + k * DescriptorSize;
    LASDimension dimension;
    const std::string problem = DescribeField(descriptor, dimension);
    if (!problem.empty())
    {
      return problem;
    }
    const std::size_t bytes = LASSizeOf(dimension.Type) * dimension.Components;
    if (at + bytes > recordLength)
    {
      return "the extra-bytes record describes more bytes than the point records hold (" +
             Str(recordLength - standardLength) + ")";
    }
    if (bytes == 0)
    {
      continue;
    }
    dimension.Name = UniqueName(descriptor, k, names);
    dimension.ByteOffset = at;
    at += bytes;
    dimensions.push_back(dimension);
  }
  if (at < recordLength)
  {
    // Bytes no descriptor names are kept as they are, so that they are written back.
    LASDimension rest;
    rest.Name = names.count("ExtraBytes") ? "ExtraBytesUndescribed" : "ExtraBytes";
    rest.Type = LASValueType::UInt8;
    rest.Components = static_cast<int>(recordLength - at);
    rest.ByteOffset = at;
    dimensions.push_back(rest);
  }
  return std::string();
}

} // namespace las
} // namespace pcbilateral
