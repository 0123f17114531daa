// libFuzzer target for the ASCII point reader and writer: any bytes must give either a clear
// error or a consistent table, never a crash, a hang or a sanitizer report; the same answer
// whether the text is parsed in one piece or in many (the parallel parser's pieces must join
// seamlessly); and a table of points written back in its layout must read back as the same
// table, layout included (header line or not, the header's names, the delimiter).
#include "CoreTesting.h"
#include "FuzzScratchFile.h"
#include "PointCloudText.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
using pcbilateral_testing::SameBits;

bool SameTables(const pcbilateral::PointCloudTable& a, const pcbilateral::PointCloudTable& b)
{
  bool same = a.NumberOfPoints == b.NumberOfPoints && SameBits(a.Positions, b.Positions) &&
              SameBits(a.Normals, b.Normals) && a.ExtraColumnNames == b.ExtraColumnNames &&
              a.ExtraColumns.size() == b.ExtraColumns.size() &&
              a.Layout.Header == b.Layout.Header &&
              a.Layout.LeadingColumnNames == b.Layout.LeadingColumnNames &&
              a.Layout.Delimiter == b.Layout.Delimiter;
  for (std::size_t c = 0; same && c < a.ExtraColumns.size(); ++c)
  {
    same = SameBits(a.ExtraColumns[c], b.ExtraColumns[c]);
  }
  return same;
}

bool IsConsistent(const pcbilateral::PointCloudTable& table, bool hasNormals)
{
  const std::size_t n = table.NumberOfPoints;
  bool consistent = table.Positions.size() == 3 * n &&
                    table.Normals.size() == (hasNormals ? 3 * n : 0) &&
                    table.ExtraColumns.size() == table.ExtraColumnNames.size();
  for (const auto& column : table.ExtraColumns)
  {
    consistent = consistent && column.size() == n;
  }
  return consistent;
}

/// Whether the table, written to a file and read back, is the same table.
bool WritesBack(const pcbilateral::PointCloudTable& table, bool hasNormals)
{
  static const std::string path = FuzzScratchPath("FuzzPointCloudText", ".xyz");
  pcbilateral::PointCloudTable back;
  const bool same = pcbilateral::WritePointCloudText(path, table).empty() &&
                    pcbilateral::ReadPointCloudText(path, hasNormals, back).empty() &&
                    SameTables(table, back);
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  return same;
}
} // namespace

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
  if (piecesError != error || !SameTables(pieces, table))
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
  if (!IsConsistent(table, hasNormals))
  {
    std::abort();
  }
  if (table.NumberOfPoints > 0 && !WritesBack(table, hasNormals))
  {
    std::abort(); // the writer did not keep the table or its layout
  }
  return 0;
}
