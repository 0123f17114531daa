// Writes the point records of a LAS or LAZ file, uncompressed, to a file, and prints how long
// reading and decompressing took (for the comparison with laz-perf, CheckWithLazPerf.py).
//   LAZRecords INPUT OUTPUT
#include "LASReader.h"
#include "LAZReader.h"

#include <chrono>
#include <cstdio>
#include <vector>

int main(int argc, char* argv[])
{
  if (argc != 3)
  {
    std::fprintf(stderr, "usage: %s INPUT OUTPUT\n", argv[0]);
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
  std::printf("ours: %llu points of %u bytes in %.4f s (%.2f million points/s)\n",
    static_cast<unsigned long long>(info.Header.NumberOfPoints),
    info.Header.RecordLength,
    seconds,
    info.Header.NumberOfPoints / seconds / 1e6);
  return 0;
}
