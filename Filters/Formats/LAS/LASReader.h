// Reading the point records of an uncompressed LAS file: the file's bytes, and the records
// decoded into columns. Plain C++17, no VTK types. ParseLASHeader (LASHeader.h) checks the
// header first.
#ifndef pcbilateral_LASReader_h
#define pcbilateral_LASReader_h

#include "LASHeader.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace pcbilateral
{

/**
 * Decodes `count` point records from `records` (the first byte of the point data):
 * coordinates as doubles into `positions` (x y z interleaved), and each of
 * `info.Dimensions` into `columns[d]` (Components values of the dimension's ColumnType per
 * point; a null column is skipped). Parallel (OpenMP); each thread first touches the part of
 * the outputs it writes, and the outputs are expected to be fresh memory (large ones are
 * advised to the kernel as huge pages). Reports progress and stops when asked (ProgressPoint);
 * returns false when stopped (the outputs are then partly written).
 */
bool DecodeLASPoints(const LASFileInfo& info,
  const std::uint8_t* records,
  std::size_t count,
  double* positions,
  void* const* columns);

/// A file's bytes, memory-mapped where the system allows it, else read in one block.
class LASFileBytes
{
public:
  LASFileBytes() = default;
  ~LASFileBytes();
  LASFileBytes(const LASFileBytes&) = delete;
  LASFileBytes& operator=(const LASFileBytes&) = delete;
  /// Returns an empty string, or a one-line message naming the file.
  std::string Open(const std::string& path);
  const std::uint8_t* Data() const { return this->Bytes; }
  std::size_t Size() const { return this->Length; }

private:
  const std::uint8_t* Bytes = nullptr;
  std::size_t Length = 0;
  bool Mapped = false;
  std::unique_ptr<std::uint8_t[]> Buffer;
};

} // namespace pcbilateral

#endif
