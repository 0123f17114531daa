#include "LASHeader.h"

#include "LASBinary.h"
#include "LASExtraBytes.h"
#include "LASPointFormat.h"
#include "LASRecordBytes.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <utility>

namespace pcbilateral
{

namespace
{
using namespace las;

std::string CompressedProblem(const std::string& source)
{
  return "is compressed (LAZ); decompress it first, e.g. with 'laszip -i " +
         std::filesystem::path(source).filename().string() +
         " -o out.las' or 'pdal translate in.laz out.las'";
}

/// Whether the bytes can be a LAS file's header on this host at all.
std::string CheckSignature(const std::uint8_t* data, std::size_t size)
{
  if (!HostIsLittleEndian())
  {
    return "LAS files are read on little-endian machines only";
  }
  if (size < 4 || std::memcmp(data, "LASF", 4) != 0)
  {
    return "not a LAS file (it does not start with the signature 'LASF')";
  }
  if (size < LegacyHeaderSize)
  {
    return "truncated: " + Str(size) + " bytes, shorter than a LAS header (" +
           Str(LegacyHeaderSize) + " bytes)";
  }
  return std::string();
}

/// The fields of the header's first 227 bytes but the point counts, scales and offsets.
void DecodeFixedFields(const std::uint8_t* data, LASHeader& h)
{
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
  h.RecordLength = Load<std::uint16_t>(data + 105);
}

/// The version and the point format, then whether the header and the offset to the points lie
/// within the file.
std::string CheckLayout(const std::uint8_t* data,
  std::size_t size,
  const std::string& source,
  bool acceptCompressed,
  LASHeader& h)
{
  const std::string version = std::to_string(h.VersionMajor) + "." + std::to_string(h.VersionMinor);
  if (h.VersionMajor != 1 || h.VersionMinor > 4)
  {
    return "unsupported LAS version " + version + " (versions 1.0 to 1.4 are read)";
  }
  // LASzip marks its files by setting the top bits of the point format.
  const std::uint8_t formatByte = data[104];
  if ((formatByte & 0xC0) && !acceptCompressed)
  {
    return CompressedProblem(source);
  }
  h.PointFormat = formatByte & 0x3F;
  if (h.PointFormat > 10)
  {
    return "point format " + std::to_string(h.PointFormat) +
           " is not supported (LAS defines point formats 0 to 10)";
  }
  const std::size_t versionHeaderSize = HeaderSizeOfVersion(h.VersionMinor);
  if (h.HeaderSize < versionHeaderSize)
  {
    return "the header size " + Str(h.HeaderSize) + " is too small for LAS " + version + " (" +
           Str(versionHeaderSize) + " bytes)";
  }
  if (h.HeaderSize > size)
  {
    return "truncated: the header announces " + Str(h.HeaderSize) +
           " bytes of header, the file has " + Str(size);
  }
  if (h.OffsetToPointData < h.HeaderSize || h.OffsetToPointData > size)
  {
    return "the offset to the point data (" + Str(h.OffsetToPointData) +
           ") is outside the file (header " + Str(h.HeaderSize) + " bytes, file " + Str(size) +
           " bytes)";
  }
  return std::string();
}

std::string DecodeScalesAndBounds(const std::uint8_t* data, LASHeader& h)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    h.Scale[axis] = Load<double>(data + 131 + 8 * axis);
    h.Offset[axis] = Load<double>(data + 155 + 8 * axis);
    h.Bounds[3 + axis] = Load<double>(data + 179 + 16 * axis);
    h.Bounds[axis] = Load<double>(data + 187 + 16 * axis);
    if (!std::isfinite(h.Scale[axis]) || h.Scale[axis] == 0.0 || !std::isfinite(h.Offset[axis]))
    {
      return std::string("the header's scale or offset of ") + "xyz"[axis] +
             " is zero or not a finite number";
    }
  }
  return std::string();
}

/// The VLRs, between the header and the point data.
std::string DecodeVLRs(const std::uint8_t* data,
  const std::string& source,
  bool acceptCompressed,
  LASFileInfo& info)
{
  const LASHeader& h = info.Header;
  std::vector<LASRecord>& vlrs = info.VLRs;
  const std::uint32_t vlrCount = Load<std::uint32_t>(data + 100);
  std::size_t at = h.HeaderSize;
  if (vlrCount > (h.OffsetToPointData - at) / VLRHeaderSize)
  {
    return "the header announces " + Str(vlrCount) +
           " variable-length records, more than fit before the point data at byte " +
           Str(h.OffsetToPointData);
  }
  for (std::uint32_t k = 0; k < vlrCount; ++k)
  {
    const std::size_t length = at + VLRHeaderSize <= h.OffsetToPointData
                                 ? static_cast<std::size_t>(RecordDataLength(data + at, false))
                                 : 0;
    if (at + VLRHeaderSize + length > h.OffsetToPointData)
    {
      return "the header announces " + Str(vlrCount) + " variable-length records but " + "record " +
             Str(k + 1) + " runs past the start of the point data at byte " +
             Str(h.OffsetToPointData);
    }
    LASRecord record = DecodeRecord(data + at, false, length);
    if (record.UserId == "laszip encoded" && record.RecordId == 22204)
    {
      if (!acceptCompressed)
      {
        return CompressedProblem(source);
      }
      info.LASzipRecord = std::move(record.Data);
      at += VLRHeaderSize + length;
      continue;
    }
    vlrs.push_back(std::move(record));
    at += VLRHeaderSize + length;
  }
  return std::string();
}

/// The number of points and the points by return: LAS 1.4 has 64-bit counts, and its 32-bit
/// ones may be 0.
void DecodePointCounts(const std::uint8_t* data, LASHeader& h)
{
  h.NumberOfPoints = Load<std::uint32_t>(data + 107);
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
}

std::string CheckPointRecords(std::size_t size, const LASHeader& h)
{
  const std::size_t pointBytes = size - h.OffsetToPointData;
  const std::size_t available = pointBytes / h.RecordLength;
  if (h.NumberOfPoints > available)
  {
    return "truncated: the header announces " + Str(h.NumberOfPoints) + " points, the file holds " +
           Str(available) + " (" + Str(pointBytes) + " bytes of point records of " +
           Str(h.RecordLength) + " bytes)";
  }
  return std::string();
}

/// The extended VLRs (LAS 1.4), after the point data.
std::string DecodeEVLRs(const std::uint8_t* data,
  std::size_t size,
  const LASHeader& h,
  std::vector<LASRecord>& evlrs)
{
  const std::uint64_t start = Load<std::uint64_t>(data + 235);
  const std::uint32_t count = Load<std::uint32_t>(data + 243);
  // Compressed points take an unknown part of the file, checked when they are decompressed.
  const bool compressed = (data[104] & 0xC0) != 0;
  const std::uint64_t pointsEnd =
    h.OffsetToPointData + (compressed ? 0 : h.NumberOfPoints * h.RecordLength);
  if (count > 0 && (start < pointsEnd || start > size || count > (size - start) / EVLRHeaderSize))
  {
    return "the header announces " + Str(count) + " extended variable-length records at byte " +
           Str(start) + ", outside the file's " + Str(size) + " bytes after its points";
  }
  std::uint64_t e = start;
  for (std::uint32_t k = 0; k < count; ++k)
  {
    const std::uint64_t length =
      e + EVLRHeaderSize <= size ? RecordDataLength(data + e, true) : size;
    if (e + EVLRHeaderSize > size || length > size - e - EVLRHeaderSize)
    {
      return "truncated: extended variable-length record " + Str(k + 1) +
             " runs past the end of the file";
    }
    evlrs.push_back(DecodeRecord(data + e, true, length));
    e += EVLRHeaderSize + length;
  }
  return std::string();
}

/// The fields of the point records again, when their extra bytes are described by an EVLR
/// rather than a VLR.
std::string DescribeExtraBytesByEVLR(LASFileInfo& info)
{
  const LASHeader& h = info.Header;
  const std::vector<LASRecord>& described = LASExtraBytesRecords(info.VLRs, info.EVLRs);
  if (&described == &info.VLRs)
  {
    return std::string();
  }
  return LASDimensionsFor(h.PointFormat, h.RecordLength, described, info.Dimensions);
}
} // namespace

std::string ParseLASHeader(const std::uint8_t* data,
  std::size_t size,
  const std::string& source,
  LASFileInfo& info,
  bool acceptCompressed)
{
  info = LASFileInfo();
  LASHeader& h = info.Header;
  std::string problem = CheckSignature(data, size);
  if (problem.empty())
  {
    DecodeFixedFields(data, h);
    problem = CheckLayout(data, size, source, acceptCompressed, h);
  }
  if (problem.empty())
  {
    problem = DecodeScalesAndBounds(data, h);
  }
  if (problem.empty())
  {
    problem = DecodeVLRs(data, source, acceptCompressed, info);
  }
  if (problem.empty())
  {
    DecodePointCounts(data, h);
    problem = LASDimensionsFor(h.PointFormat, h.RecordLength, info.VLRs, info.Dimensions);
  }
  const bool compressed = problem.empty() && (data[104] & 0xC0) != 0;
  if (problem.empty() && compressed != !info.LASzipRecord.empty())
  {
    problem = compressed
                ? "the point format marks it compressed (LAZ) but it has no LASzip record"
                : "it has a LASzip record (LAZ) but its point format is not marked compressed";
  }
  if (problem.empty() && !compressed)
  {
    problem = CheckPointRecords(size, h);
  }
  if (problem.empty() && h.VersionMinor >= 4)
  {
    problem = DecodeEVLRs(data, size, h, info.EVLRs);
    if (problem.empty())
    {
      problem = DescribeExtraBytesByEVLR(info);
    }
  }
  return problem.empty() ? problem : source + ": " + problem;
}

} // namespace pcbilateral
