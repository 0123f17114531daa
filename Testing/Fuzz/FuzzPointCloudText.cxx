// libFuzzer target for the ASCII point reader: any bytes must give either a clear error or a
// consistent table, never a crash, a hang or a sanitizer report.
#include "PointCloudText.h"

#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // The first byte chooses whether columns 4 to 6 are normals.
  const bool hasNormals = size > 0 && (data[0] & 1);
  pcbilateral::PointCloudTable table;
  const std::string error = pcbilateral::ParsePointCloudText(
    reinterpret_cast<const char*>(data), size, hasNormals, "fuzz", table);
  if (!error.empty())
  {
    if (error.compare(0, 5, "fuzz:") != 0 || error.find('\n') != std::string::npos)
    {
      std::abort(); // an error must be one line naming the source
    }
    return 0;
  }
  const std::size_t n = table.NumberOfPoints;
  bool consistent = table.Positions.size() == 3 * n &&
                    table.Normals.size() == (hasNormals ? 3 * n : 0) &&
                    table.ExtraColumns.size() == table.ExtraColumnNames.size();
  for (const auto& column : table.ExtraColumns)
  {
    consistent = consistent && column.size() == n;
  }
  if (!consistent)
  {
    std::abort();
  }
  return 0;
}
