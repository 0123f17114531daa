// libFuzzer target for the LAZ decoder and encoder: any bytes must give either a one-line error
// naming the source, or point records that decode (DecodeLASPoints) without reading outside the
// bytes (AddressSanitizer watches), the same records for a part of the file as for the whole,
// and, for point formats 0 to 3, records that the LAZ writer writes and its reader reads back
// byte for byte. A damaged stream may decode to other records (arithmetic coding has no check
// sums) but never crashes, hangs or reads outside its chunk.
#include "FuzzScratchFile.h"
#include "LASHeader.h"
#include "LASReader.h"
#include "LASWriter.h"
#include "LAZReader.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
/// The records decoded into columns, as the VTK reader does.
struct Columns
{
  std::vector<double> Positions;
  std::vector<std::vector<std::uint8_t>> Storage;
  std::vector<void*> Pointers;

  Columns(const pcbilateral::LASFileInfo& info, const std::uint8_t* records)
    : Positions(3 * info.Header.NumberOfPoints)
  {
    const auto count = static_cast<std::size_t>(info.Header.NumberOfPoints);
    for (const pcbilateral::LASDimension& dimension : info.Dimensions)
    {
      this->Storage.emplace_back(count * pcbilateral::LASColumnBytes(dimension));
      this->Pointers.push_back(this->Storage.back().data());
    }
    pcbilateral::DecodeLASPoints(
      info, records, count, this->Positions.data(), this->Pointers.data());
  }
};

/// A part of the points decompresses to the same records as the whole.
void CheckPart(const std::vector<std::uint8_t>& bytes,
  const pcbilateral::LASFileInfo& info,
  const std::vector<std::uint8_t>& records)
{
  const std::uint64_t count = info.Header.NumberOfPoints;
  const std::size_t length = info.Header.RecordLength;
  const std::uint64_t first = count / 2;
  const std::uint64_t part = std::min<std::uint64_t>(count - first, 3);
  std::vector<std::uint8_t> some(part * length);
  const std::string error = pcbilateral::DecompressLAZPoints(
    bytes.data(), bytes.size(), info, "fuzz", first, part, some.data());
  if (!error.empty() || std::memcmp(some.data(), records.data() + first * length, some.size()))
  {
    std::abort(); // a part differs from the whole
  }
}

/// Written as LAZ and read back: the same records (formats 0 to 3; others are refused).
void CheckWrittenBack(const pcbilateral::LASFileInfo& info,
  const std::vector<std::uint8_t>& records)
{
  static const std::string path = FuzzScratchPath("FuzzLAZ", ".laz");
  const Columns columns(info, records.data());
  const std::vector<const void*> pointers(columns.Pointers.begin(), columns.Pointers.end());
  const std::string error = pcbilateral::WriteLAZ(path,
    info,
    static_cast<std::size_t>(info.Header.NumberOfPoints),
    columns.Positions.data(),
    pointers.data());
  if (RefusedWithoutFile(error, path))
  {
    return;
  }
  pcbilateral::LASFileBytes file;
  pcbilateral::LASFileInfo back;
  std::vector<std::uint8_t> decompressed;
  const std::uint8_t* again = nullptr;
  if (!file.Open(path).empty() ||
      !pcbilateral::ParseLASHeader(file.Data(), file.Size(), path, back, true).empty() ||
      !pcbilateral::UncompressedLASRecords(
        file.Data(), file.Size(), back, path, decompressed, again)
         .empty())
  {
    std::abort(); // the writer wrote a file its reader refuses
  }
  // The coordinates are written back from doubles: compared as LASWriter's fuzzer does would
  // need the scale checks; the other fields must come back byte for byte.
  const std::size_t length = info.Header.RecordLength;
  for (std::size_t i = 0; i < info.Header.NumberOfPoints; ++i)
  {
    if (std::memcmp(records.data() + i * length + 12, again + i * length + 12, length - 12) != 0)
    {
      std::abort(); // the written records differ
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
  std::string error = pcbilateral::ParseLASHeader(bytes.data(), size, "fuzz", info, true);
  if (!error.empty())
  {
    CheckOneLine(error, "fuzz");
    return 0;
  }
  if (info.LASzipRecord.empty())
  {
    return 0; // uncompressed: FuzzLAS's
  }
  std::vector<std::uint8_t> records;
  const std::uint8_t* decoded = nullptr;
  error = pcbilateral::UncompressedLASRecords(bytes.data(), size, info, "fuzz", records, decoded);
  if (!error.empty())
  {
    CheckOneLine(error, "fuzz");
    return 0;
  }
  const Columns columns(info, decoded);
  if (info.Header.NumberOfPoints > 0)
  {
    CheckPart(bytes, info, records);
  }
  CheckWrittenBack(info, records);
  return 0;
}
