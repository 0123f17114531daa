// The layout of the point records of each LAS point format (0 to 10): where each standard
// field lies, then the extra bytes. Plain C++17, no VTK types.
#ifndef pcbilateral_LASPointFormat_h
#define pcbilateral_LASPointFormat_h

#include "LASDimension.h"
#include "LASRecord.h"

#include <cstddef>
#include <string>
#include <vector>

namespace pcbilateral
{

/// The size of a record of a point format without extra bytes (0 for formats beyond 10).
std::size_t LASStandardRecordLength(int pointFormat);

/**
 * The fields of a point format: the standard ones, then the extra bytes of a longer record,
 * named by the extra-bytes VLR (record 4 of "LASF_Spec") when `vlrs` has one; bytes it does
 * not describe become one "ExtraBytes" field of as many unsigned bytes. Returns an empty
 * string, or what is wrong (a record too short for its format, descriptors beyond the record).
 */
std::string LASDimensionsFor(int pointFormat,
  std::size_t recordLength,
  const std::vector<LASRecord>& vlrs,
  std::vector<LASDimension>& dimensions);

/// The records that describe a file's extra bytes, for LASDimensionsFor: its VLRs, unless only
/// its EVLRs hold an extra-bytes record (LAS 1.4 allows it there too).
const std::vector<LASRecord>& LASExtraBytesRecords(const std::vector<LASRecord>& vlrs,
  const std::vector<LASRecord>& evlrs);

} // namespace pcbilateral

#endif
