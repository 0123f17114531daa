#include "LASCoordinateSystem.h"

#include <algorithm>

namespace pcbilateral
{

bool FindLASCoordinateSystemWKT(const LASFileInfo& info, std::string& wkt)
{
  for (const auto* records : { &info.VLRs, &info.EVLRs })
  {
    for (const LASRecord& record : *records)
    {
      if (record.UserId == "LASF_Projection" && record.RecordId == 2112)
      {
        const auto end = std::find(record.Data.begin(), record.Data.end(), std::uint8_t{ 0 });
        wkt.assign(record.Data.begin(), end);
        return true;
      }
    }
  }
  wkt.clear();
  return false;
}

} // namespace pcbilateral
