// The bytes of a part of a file, for the checks that look at a file before a reader does.
#ifndef pcbilateral_FileBytes_h
#define pcbilateral_FileBytes_h

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

namespace pcbilateral
{

/// Up to `count` bytes of a file from `offset`: fewer at its end, none when it cannot be read.
inline std::string ReadFileBytes(const std::string& path, std::uintmax_t offset, std::size_t count)
{
  std::ifstream file(path, std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  std::string bytes(count, '\0');
  file.read(&bytes[0], static_cast<std::streamsize>(count));
  bytes.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, file.gcount())));
  return bytes;
}

} // namespace pcbilateral

#endif
