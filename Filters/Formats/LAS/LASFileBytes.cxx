#include "LASReader.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>
#define PCB_LAS_MMAP 1
#endif

namespace pcbilateral
{

namespace
{
/// The file's `length` bytes mapped for reading, or null where that is not possible.
const std::uint8_t* MapReadOnly(const std::string& path, std::size_t length)
{
#ifdef PCB_LAS_MMAP
  // Mapped: no copy. The pages are mapped all at once where the system can (Linux's
  // MAP_POPULATE): a fault per 4 KB page as the decoding touches them made reading take twice
  // as long as a plain read of the bytes (pcb_benchmark --las); with it, about as long.
#ifdef MAP_POPULATE
  constexpr int PopulateFlag = MAP_POPULATE;
#else
  constexpr int PopulateFlag = 0;
#endif
  const int descriptor = ::open(path.c_str(), O_RDONLY);
  if (descriptor >= 0)
  {
    void* mapped = mmap(nullptr, length, PROT_READ, MAP_PRIVATE | PopulateFlag, descriptor, 0);
    ::close(descriptor);
    if (mapped != MAP_FAILED)
    {
      madvise(mapped, length, MADV_WILLNEED);
      return static_cast<const std::uint8_t*>(mapped);
    }
  }
#else
  (void)path;
  (void)length;
#endif
  return nullptr;
}
} // namespace

LASFileBytes::~LASFileBytes()
{
#ifdef PCB_LAS_MMAP
  if (this->Mapped)
  {
    munmap(const_cast<std::uint8_t*>(this->Bytes), this->Length);
  }
#endif
}

std::string LASFileBytes::Open(const std::string& path)
{
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
  {
    return path + ": " + std::strerror(ENOENT);
  }
  if (std::filesystem::is_directory(status))
  {
    return path + ": is a directory, not a point file";
  }
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error)
  {
    return path + ": " + error.message();
  }
  this->Length = static_cast<std::size_t>(size);
  static const std::uint8_t empty = 0;
  this->Bytes = &empty;
  if (this->Length == 0)
  {
    return std::string();
  }
  if (const std::uint8_t* mapped = MapReadOnly(path, this->Length))
  {
    this->Bytes = mapped;
    this->Mapped = true;
    return std::string();
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
  {
    return path + ": cannot be opened for reading (" + std::strerror(errno) + ")";
  }
  this->Buffer.reset(new std::uint8_t[this->Length]);
  const std::size_t read = std::fread(this->Buffer.get(), 1, this->Length, file);
  std::fclose(file);
  if (read != this->Length)
  {
    return path + ": read error";
  }
  this->Bytes = this->Buffer.get();
  return std::string();
}

} // namespace pcbilateral
