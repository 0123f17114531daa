// An input file mapped for reading, a range at a time: the streamed readers' (LAS, LAZ, PCD)
// view of their file. Plain C++17 over POSIX.
#ifndef pcbilateral_MappedInput_h
#define pcbilateral_MappedInput_h

#include <cstddef>
#include <cstdint>
#include <string>

namespace pcbilateral
{

/**
 * A file mapped, not populated: only the pages of the ranges read come in, and Release gives
 * them back, so that a streamed run holds a window of a file however large it is. An empty file
 * maps to no bytes (Data null, Size 0), which the format's header check then reports as the
 * run in memory does.
 */
class MappedInput
{
public:
  MappedInput() = default;
  ~MappedInput();
  MappedInput(const MappedInput&) = delete;
  MappedInput& operator=(const MappedInput&) = delete;

  /// Maps the file at `path`. An empty string, or why not: the system's reason when it cannot
  /// be opened ("No such file or directory"), or "cannot be mapped for reading (...)".
  std::string Open(const std::string& path);
  const std::uint8_t* Data() const { return this->Bytes; }
  std::size_t Size() const { return this->Length; }
  /// Gives the pages read so far back to the system (they are read again from the file when
  /// needed).
  void Release() const;

private:
  const std::uint8_t* Bytes = nullptr;
  std::size_t Length = 0;
};

} // namespace pcbilateral

#endif
