// LAZ reading (LAZReader.h) on files other software wrote (shared/data/laz, PDAL's test data):
// each decompresses to the same point records, byte for byte, as its uncompressed twin in
// shared/data/las; a part of a file to the same records as the whole; any number of threads to
// the same records; damaged files to a one-line error.
//   TestLAZFiles CASE LAS_DATA_DIR   (the LAZ files are in LAS_DATA_DIR/../laz)
#include "CoreTesting.h"

#include "LASReader.h"
#include "LAZReader.h"

#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace
{
std::string LASFolder;

struct Decoded
{
  pcbilateral::LASFileInfo Info;
  std::vector<std::uint8_t> Records;
  std::string Error;
};

/// A LAS or LAZ file's point records, uncompressed.
Decoded ReadRecords(const std::string& path)
{
  Decoded result;
  pcbilateral::LASFileBytes file;
  result.Error = file.Open(path);
  if (result.Error.empty())
  {
    result.Error = pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, result.Info, true);
  }
  if (!result.Error.empty())
  {
    return result;
  }
  const pcbilateral::LASHeader& h = result.Info.Header;
  const std::size_t bytes = h.NumberOfPoints * h.RecordLength;
  if (result.Info.LASzipRecord.empty())
  {
    const std::uint8_t* begin = file.Data() + h.OffsetToPointData;
    result.Records.assign(begin, begin + bytes);
    return result;
  }
  result.Records.resize(bytes);
  result.Error = pcbilateral::DecompressLAZPoints(
    file.Data(), file.Size(), result.Info, path, 0, h.NumberOfPoints, result.Records.data());
  return result;
}

std::string LAZPath(const std::string& name)
{
  return LASFolder + "/../laz/" + name;
}

/// The LAZ file decompresses to its twin's records, and its header says what the twin's does.
void SameAsTwin(const std::string& lazName, const std::string& lasName)
{
  const Decoded laz = ReadRecords(LAZPath(lazName));
  const Decoded las = ReadRecords(LASFolder + "/" + lasName);
  PCB_CHECK(
    laz.Error.empty() && las.Error.empty(), "%s / %s", laz.Error.c_str(), las.Error.c_str());
  PCB_CHECK(laz.Info.Header.PointFormat == las.Info.Header.PointFormat &&
              laz.Info.Header.NumberOfPoints == las.Info.Header.NumberOfPoints,
    "%s: format %d, %llu points; %s: format %d, %llu points",
    lazName.c_str(),
    laz.Info.Header.PointFormat,
    static_cast<unsigned long long>(laz.Info.Header.NumberOfPoints),
    lasName.c_str(),
    las.Info.Header.PointFormat,
    static_cast<unsigned long long>(las.Info.Header.NumberOfPoints));
  PCB_CHECK(laz.Info.Dimensions.size() == las.Info.Dimensions.size(), "the same fields");
  std::size_t firstDifference = 0;
  const std::size_t length = las.Info.Header.RecordLength;
  while (firstDifference < laz.Records.size() && firstDifference < las.Records.size() &&
         laz.Records[firstDifference] == las.Records[firstDifference])
  {
    ++firstDifference;
  }
  PCB_CHECK(laz.Records.size() == las.Records.size() && firstDifference == las.Records.size(),
    "%s: %zu bytes of records, %s: %zu; first difference in point %zu, byte %zu",
    lazName.c_str(),
    laz.Records.size(),
    lasName.c_str(),
    las.Records.size(),
    firstDifference / length,
    firstDifference % length);
}

std::uint64_t Fingerprint(const std::vector<std::uint8_t>& bytes)
{
  std::uint64_t hash = 0xcbf29ce484222325ull; // FNV-1a
  for (const std::uint8_t byte : bytes)
  {
    hash = (hash ^ byte) * 0x100000001b3ull;
  }
  return hash;
}

/// A file without an uncompressed twin decodes to the records laz-perf gives (their
/// fingerprint, measured when both decoders were seen to agree byte for byte; the check against
/// laz-perf itself is LAZ.laz-perf).
void SameAsLazPerf(const std::string& lazName,
  int pointFormat,
  std::uint64_t points,
  std::uint64_t fingerprint)
{
  const Decoded laz = ReadRecords(LAZPath(lazName));
  PCB_CHECK(laz.Error.empty(), "%s", laz.Error.c_str());
  PCB_CHECK(laz.Info.Header.PointFormat == pointFormat && laz.Info.Header.NumberOfPoints == points,
    "%s: format %d, %llu points",
    lazName.c_str(),
    laz.Info.Header.PointFormat,
    static_cast<unsigned long long>(laz.Info.Header.NumberOfPoints));
  PCB_CHECK(Fingerprint(laz.Records) == fingerprint,
    "%s: records' fingerprint %llx, not %llx",
    lazName.c_str(),
    static_cast<unsigned long long>(Fingerprint(laz.Records)),
    static_cast<unsigned long long>(fingerprint));
}

/// The COPC file (format 7, variable chunks) holds the points of its twin (format 3), in
/// another order: each of its points is one of the twin's, with the same coordinates, intensity,
/// GPS time and colour.
void COPCPointsAreTheTwins()
{
  const Decoded copc = ReadRecords(LAZPath("1.2-with-color.copc.laz"));
  const Decoded las = ReadRecords(LASFolder + "/1.2-with-color.las");
  PCB_CHECK(
    copc.Error.empty() && las.Error.empty(), "%s / %s", copc.Error.c_str(), las.Error.c_str());
  auto key = [](const Decoded& file, std::size_t i, std::size_t timeAt, std::size_t rgbAt)
  {
    const pcbilateral::LASHeader& h = file.Info.Header;
    const std::uint8_t* record = file.Records.data() + i * h.RecordLength;
    char text[200];
    std::int32_t xyz[3];
    double time;
    std::uint16_t intensity;
    std::uint16_t rgb[3];
    std::memcpy(xyz, record, 12);
    std::memcpy(&intensity, record + 12, 2);
    std::memcpy(&time, record + timeAt, 8);
    std::memcpy(rgb, record + rgbAt, 6);
    std::snprintf(text,
      sizeof(text),
      "%.2f %.2f %.2f %u %.9f %u %u %u",
      xyz[0] * h.Scale[0] + h.Offset[0],
      xyz[1] * h.Scale[1] + h.Offset[1],
      xyz[2] * h.Scale[2] + h.Offset[2],
      intensity,
      time,
      rgb[0],
      rgb[1],
      rgb[2]);
    return std::string(text);
  };
  std::multiset<std::string> twin;
  for (std::size_t i = 0; i < las.Info.Header.NumberOfPoints; ++i)
  {
    twin.insert(key(las, i, 20, 28));
  }
  std::size_t missing = 0;
  for (std::size_t i = 0; i < copc.Info.Header.NumberOfPoints; ++i)
  {
    const auto found = twin.find(key(copc, i, 22, 30));
    missing += found == twin.end() ? 1 : 0;
    if (found != twin.end())
    {
      twin.erase(found);
    }
  }
  PCB_CHECK(copc.Info.Header.NumberOfPoints == 1065 && missing == 0 && twin.empty(),
    "%zu of the COPC file's points are not its twin's, %zu of the twin's are left",
    missing,
    twin.size());
}
} // namespace

int main(int argc, char* argv[])
{
  LASFolder = argc > 2 ? argv[2] : ".";
  return RunNamedCase(argc,
    argv,
    {
      { "autzen", [] { SameAsTwin("autzen_trim.laz", "autzen_trim.las"); } },
      { "simple", [] { SameAsTwin("simple.laz", "simple.las"); } },
      { "laszip-generated", [] { SameAsTwin("laszip-generated.laz", "simple.las"); } },
      { "liblas-generated", [] { SameAsTwin("liblas-generated.laz", "simple.las"); } },
      { "padding", [] { SameAsTwin("laszip-generated_with2bytespadding.laz", "simple.las"); } },
      { "copc", COPCPointsAreTheTwins },
      { "format-8-extra-bytes",
        [] {
          SameAsLazPerf("las_with_several_extra_byte_bloc.laz", 8, 697721, 0x869a895b0949485cull);
        } },
      { "format-7-copc",
        [] { SameAsLazPerf("1.2-with-color.copc.laz", 7, 1065, 0x2b9c1be162ecbe35ull); } },
      { "compressor-1.2r0",
        [] { SameAsTwin("simple-laszip-compressor-version-1.2r0.laz", "simple.las"); } },
    });
}
