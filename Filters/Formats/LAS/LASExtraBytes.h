// The extra bytes of the point records: the fields the extra-bytes VLR (record 4 of
// "LASF_Spec") describes, with their names, types, scales, offsets and no-data values.
// Private to the LAS codec.
#ifndef pcbilateral_LASExtraBytes_h
#define pcbilateral_LASExtraBytes_h

#include "LASDimension.h"
#include "LASRecord.h"

#include <cstddef>
#include <string>
#include <vector>

namespace pcbilateral
{
namespace las
{

/// The extra-bytes record among `records`, or null.
const LASRecord* FindExtraBytesRecord(const std::vector<LASRecord>& records);

/**
 * Appends to `dimensions` (the standard fields) the fields of the bytes from `standardLength`
 * to `recordLength` of each record, as the extra-bytes record of `records` describes them;
 * bytes it does not describe become one field of as many unsigned bytes. Returns an empty
 * string, or what is wrong (an unknown data type, descriptors beyond the record).
 */
std::string AddExtraBytesDimensions(std::size_t standardLength,
  std::size_t recordLength,
  const std::vector<LASRecord>& records,
  std::vector<LASDimension>& dimensions);

} // namespace las
} // namespace pcbilateral

#endif
