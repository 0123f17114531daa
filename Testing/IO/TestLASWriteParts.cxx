// Writing one LAS or LAZ file in parts (LASWriteParts.h), as the processes of an MPI run do, here
// in one process: each part's records at its offset, the header from the merged summaries, a
// LAZ file's chunks per part and its chunk table written separately. A LAS file so written is,
// byte for byte, WriteLAS's; a LAZ file has WriteLAZ's records, in chunks that end where each
// part ends. The stream writers (LASStreamWriter, LAZStreamWriter: pcbilateral --memory-limit)
// appended in runs write the files written at once, byte for byte.
//   TestLASWriteParts CASE LAS_DATA_DIR
#include "CoreTesting.h"

#include "LASReader.h"
#include "LASWriteParts.h"
#include "LASWriter.h"
#include "LAZReader.h"
#include "LAZWriter.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace
{
std::string LASFolder;

/// A file's points as the writers take them: positions and one column per dimension.
struct Cloud
{
  pcbilateral::LASFileInfo Info;
  std::size_t Count = 0;
  std::vector<double> Positions;
  std::vector<std::vector<std::uint8_t>> Storage;

  /// The columns of the points from `first` on.
  std::vector<const void*> Columns(std::size_t first) const
  {
    std::vector<const void*> columns;
    for (std::size_t d = 0; d < this->Storage.size(); ++d)
    {
      columns.push_back(
        this->Storage[d].data() + first * pcbilateral::LASColumnBytes(this->Info.Dimensions[d]));
    }
    return columns;
  }
};

/// The records of a LAS or LAZ file, uncompressed; `info` its header.
std::vector<std::uint8_t> Records(const std::string& path, pcbilateral::LASFileInfo& info)
{
  pcbilateral::LASFileBytes file;
  std::string error = file.Open(path);
  error =
    error.empty() ? pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, info, true) : error;
  PCB_CHECK(error.empty(), "%s", error.c_str());
  const pcbilateral::LASHeader& h = info.Header;
  std::vector<std::uint8_t> records(h.NumberOfPoints * h.RecordLength);
  if (info.LASzipRecord.empty())
  {
    std::copy_n(file.Data() + h.OffsetToPointData, records.size(), records.begin());
    return records;
  }
  error = pcbilateral::DecompressLAZPoints(
    file.Data(), file.Size(), info, path, 0, h.NumberOfPoints, records.data());
  PCB_CHECK(error.empty(), "%s", error.c_str());
  return records;
}

Cloud Load(const std::string& name)
{
  Cloud cloud;
  const std::vector<std::uint8_t> records = Records(LASFolder + "/" + name, cloud.Info);
  cloud.Count = cloud.Info.Header.NumberOfPoints;
  cloud.Positions.resize(3 * cloud.Count);
  std::vector<void*> columns;
  for (const pcbilateral::LASDimension& dimension : cloud.Info.Dimensions)
  {
    cloud.Storage.emplace_back(cloud.Count * pcbilateral::LASColumnBytes(dimension));
    columns.push_back(cloud.Storage.back().data());
  }
  pcbilateral::DecodeLASPoints(
    cloud.Info, records.data(), cloud.Count, cloud.Positions.data(), columns.data());
  return cloud;
}

/// The parts' first points: three uneven parts, one of them empty, then the end.
std::vector<std::size_t> Splits(std::size_t count)
{
  return { 0, count / 7, count / 7, count - count / 3, count };
}

void Put(std::FILE* file, std::uint64_t offset, const std::vector<std::uint8_t>& bytes)
{
  PCB_CHECK(std::fseek(file, static_cast<long>(offset), SEEK_SET) == 0 &&
              std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size(),
    "a write failed");
}

/// Written in parts as LAS, the file is WriteLAS's, byte for byte.
void LASInParts(const std::string& name)
{
  const Cloud cloud = Load(name);
  const std::string whole = name + ".whole.las";
  const std::string parts = name + ".parts.las";
  const std::vector<const void*> all = cloud.Columns(0);
  std::string error =
    pcbilateral::WriteLAS(whole, cloud.Info, cloud.Count, cloud.Positions.data(), all.data());
  PCB_CHECK(error.empty(), "%s", error.c_str());

  const pcbilateral::LASPartsLayout layout(cloud.Info, cloud.Count, false);
  PCB_CHECK(layout.Problem().empty(), "%s", layout.Problem().c_str());
  std::FILE* file = std::fopen(parts.c_str(), "w+b");
  PCB_CHECK(file != nullptr, "%s cannot be written", parts.c_str());
  const std::vector<std::size_t> splits = Splits(cloud.Count);
  const std::uint64_t recordLength = cloud.Info.Header.RecordLength;
  pcbilateral::LASPartSummary summary;
  for (std::size_t p = splits.size() - 1; p-- > 0;) // parts in any order: the last first
  {
    pcbilateral::LASPartSummary part;
    const std::vector<const void*> columns = cloud.Columns(splits[p]);
    error = pcbilateral::WriteLASPart(file,
      layout.PointDataOffset() + splits[p] * recordLength,
      cloud.Info,
      splits[p + 1] - splits[p],
      cloud.Positions.data() + 3 * splits[p],
      columns.data(),
      part);
    PCB_CHECK(error.empty(), "part %zu: %s", p, error.c_str());
    pcbilateral::MergeLASPartSummary(summary, part);
  }
  Put(file, 0, layout.Head(summary, cloud.Count * recordLength));
  Put(file, layout.PointDataOffset() + cloud.Count * recordLength, layout.Tail());
  std::fclose(file);
  PCB_CHECK(pcbilateral_testing::FileContents(parts) == pcbilateral_testing::FileContents(whole),
    "%s: written in parts, not WriteLAS's file",
    name.c_str());
}

/// Written in parts as LAZ, the file has WriteLAZ's records, one chunk table of every part's
/// chunks, and the reader reads it.
void LAZInParts(const std::string& name)
{
  const Cloud cloud = Load(name);
  const std::string whole = name + ".whole.laz";
  const std::string parts = name + ".parts.laz";
  const std::vector<const void*> all = cloud.Columns(0);
  std::string error =
    pcbilateral::WriteLAZ(whole, cloud.Info, cloud.Count, cloud.Positions.data(), all.data());
  PCB_CHECK(error.empty(), "%s", error.c_str());

  const pcbilateral::LASPartsLayout layout(cloud.Info, cloud.Count, true);
  PCB_CHECK(
    layout.Problem().empty() && layout.Compression().ChunkSize == pcbilateral::VariableChunkSize,
    "%s",
    layout.Problem().c_str());
  const std::vector<std::size_t> splits = Splits(cloud.Count);
  pcbilateral::LASPartSummary summary;
  std::vector<std::uint8_t> chunks;
  std::vector<std::uint64_t> points, sizes;
  for (std::size_t p = 0; p + 1 < splits.size(); ++p)
  {
    pcbilateral::LAZPart part;
    pcbilateral::LASPartSummary partSummary;
    const std::vector<const void*> columns = cloud.Columns(splits[p]);
    error = pcbilateral::CompressLAZPart(cloud.Info,
      layout.Compression(),
      splits[p + 1] - splits[p],
      cloud.Positions.data() + 3 * splits[p],
      columns.data(),
      part,
      partSummary);
    PCB_CHECK(error.empty(), "part %zu: %s", p, error.c_str());
    pcbilateral::MergeLASPartSummary(summary, partSummary);
    chunks.insert(chunks.end(), part.Bytes.begin(), part.Bytes.end());
    points.insert(points.end(), part.ChunkPoints.begin(), part.ChunkPoints.end());
    sizes.insert(sizes.end(), part.ChunkBytes.begin(), part.ChunkBytes.end());
  }
  const std::vector<std::uint8_t> table = pcbilateral::EncodeLAZChunkTable(points, sizes, true);
  const std::uint64_t tableOffset = layout.PointDataOffset() + 8 + chunks.size();
  std::vector<std::uint8_t> file = layout.Head(summary, 8 + chunks.size() + table.size());
  for (int b = 0; b < 8; ++b)
  {
    file.push_back(static_cast<std::uint8_t>(tableOffset >> (8 * b)));
  }
  file.insert(file.end(), chunks.begin(), chunks.end());
  file.insert(file.end(), table.begin(), table.end());
  const std::vector<std::uint8_t> tail = layout.Tail();
  file.insert(file.end(), tail.begin(), tail.end());
  pcbilateral_testing::WriteFileContents(parts, std::string(file.begin(), file.end()));

  pcbilateral::LASFileInfo wholeInfo, partsInfo;
  PCB_CHECK(Records(parts, partsInfo) == Records(whole, wholeInfo),
    "%s: written in parts, not WriteLAZ's records",
    name.c_str());
  const pcbilateral::LASHeader& a = wholeInfo.Header;
  const pcbilateral::LASHeader& b = partsInfo.Header;
  PCB_CHECK(a.NumberOfPoints == b.NumberOfPoints && std::equal(a.Bounds, a.Bounds + 6, b.Bounds) &&
              std::equal(a.PointsByReturn, a.PointsByReturn + 15, b.PointsByReturn),
    "%s: the header's totals differ from WriteLAZ's",
    name.c_str());
  PCB_CHECK(points.size() > 3, "%s: %zu chunks, one part's at least", name.c_str(), points.size());
}

/// Appended in uneven runs (a point alone, runs that cut the chunks of 50,000 points, one that
/// ends on a chunk's boundary, an empty one), the stream writers write WriteLAS's and WriteLAZ's
/// files, byte for byte.
template<typename Writer>
void WrittenInRuns(const std::string& name, const char* extension)
{
  const Cloud cloud = Load(name);
  const bool compressed = std::string(extension) == ".laz";
  const std::string whole = name + ".whole" + extension;
  const std::string runs = name + ".runs" + extension;
  const std::vector<const void*> all = cloud.Columns(0);
  std::string error = (compressed ? pcbilateral::WriteLAZ : pcbilateral::WriteLAS)(
    whole, cloud.Info, cloud.Count, cloud.Positions.data(), all.data());
  PCB_CHECK(error.empty(), "%s", error.c_str());
  Writer writer;
  error = writer.Open(runs, cloud.Info, cloud.Count);
  const std::size_t runLengths[] = { 1, 0, 49999, 37000, 63000, 100000 };
  std::size_t first = 0;
  for (std::size_t r = 0; first < cloud.Count && error.empty(); ++r)
  {
    const std::size_t length = r < 6 ? runLengths[r] : 41234;
    const std::size_t count = std::min(length, cloud.Count - first);
    const std::vector<const void*> columns = cloud.Columns(first);
    error = writer.Append(count, cloud.Positions.data() + 3 * first, columns.data());
    first += count;
  }
  error = error.empty() ? writer.Close() : error;
  PCB_CHECK(error.empty(), "%s: %s", runs.c_str(), error.c_str());
  PCB_CHECK(pcbilateral_testing::FileContents(runs) == pcbilateral_testing::FileContents(whole),
    "%s: written in runs, not the file written at once",
    runs.c_str());
}

/// A point that does not fit the records makes its part fail, and the summary says so.
void OutOfRange()
{
  Cloud cloud = Load("simple.las");
  cloud.Positions[3 * 700] = std::numeric_limits<double>::quiet_NaN();
  std::FILE* file = std::fopen("out-of-range.las", "w+b");
  pcbilateral::LASPartSummary part;
  const std::vector<const void*> columns = cloud.Columns(600);
  const std::string error = pcbilateral::WriteLASPart(
    file, 227, cloud.Info, 200, cloud.Positions.data() + 3 * 600, columns.data(), part);
  std::fclose(file);
  PCB_CHECK(part.OutOfRange && error.find("do not fit") != std::string::npos, "%s", error.c_str());
  pcbilateral::LAZPart compressed;
  const pcbilateral::LASPartsLayout layout(cloud.Info, cloud.Count, true);
  const std::string lazError = pcbilateral::CompressLAZPart(cloud.Info,
    layout.Compression(),
    200,
    cloud.Positions.data() + 3 * 600,
    columns.data(),
    compressed,
    part);
  PCB_CHECK(part.OutOfRange && !lazError.empty(), "LAZ: %s", lazError.c_str());
}
} // namespace

int main(int argc, char* argv[])
{
  LASFolder = argc > 2 ? argv[2] : ".";
  return RunNamedCase(argc,
    argv,
    {
      { "las",
        []
        {
          for (const char* name : { "autzen_trim.las",
                 "autzen_trim_7.las",
                 "test1_4.las",
                 "extrabytes.las",
                 "no-points.las" })
          {
            LASInParts(name);
          }
        } },
      { "laz",
        []
        {
          LAZInParts("autzen_trim.las");
          LAZInParts("autzen_trim_7.las");
        } },
      { "out-of-range", OutOfRange },
      { "stream",
        []
        {
          for (const char* name : { "autzen_trim.las", "autzen_trim_7.las", "extrabytes.las" })
          {
            WrittenInRuns<pcbilateral::LASStreamWriter>(name, ".las");
            WrittenInRuns<pcbilateral::LAZStreamWriter>(name, ".laz");
          }
        } },
    });
}
