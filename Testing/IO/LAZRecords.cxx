// Writes the point records of a LAS or LAZ file, uncompressed, to a file, and prints how long
// reading and decompressing took (for the comparison with laz-perf, CheckWithLazPerf.py). With
// a third file name, also writes the points read (decoded into columns, as the VTK reader does)
// as a LAZ file there, and prints how long that took.
//   LAZRecords INPUT OUTPUT [WRITTEN.laz]
#include "LASReader.h"
#include "LASWriter.h"
#include "LAZReader.h"

#include <chrono>
#include <cstdio>
#include <vector>

namespace
{
/// Writes the points of the records as a LAZ file, through columns.
std::string WriteAsLAZ(const pcbilateral::LASFileInfo& info,
  const std::uint8_t* records,
  const char* path)
{
  const std::size_t count = info.Header.NumberOfPoints;
  std::vector<double> positions(3 * count);
  std::vector<std::vector<std::uint8_t>> storage;
  std::vector<void*> columns;
  for (const pcbilateral::LASDimension& dimension : info.Dimensions)
  {
    storage.emplace_back(count * pcbilateral::LASColumnBytes(dimension));
    columns.push_back(storage.back().data());
  }
  pcbilateral::DecodeLASPoints(info,
    records,
    count,
    positions.data(),
    const_cast<void* const*>(reinterpret_cast<void* const*>(columns.data())));
  const auto start = std::chrono::steady_clock::now();
  const std::string error =
    pcbilateral::WriteLAZ(path, info, count, positions.data(), columns.data());
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("written as LAZ in %.4f s (%.2f million points/s)\n", seconds, count / seconds / 1e6);
  return error;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc != 3 && argc != 4)
  {
    std::fprintf(stderr, "usage: %s INPUT OUTPUT [WRITTEN.laz]\n", argv[0]);
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  pcbilateral::LASFileBytes file;
  pcbilateral::LASFileInfo info;
  std::string error = file.Open(argv[1]);
  if (error.empty())
  {
    error = pcbilateral::ParseLASHeader(file.Data(), file.Size(), argv[1], info, true);
  }
  std::vector<std::uint8_t> decompressed;
  const std::uint8_t* records = nullptr;
  if (error.empty())
  {
    error = pcbilateral::UncompressedLASRecords(
      file.Data(), file.Size(), info, argv[1], decompressed, records);
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!error.empty())
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const std::size_t bytes = info.Header.NumberOfPoints * info.Header.RecordLength;
  std::FILE* out = std::fopen(argv[2], "wb");
  if (!out || std::fwrite(records, 1, bytes, out) != bytes || std::fclose(out) != 0)
  {
    std::fprintf(stderr, "%s: cannot be written\n", argv[2]);
    return 1;
  }
  if (argc == 4)
  {
    error = WriteAsLAZ(info, records, argv[3]);
    if (!error.empty())
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
  }
  std::printf("ours: %llu points of %u bytes in %.4f s (%.2f million points/s)\n",
    static_cast<unsigned long long>(info.Header.NumberOfPoints),
    info.Header.RecordLength,
    seconds,
    info.Header.NumberOfPoints / seconds / 1e6);
  return 0;
}
