#include "MappedInput.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pcbilateral
{

MappedInput::~MappedInput()
{
  if (this->Bytes != nullptr)
  {
    ::munmap(const_cast<std::uint8_t*>(this->Bytes), this->Length);
  }
}

std::string MappedInput::Open(const std::string& path)
{
  const int descriptor = ::open(path.c_str(), O_RDONLY);
  struct stat status;
  if (descriptor < 0 || ::fstat(descriptor, &status) != 0)
  {
    const std::string problem = std::strerror(errno);
    if (descriptor >= 0)
    {
      ::close(descriptor);
    }
    return problem;
  }
  const auto size = static_cast<std::size_t>(status.st_size);
  void* mapped = size > 0 ? ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, descriptor, 0) : nullptr;
  const int mapError = errno;
  ::close(descriptor);
  if (mapped == MAP_FAILED)
  {
    return std::string("cannot be mapped for reading (") + std::strerror(mapError) + ")";
  }
  this->Bytes = static_cast<const std::uint8_t*>(mapped);
  this->Length = mapped != nullptr ? size : 0;
  return std::string();
}

void MappedInput::Release() const
{
  if (this->Bytes != nullptr)
  {
    ::madvise(const_cast<std::uint8_t*>(this->Bytes), this->Length, MADV_DONTNEED);
  }
}

} // namespace pcbilateral
