// The two ways of writing the encoded point records into a LAS file: straight into a memory
// mapping of the file, or in chunks written with fwrite while the next ones are encoded.
// Private to the LAS codec.
#ifndef pcbilateral_LASWritePoints_h
#define pcbilateral_LASWritePoints_h

#include "LASPointEncoder.h"

#include <cstdint>
#include <cstdio>
#include <vector>

namespace pcbilateral
{
namespace las
{

/**
 * Writes the records in chunks of a few blocks with fwrite, by one thread started for the
 * whole file, while the next chunks are encoded (three chunks in turn). Stops at the first
 * chunk with a point out of range (its summary says so; the chunk is not written). Returns
 * whether every write succeeded (if not, errno says why).
 */
bool WritePointsInChunks(std::FILE* file,
  const BlockEncoder& encoder,
  std::vector<BlockSummary>& summaries);

enum class MappedWrite
{
  Written,
  Failed,   // errno says why
  NotMapped // not possible here: write the records another way
};

/**
 * Writes the records straight into a memory mapping of the file, every thread encoding its
 * blocks there: no copy of the records into the page cache by fwrite, and no thread left only
 * writing. The file (opened empty, its header and VLRs written) is first extended over the
 * records with fallocate, which reserves their blocks: a full disk is an error now, rather than
 * a SIGBUS when a page of the mapping is stored into later, and the new range reads as zeros,
 * as the encoder needs (it leaves the fields without a column alone). In tmpfs, on a file system
 * without fallocate, where the file cannot be mapped, or with PCB_LAS_WRITE_MAPPED=0 in the
 * environment, the records are not written and NotMapped is returned (the file may have been
 * extended over them by then). Leaves the file's position after the records.
 */
MappedWrite WritePointsMapped(std::FILE* file,
  std::uint64_t offset,
  const BlockEncoder& encoder,
  std::vector<BlockSummary>& summaries);

} // namespace las
} // namespace pcbilateral

#endif
