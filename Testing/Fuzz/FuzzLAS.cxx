// libFuzzer target for the LAS parser: any bytes must give either a one-line error naming the
// source, or a header whose every announced record lies within the bytes, then decode without
// reading outside them (AddressSanitizer watches the decoding), and write back what was read.
#include "LASFormat.h"

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // A copy of exactly `size` bytes, so that a read past the end is caught.
  const std::vector<std::uint8_t> bytes(data, data + size);
  pcbilateral::LASFileInfo info;
  const std::string error = pcbilateral::ParseLASHeader(bytes.data(), size, "fuzz", info);
  if (!error.empty())
  {
    if (error.compare(0, 6, "fuzz: ") != 0 || error.find('\n') != std::string::npos)
    {
      std::abort(); // an error must be one line naming the source
    }
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
  const auto count = static_cast<std::size_t>(header.NumberOfPoints);
  std::vector<double> positions(3 * count);
  std::vector<std::vector<std::uint8_t>> storage;
  std::vector<void*> columns;
  for (const pcbilateral::LASDimension& dimension : info.Dimensions)
  {
    storage.emplace_back(count * pcbilateral::LASColumnBytes(dimension));
    columns.push_back(storage.back().data());
  }
  pcbilateral::DecodeLASPoints(
    info, bytes.data() + header.OffsetToPointData, count, positions.data(), columns.data());
  return 0;
}
