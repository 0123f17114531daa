// The coordinate system a LAS file's records hold (LASCoordinateSystem.h): the first OGC WKT
// record among the VLRs, then the EVLRs, up to its first NUL; none for GeoTIFF keys only.
#include "CoreTesting.h"

#include "LASCoordinateSystem.h"

#include <string>

namespace
{
using pcbilateral::LASFileInfo;
using pcbilateral::LASRecord;

LASRecord Record(const std::string& userId, int recordId, const std::string& bytes)
{
  LASRecord record;
  record.UserId = userId;
  record.RecordId = static_cast<decltype(record.RecordId)>(recordId);
  record.Data.assign(bytes.begin(), bytes.end());
  return record;
}

void FindsTheWKT()
{
  const std::string wkt = "PROJCS[\"NAD83 / Oregon GIC Lambert (ft)\"]";
  LASFileInfo info;
  info.VLRs.push_back(Record("LASF_Projection", 34735, std::string(8, '\1'))); // GeoTIFF keys
  info.VLRs.push_back(Record("LASF_Spec", 2112, "not a projection"));
  info.EVLRs.push_back(Record("LASF_Projection", 2112, wkt + std::string(3, '\0') + "tail"));
  std::string found;
  PCB_CHECK(pcbilateral::FindLASCoordinateSystemWKT(info, found) && found == wkt,
    "the EVLR's text: got '%s'",
    found.c_str());
  info.VLRs.push_back(Record("LASF_Projection", 2112, "GEOGCS[\"first\"]"));
  PCB_CHECK(pcbilateral::FindLASCoordinateSystemWKT(info, found) && found == "GEOGCS[\"first\"]",
    "a VLR comes before the EVLRs: got '%s'",
    found.c_str());
}

void NoWKT()
{
  LASFileInfo info;
  std::string found = "left over";
  PCB_CHECK(!pcbilateral::FindLASCoordinateSystemWKT(info, found) && found.empty(),
    "no records: found '%s'",
    found.c_str());
  info.VLRs.push_back(Record("LASF_Projection", 34735, std::string(8, '\1')));
  PCB_CHECK(!pcbilateral::FindLASCoordinateSystemWKT(info, found), "GeoTIFF keys are no WKT");
  info.VLRs.push_back(Record("LASF_Projection", 2112, std::string(4, '\0')));
  PCB_CHECK(pcbilateral::FindLASCoordinateSystemWKT(info, found) && found.empty(),
    "an empty WKT record is a WKT record: found '%s'",
    found.c_str());
}
} // namespace

int main(int argc, char* argv[])
{
  return RunNamedCase(argc, argv, { { "wkt", FindsTheWKT }, { "no-wkt", NoWKT } });
}
