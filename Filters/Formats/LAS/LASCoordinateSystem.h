// The coordinate reference system of a LAS file, as its records hold it. The records themselves
// are kept and written back unchanged; this reads them for people. Plain C++17.
#ifndef pcbilateral_LASCoordinateSystem_h
#define pcbilateral_LASCoordinateSystem_h

#include "LASHeader.h"

#include <string>

namespace pcbilateral
{

/// Whether the file holds its coordinate system as well-known text (an OGC WKT record,
/// LASF_Projection 2112; not a file with GeoTIFF keys only, or with no coordinate system), and
/// that text: the first such record among the VLRs, then the EVLRs, up to its first NUL.
bool FindLASCoordinateSystemWKT(const LASFileInfo& info, std::string& wkt);

} // namespace pcbilateral

#endif
