// LAZ reading (LAZReader.h) on files other software wrote (shared/data/laz, PDAL's test data):
// each decompresses to the same point records, byte for byte, as its uncompressed twin in
// shared/data/las; a part of a file to the same records as the whole; any number of threads to
// the same records; damaged files to a one-line error.
//   TestLAZFiles CASE LAS_DATA_DIR   (the LAZ files are in LAS_DATA_DIR/../laz)
#include "CoreTesting.h"
#include "LASPointKey.h"

#include "LASReader.h"
#include "LASWriter.h"
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
  auto key = [](const Decoded& file, std::size_t i)
  { return PointKey(file.Info.Header, file.Records.data() + i * file.Info.Header.RecordLength); };
  std::multiset<std::string> twin;
  for (std::size_t i = 0; i < las.Info.Header.NumberOfPoints; ++i)
  {
    twin.insert(key(las, i));
  }
  std::size_t missing = 0;
  for (std::size_t i = 0; i < copc.Info.Header.NumberOfPoints; ++i)
  {
    const auto found = twin.find(key(copc, i));
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
/// Points asked for across a chunk boundary are those of the whole file; any number of threads
/// gives the same records.
void PartsAndThreads()
{
  const std::string path = LAZPath("autzen_trim.laz");
  pcbilateral::LASFileBytes file;
  pcbilateral::LASFileInfo info;
  PCB_CHECK(file.Open(path).empty() &&
              pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, info, true).empty(),
    "%s",
    path.c_str());
  const std::size_t length = info.Header.RecordLength;
  const std::size_t count = info.Header.NumberOfPoints;
  std::vector<std::uint8_t> whole(count * length);
  std::vector<std::uint8_t> alone(count * length);
#ifdef _OPENMP
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
#endif
  std::string error =
    pcbilateral::DecompressLAZPoints(file.Data(), file.Size(), info, path, 0, count, alone.data());
#ifdef _OPENMP
  omp_set_num_threads(threads > 2 ? threads : 3);
#endif
  error +=
    pcbilateral::DecompressLAZPoints(file.Data(), file.Size(), info, path, 0, count, whole.data());
  PCB_CHECK(error.empty() && whole == alone, "one thread and several: %s", error.c_str());
  for (const auto& [first, points] : { std::pair<std::size_t, std::size_t>{ 49990, 20 },
         { 0, 1 },
         { 50000, 50000 },
         { 109999, 1 },
         { 20, 100000 } })
  {
    std::vector<std::uint8_t> part(points * length);
    error = pcbilateral::DecompressLAZPoints(
      file.Data(), file.Size(), info, path, first, points, part.data());
    PCB_CHECK(
      error.empty() && std::memcmp(part.data(), whole.data() + first * length, part.size()) == 0,
      "points %zu to %zu: %s",
      first,
      first + points,
      error.c_str());
  }
  std::vector<std::uint8_t> beyond(length);
  error =
    pcbilateral::DecompressLAZPoints(file.Data(), file.Size(), info, path, count, 1, beyond.data());
  PCB_CHECK(
    error.find("asked for") != std::string::npos, "a point beyond the last: '%s'", error.c_str());
}

/// A damaged or unsupported LAZ file gives one line naming the file and the problem.
void ExpectError(const std::string& name,
  std::vector<std::uint8_t> bytes,
  const std::string& expected)
{
  pcbilateral::LASFileInfo info;
  std::string error = pcbilateral::ParseLASHeader(bytes.data(), bytes.size(), name, info, true);
  if (error.empty())
  {
    std::vector<std::uint8_t> decompressed;
    const std::uint8_t* records = nullptr;
    error = pcbilateral::UncompressedLASRecords(
      bytes.data(), bytes.size(), info, name, decompressed, records);
  }
  PCB_CHECK(error.find(expected) != std::string::npos && error.rfind(name, 0) == 0 &&
              error.find('\n') == std::string::npos,
    "%s: the error is '%s', expected '%s'",
    name.c_str(),
    error.c_str(),
    expected.c_str());
}

std::vector<std::uint8_t> FileContentsOf(const std::string& path)
{
  const std::string text = pcbilateral_testing::FileContents(path);
  return std::vector<std::uint8_t>(text.begin(), text.end());
}

/// Where the data of the LASzip record starts in a file.
std::size_t LASzipRecordAt(const std::vector<std::uint8_t>& bytes)
{
  std::size_t at = bytes[94] | (bytes[95] << 8);
  while (at + 54 < bytes.size() && std::memcmp(&bytes[at + 2], "laszip encoded", 14) != 0)
  {
    at += 54 + (bytes[at + 20] | (bytes[at + 21] << 8));
  }
  return at + 54;
}

void DamagedAndUnsupported()
{
  const std::vector<std::uint8_t> autzen = FileContentsOf(LAZPath("autzen_trim.laz"));
  std::vector<std::uint8_t> bytes = autzen;
  bytes.resize(400000);
  ExpectError("cut.laz", bytes, "truncated or damaged: the chunk table should be at byte");
  bytes = autzen;
  std::memset(&bytes[bytes.size() - 20], 0xAB, 20); // the chunk table's entries
  ExpectError("table.laz", bytes, "chunk table");
  bytes = autzen;
  bytes[104] = 0x84; // point format 4, with waveforms, and its record length
  bytes[105] = 57;
  ExpectError("waveform.laz", bytes, "LAZ point format 4 (with waveforms) is not supported");
  bytes = autzen;
  bytes[LASzipRecordAt(bytes)] = 7; // the compressor
  ExpectError("compressor.laz", bytes, "the LAZ compressor 7 is not supported");
  bytes = autzen;
  bytes[LASzipRecordAt(bytes) + 34 + 4] = 9; // point10's version
  ExpectError("version.laz", bytes, "the LAZ item point10 (type 6) version 9 is not supported");
  bytes = FileContentsOf(LAZPath("simple-laszip-compressor-version-1.2r0.laz"));
  bytes[LASzipRecordAt(bytes) + 34 + 12] = 0; // rgb12 version 1 made byte version 1
  ExpectError("byte-v1.laz", bytes, "byte (type 0) version 1");
  // A layered chunk whose first layer announces more bytes than the chunk holds.
  bytes = FileContentsOf(LAZPath("las_with_several_extra_byte_bloc.laz"));
  const std::size_t offset = bytes[96] | (bytes[97] << 8) | (bytes[98] << 16);
  std::memset(&bytes[offset + 8 + 41 + 4], 0xEE, 4);
  ExpectError("layer.laz", bytes, "layer 1 of 14");
}
/// The records of a COPC file's octree, which a LAZ written from it does not keep.
std::size_t COPCRecords(const pcbilateral::LASFileInfo& info)
{
  std::size_t count = 0;
  for (const auto* records : { &info.VLRs, &info.EVLRs })
  {
    for (const pcbilateral::LASRecord& record : *records)
    {
      count += record.UserId == "copc" ? 1 : 0;
    }
  }
  return count;
}

/// A file read into columns (as the VTK reader does) and written as LAZ: the written file
/// decompresses to the same point records, byte for byte, with the same header fields but the
/// point format's LASzip mark, the offset to the points and the count of VLRs (one more: the
/// LASzip record; a COPC file's octree records are not kept).
void RoundTrip(const std::string& path, const std::string& written)
{
  const Decoded original = ReadRecords(path);
  PCB_CHECK(original.Error.empty(), "%s", original.Error.c_str());
  const pcbilateral::LASFileInfo& info = original.Info;
  const std::size_t count = info.Header.NumberOfPoints;
  std::vector<double> positions(3 * count);
  std::vector<std::vector<std::uint8_t>> storage;
  std::vector<void*> columns;
  for (const pcbilateral::LASDimension& dimension : info.Dimensions)
  {
    storage.emplace_back(count * pcbilateral::LASColumnBytes(dimension));
    columns.push_back(storage.back().data());
  }
  pcbilateral::DecodeLASPoints(
    info, original.Records.data(), count, positions.data(), columns.data());
  const std::string error = pcbilateral::WriteLAZ(
    written, info, count, positions.data(), const_cast<const void* const*>(columns.data()));
  PCB_CHECK(error.empty(), "%s", error.c_str());
  const Decoded back = ReadRecords(written);
  PCB_CHECK(back.Error.empty() && !back.Info.LASzipRecord.empty(),
    "%s: %s",
    written.c_str(),
    back.Error.c_str());
  PCB_CHECK(
    back.Records == original.Records, "%s: the records of %s", written.c_str(), path.c_str());
  const pcbilateral::LASHeader& a = info.Header;
  const pcbilateral::LASHeader& b = back.Info.Header;
  PCB_CHECK(a.PointFormat == b.PointFormat && a.RecordLength == b.RecordLength &&
              a.NumberOfPoints == b.NumberOfPoints &&
              a.GeneratingSoftware == b.GeneratingSoftware && a.CreationYear == b.CreationYear &&
              std::memcmp(a.Scale, b.Scale, sizeof(a.Scale)) == 0 &&
              std::memcmp(a.Offset, b.Offset, sizeof(a.Offset)) == 0 &&
              back.Info.VLRs.size() + back.Info.EVLRs.size() + COPCRecords(info) ==
                info.VLRs.size() + info.EVLRs.size(),
    "%s: the header and VLRs of %s",
    written.c_str(),
    path.c_str());
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
      { "write-autzen", [] { RoundTrip(LAZPath("autzen_trim.laz"), "autzen_written.laz"); } },
      { "write-formats-6-to-8",
        []
        {
          RoundTrip(LASFolder + "/test1_4.las", "test1_4.laz");
          RoundTrip(LASFolder + "/autzen_trim_7.las", "autzen_trim_7.laz");
          RoundTrip(LAZPath("1.2-with-color.copc.laz"), "copc_written.laz");
          RoundTrip(LAZPath("las_with_several_extra_byte_bloc.laz"), "format8_written.laz");
        } },
      { "write-threads",
        []
        {
          // The same file whatever the number of threads compressing its chunks.
          const std::string path = LASFolder + "/autzen_trim_7.las";
#ifdef _OPENMP
          const int threads = omp_get_max_threads();
          omp_set_num_threads(1);
#endif
          RoundTrip(path, "one_thread.laz");
#ifdef _OPENMP
          omp_set_num_threads(threads > 2 ? threads : 3);
#endif
          RoundTrip(path, "threads.laz");
          PCB_CHECK(pcbilateral_testing::FileContents("one_thread.laz") ==
                      pcbilateral_testing::FileContents("threads.laz"),
            "one thread and several wrote different files");
        } },
      { "write-las-formats",
        []
        {
          for (const char* name : { "simple.las", "100-points.las", "extrabytes.las" })
          {
            RoundTrip(LASFolder + "/" + name, std::string(name) + ".laz");
          }
        } },
      { "parts-and-threads", PartsAndThreads },
      { "damaged-and-unsupported", DamagedAndUnsupported },
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
