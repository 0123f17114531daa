// LAZ reading (LAZReader.h) on files other software wrote (shared/data/laz, PDAL's test data):
// each decompresses to the same point records, byte for byte, as its uncompressed twin in
// shared/data/las; a part of a file to the same records as the whole; any number of threads to
// the same records; damaged files to a one-line error.
//   TestLAZFiles CASE LAS_DATA_DIR   (the LAZ files are in LAS_DATA_DIR/../laz)
#include "CoreTesting.h"

#include "LASReader.h"
#include "LAZReader.h"

#include <cstring>
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
      { "compressor-1.2r0",
        [] { SameAsTwin("simple-laszip-compressor-version-1.2r0.laz", "simple.las"); } },
    });
}
