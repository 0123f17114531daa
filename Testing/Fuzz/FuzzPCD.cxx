// libFuzzer target for the PCD reader and writer: any bytes must give either a one-line error
// naming the source and no points, or a cloud whose columns hold exactly their points' values,
// decoded without reading outside the bytes (AddressSanitizer watches). What decodes is written
// again in its own encoding (to a temporary file) and read back: the same points and fields,
// bit for bit (ascii: any NaN for a NaN, since text keeps no NaN payload). The NaN points are
// kept or dropped as the first byte says, so both paths are covered.
#include "FuzzScratchFile.h"
#include "PCDFile.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
bool SameDouble(double a, double b, bool anyNaN)
{
  if (anyNaN && std::isnan(a) && std::isnan(b))
  {
    return true;
  }
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Whether two values of a field are the same (any NaN for a NaN when `anyNaN`).
bool SameValues(const pcbilateral::PCDColumn& a, const pcbilateral::PCDColumn& b, bool anyNaN)
{
  const pcbilateral::PCDField& field = a.Field;
  if (a.Bytes.size() != b.Bytes.size())
  {
    return false;
  }
  if (!anyNaN || field.Type != 'F' || pcbilateral::IsPCDPackedColour(field))
  {
    return a.Bytes == b.Bytes;
  }
  for (std::size_t at = 0; at < a.Bytes.size(); at += field.Size)
  {
    double x = 0, y = 0;
    if (field.Size == 4)
    {
      float u, v;
      std::memcpy(&u, a.Bytes.data() + at, 4);
      std::memcpy(&v, b.Bytes.data() + at, 4);
      x = u;
      y = v;
    }
    else
    {
      std::memcpy(&x, a.Bytes.data() + at, 8);
      std::memcpy(&y, b.Bytes.data() + at, 8);
    }
    if (!SameDouble(x, y, true))
    {
      return false;
    }
  }
  return true;
}

void CheckWrittenBack(const pcbilateral::PCDCloud& cloud,
  const pcbilateral::PCDReadOptions& options)
{
  static const std::string path = FuzzScratchPath("FuzzPCD", ".pcd");
  const std::string error = pcbilateral::WritePCD(path, cloud, cloud.Header.Encoding);
  if (RefusedWithoutFile(error, path))
  {
    return;
  }
  pcbilateral::PCDCloud back;
  if (!pcbilateral::ReadPCD(path, options, back).empty())
  {
    std::abort(); // the writer wrote a file its reader refuses
  }
  const bool anyNaN = cloud.Header.Encoding == pcbilateral::PCDEncoding::ASCII;
  if (back.NumberOfPoints != cloud.NumberOfPoints || back.Columns.size() != cloud.Columns.size() ||
      back.Header.Fields.size() != cloud.Header.Fields.size())
  {
    std::abort(); // not the same cloud
  }
  for (std::size_t i = 0; i < cloud.Positions.size(); ++i)
  {
    // x y z of an integer type or F4 hold their values exactly as doubles.
    if (!SameDouble(cloud.Positions[i], back.Positions[i], anyNaN))
    {
      std::abort(); // a coordinate changed
    }
  }
  for (std::size_t k = 0; k < cloud.Columns.size(); ++k)
  {
    if (!SameValues(cloud.Columns[k], back.Columns[k], anyNaN))
    {
      std::abort(); // a field changed
    }
  }
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // A copy of exactly `size` bytes, so that a read past the end is caught.
  const std::vector<char> bytes(data, data + size);
  pcbilateral::PCDReadOptions options;
  options.KeepNaNPoints = size > 0 && (data[0] & 1) == 0;
  pcbilateral::PCDCloud cloud;
  const std::string error = pcbilateral::DecodePCD(bytes.data(), size, "fuzz", options, cloud);
  if (!error.empty())
  {
    CheckOneLine(error, "fuzz");
    if (cloud.NumberOfPoints != 0 || !cloud.Positions.empty() || !cloud.Columns.empty())
    {
      std::abort(); // an error with points
    }
    return 0;
  }
  if (cloud.Positions.size() != 3 * cloud.NumberOfPoints ||
      cloud.NumberOfPoints + cloud.NumberOfDroppedPoints != cloud.Header.NumberOfPoints)
  {
    std::abort(); // the points do not add up
  }
  for (const pcbilateral::PCDColumn& column : cloud.Columns)
  {
    if (column.Bytes.size() != cloud.NumberOfPoints * column.Field.Bytes())
    {
      std::abort(); // a column of another length
    }
  }
  CheckWrittenBack(cloud, options);
  return 0;
}
