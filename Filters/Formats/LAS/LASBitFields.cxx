#include "LASBitFields.h"

#include <algorithm>

namespace pcbilateral
{
namespace las
{

std::vector<BitFieldByte> GroupBitFields(const LASFileInfo& info, const void* const* columns)
{
  std::vector<BitFieldByte> bytes;
  for (std::size_t d = 0; d < info.Dimensions.size(); ++d)
  {
    const LASDimension& dimension = info.Dimensions[d];
    if (!columns[d] || dimension.BitCount == 0)
    {
      continue;
    }
    auto byte = std::find_if(bytes.begin(),
      bytes.end(),
      [&](const BitFieldByte& b) { return b.ByteOffset == dimension.ByteOffset; });
    if (byte == bytes.end())
    {
      bytes.push_back(BitFieldByte{ dimension.ByteOffset, {} });
      byte = bytes.end() - 1;
    }
    byte->Fields.push_back(
      BitField{ d, (1u << dimension.BitCount) - 1u, static_cast<unsigned>(dimension.BitShift) });
  }
  return bytes;
}

} // namespace las
} // namespace pcbilateral
