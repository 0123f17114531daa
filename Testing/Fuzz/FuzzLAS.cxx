// libFuzzer target for the LAS parser, decoder and writer: any bytes must give either a
// one-line error naming the source, or a header whose every announced record lies within the
// bytes, then decode without reading outside them (AddressSanitizer watches the decoding).
// What decodes is written again (to a temporary file) and read back: the writer either
// refuses with a one-line error naming its file and leaves no file, or writes a file that
// reads back with the same fields and the same point records, byte for byte. The one
// exception: the coordinates of an axis whose scale and offset cannot give every stored
// integer back (a scale near zero or infinity, an offset of 2^48 steps or more) must decode to
// the same values, not to the same integers.
#include "FuzzScratchFile.h"
#include "LASHeader.h"
#include "LASReader.h"
#include "LASWriter.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
struct DecodedPoints
{
  std::vector<double> Positions;
  std::vector<std::vector<std::uint8_t>> Storage;
  std::vector<void*> Columns;
};

DecodedPoints Decode(const pcbilateral::LASFileInfo& info, const std::uint8_t* data)
{
  const auto count = static_cast<std::size_t>(info.Header.NumberOfPoints);
  DecodedPoints points;
  points.Positions.resize(3 * count);
  for (const pcbilateral::LASDimension& dimension : info.Dimensions)
  {
    points.Storage.emplace_back(count * pcbilateral::LASColumnBytes(dimension));
    points.Columns.push_back(points.Storage.back().data());
  }
  pcbilateral::DecodeLASPoints(info,
    data + info.Header.OffsetToPointData,
    count,
    points.Positions.data(),
    points.Columns.data());
  return points;
}

void CheckWrittenBack(const pcbilateral::LASFileInfo& info,
  const std::uint8_t* data,
  const DecodedPoints& points)
{
  static const std::string path = FuzzScratchPath("FuzzLAS", ".las");
  const auto count = static_cast<std::size_t>(info.Header.NumberOfPoints);
  const std::vector<const void*> columns(points.Columns.begin(), points.Columns.end());
  const std::string error =
    pcbilateral::WriteLAS(path, info, count, points.Positions.data(), columns.data());
  if (RefusedWithoutFile(error, path))
  {
    return;
  }
  pcbilateral::LASFileBytes file;
  pcbilateral::LASFileInfo back;
  if (!file.Open(path).empty() ||
      !pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, back).empty())
  {
    std::abort(); // the writer wrote a file its reader refuses
  }
  if (back.Header.NumberOfPoints != info.Header.NumberOfPoints ||
      back.Header.PointFormat != info.Header.PointFormat ||
      back.Header.RecordLength != info.Header.RecordLength ||
      back.Dimensions.size() != info.Dimensions.size())
  {
    std::abort(); // not the same kind of records
  }
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const pcbilateral::LASDimension& a = info.Dimensions[d];
    const pcbilateral::LASDimension& b = back.Dimensions[d];
    if (a.Name != b.Name || a.Type != b.Type || a.ColumnType != b.ColumnType ||
        a.Components != b.Components || a.ByteOffset != b.ByteOffset || a.Scaled != b.Scaled)
    {
      std::abort(); // the fields changed
    }
  }
  const std::size_t stride = info.Header.RecordLength;
  const std::uint8_t* original = data + info.Header.OffsetToPointData;
  const std::uint8_t* written = file.Data() + back.Header.OffsetToPointData;
  bool exact[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    exact[axis] = pcbilateral::LASScalingIsExact(info.Header.Scale[axis], info.Header.Offset[axis]);
  }
  const DecodedPoints again = Decode(back, file.Data());
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::uint8_t* a = original + i * stride;
    const std::uint8_t* b = written + i * stride;
    for (int axis = 0; axis < 3; ++axis)
    {
      const bool same = exact[axis]
                          ? std::memcmp(a + 4 * axis, b + 4 * axis, 4) == 0
                          : points.Positions[3 * i + axis] == again.Positions[3 * i + axis];
      if (!same)
      {
        std::abort(); // a coordinate changed
      }
    }
    if (std::memcmp(a + 12, b + 12, stride - 12) != 0)
    {
      std::abort(); // the other fields of a record changed
    }
  }
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // A copy of exactly `size` bytes, so that a read past the end is caught.
  const std::vector<std::uint8_t> bytes(data, data + size);
  pcbilateral::LASFileInfo info;
  const std::string error = pcbilateral::ParseLASHeader(bytes.data(), size, "fuzz", info);
  if (!error.empty())
  {
    CheckOneLine(error, "fuzz");
    return 0;
  }
  const pcbilateral::LASHeader& header = info.Header;
  if (header.OffsetToPointData > size ||
      header.NumberOfPoints > (size - header.OffsetToPointData) / header.RecordLength)
  {
    std::abort(); // accepted a header promising more than the bytes hold
  }
  for (const pcbilateral::LASDimension& dimension : info.Dimensions)
  {
    if (dimension.ByteOffset +
          pcbilateral::LASSizeOf(dimension.Type) * static_cast<std::size_t>(dimension.Components) >
        header.RecordLength)
    {
      std::abort(); // a field beyond the record
    }
  }
  const DecodedPoints points = Decode(info, bytes.data());
  CheckWrittenBack(info, bytes.data(), points);
  return 0;
}
