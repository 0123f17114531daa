// libFuzzer target for the ASCII point reader: any bytes must give either a clear error or a
// consistent table, never a crash, a hang or a sanitizer report; and the same answer whether
// the text is parsed in one piece or in many (the parallel parser's pieces must join seamlessly).
#include "PointCloudText.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // The first byte chooses whether columns 4 to 6 are normals.
  const bool hasNormals = size > 0 && (data[0] & 1);
  pcbilateral::PointCloudTable table;
  const std::string error = pcbilateral::ParsePointCloudText(
    reinterpret_cast<const char*>(data), size, hasNormals, "fuzz", table);
  pcbilateral::PointCloudTable pieces;
  const std::size_t pieceBytes = 1 + (size > 1 ? data[1] % 16 : 0);
  const std::string piecesError = pcbilateral::ParsePointCloudText(
    reinterpret_cast<const char*>(data), size, hasNormals, "fuzz", pieces, pieceBytes);
  auto sameBits = [](const std::vector<double>& a, const std::vector<double>& b)
  {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
  };
  bool same = piecesError == error && pieces.NumberOfPoints == table.NumberOfPoints &&
              sameBits(pieces.Positions, table.Positions) &&
              sameBits(pieces.Normals, table.Normals) &&
              pieces.ExtraColumnNames == table.ExtraColumnNames &&
              pieces.ExtraColumns.size() == table.ExtraColumns.size();
  for (std::size_t c = 0; same && c < table.ExtraColumns.size(); ++c)
  {
    same = sameBits(pieces.ExtraColumns[c], table.ExtraColumns[c]);
  }
  if (!same)
  {
    std::abort(); // parsing in pieces changed the answer
  }
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
